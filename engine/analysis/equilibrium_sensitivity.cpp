#include "analysis/equilibrium_sensitivity.hpp"

#include <Eigen/Geometry>

namespace ashlar {

namespace {

// A body's multipliers as (force, moment) 3-vectors in x, y, z order, with
// zeros for the rows a planar problem leaves out.
struct BodyMultipliers {
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
};

BodyMultipliers multipliers_of(const EquilibriumProblem& problem, const Eigen::VectorXd& y,
                               int row, const std::array<int, 6>& rows) {
  BodyMultipliers m;
  if (row < 0) return m;
  Eigen::Matrix<double, 6, 1> full = Eigen::Matrix<double, 6, 1>::Zero();
  for (int r = 0; r < problem.block_rows; ++r) full(rows[r]) = y(row + r);
  m.force = full.head<3>();
  m.moment = full.tail<3>();
  return m;
}

}  // namespace

EquilibriumSensitivity equilibrium_sensitivity(const Structure& structure,
                                               const EquilibriumProblem& problem,
                                               const InteriorPointSolution& optimum) {
  const Eigen::VectorXd& x = optimum.x;
  const Eigen::VectorXd& y = optimum.y;
  const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces();
  const std::vector<Interface>& interfaces = *interfaces_list;
  const std::vector<Cable>& cables = structure.cables();
  const double wu = problem.weight_unit, lu = problem.length_unit;
  const int n = structure.size();
  EquilibriumSensitivity out;
  out.vertex_position.assign(problem.contact_vertex_count, Vec3::Zero());
  out.vertex_frame.assign(problem.contact_vertex_count, Mat3::Zero());
  out.block_centroid.assign(n, Vec3::Zero());
  out.block_weight.assign(n, 0.0);
  out.cable_from.assign(cables.size(), Vec3::Zero());
  out.cable_to.assign(cables.size(), Vec3::Zero());
  std::vector<BodyMultipliers> multipliers(n);
  for (int i = 0; i < n; ++i) multipliers[i] = multipliers_of(problem, y, problem.row_of_block[i], rows);

  // -y^T A x: each vertex's force F acts on b at its position, -F on a.
  double d_length_unit = 0.0;
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    const ForceGroup& v = problem.groups[k];
    const Interface& contact = interfaces[v.source];
    const Eigen::Vector4d f = x.segment<4>(4 * k);
    const Vec3 force = (f(0) - f(1)) * contact.normal + f(2) * contact.u + f(3) * contact.v;
    Vec3 d_force = Vec3::Zero();  // d(y^T A x)/dF
    const struct { int block, row; double sign; } sides[2] = {{v.block_b, v.row_b, 1.0},
                                                              {v.block_a, v.row_a, -1.0}};
    for (const auto& side : sides) {
      if (side.row < 0) continue;
      const BodyMultipliers& m = multipliers[side.block];
      const Vec3 arm = (problem.vertex_position(v) - structure.block(side.block).centroid()) / lu;
      // y_F . F + y_M . (arm x F), with arm x F's dependence on position,
      // centroid and the unit of length.
      const Vec3 lever = force.cross(m.moment) / lu;
      out.vertex_position[k] -= side.sign * lever;
      out.block_centroid[side.block] += side.sign * lever;
      d_length_unit += side.sign * m.moment.dot(arm.cross(force)) / lu;
      d_force += side.sign * (m.force + m.moment.cross(arm));
    }
    out.vertex_frame[k].col(0) = -(f(0) - f(1)) * d_force;
    out.vertex_frame[k].col(1) = -f(2) * d_force;
    out.vertex_frame[k].col(2) = -f(3) * d_force;
  }

  // Cables: -y^T A x through the pull's direction and arms; z^T dl through
  // the tension bound (scaled by wu); +y^T b through their own weight.
  double d_weight_unit_bounds = 0.0;
  const std::vector<int> first_row = problem.inequality_starts();
  for (size_t k = problem.contact_vertex_count; k < problem.groups.size(); ++k) {
    const ForceGroup& g = problem.groups[k];
    if (g.kind != GroupKind::cable && g.kind != GroupKind::bounded_cable) continue;
    const Cable& cable = cables[g.source];
    const Vec3 span = cable.to.point - cable.from.point;
    const double length = span.norm();
    const Vec3 along = span / length;
    const double pull = x(4 * k) - x(4 * k + 1);
    const struct { int block, row; const Vec3& point; double sign; Vec3& gradient; } ends[2] = {
        {g.block_a, g.row_a, cable.from.point, 1.0, out.cable_from[g.source]},
        {g.block_b, g.row_b, cable.to.point, -1.0, out.cable_to[g.source]}};
    Vec3 d_along = Vec3::Zero();  // d(y^T A x)/d(along)
    // d(y^T b)/d(cable weight): half of it hangs at each end.
    double weight_multiplier = 0.0;
    for (const auto& end : ends) {
      if (end.row < 0) continue;
      const BodyMultipliers m = multipliers_of(problem, y, end.row, rows);
      const Vec3 force = end.sign * pull * along;
      d_along += end.sign * pull * m.force;
      weight_multiplier += 0.5 * m.force.z() / wu;
      if (end.block < 0) continue;  // junctions balance forces only
      const Vec3 arm = (end.point - structure.block(end.block).centroid()) / lu;
      weight_multiplier += 0.5 * m.moment.dot(arm.cross(Vec3::UnitZ())) / wu;
      d_along += end.sign * pull * m.moment.cross(arm);
      const Vec3 lever = force.cross(m.moment) / lu;
      end.gradient -= lever;
      out.block_centroid[end.block] += lever;
      d_length_unit += m.moment.dot(arm.cross(force)) / lu;
      // y^T b: half the weight at this end, -arm x (0, 0, -w/2) / wu.
      const double half_weight = 0.5 * cable.mass_per_length * length * kGravity;
      const Vec3 up_lever = Vec3::UnitZ().cross(m.moment) * half_weight / (wu * lu);
      end.gradient += up_lever;
      out.block_centroid[end.block] -= up_lever;
      d_length_unit -= m.moment.dot(arm.cross(Vec3::UnitZ())) * half_weight / (wu * lu);
    }
    // d(along)/d(to) = (I - along along^T) / length = -d(along)/d(from).
    const Vec3 d_to = -(d_along - along * along.dot(d_along)) / length;
    out.cable_to[g.source] += d_to;
    out.cable_from[g.source] -= d_to;
    // The weight's size: d(weight)/d(to) = rho g along.
    const Vec3 d_weight_d_to = cable.mass_per_length * kGravity * along;
    out.cable_to[g.source] += weight_multiplier * d_weight_d_to;
    out.cable_from[g.source] -= weight_multiplier * d_weight_d_to;
    if (g.kind == GroupKind::bounded_cable) {
      const GroupRules& rules = problem.rules_of(g);
      // l = -max_tension / wu, so dl/dwu = max_tension / wu^2 = g.bound / wu.
      d_weight_unit_bounds +=
          optimum.z.segment(first_row[k], rules.rows.rows()).dot(rules.bound_coefficients) * g.bound / wu;
    }
  }

  // +y^T b: weights and point loads, in units of wu and lu.
  for (int i = 0; i < n; ++i) {
    if (problem.row_of_block[i] >= 0) out.block_weight[i] = multipliers[i].force.z() / wu;
  }
  for (const PointLoad& load : structure.loads()) {
    if (problem.row_of_block[load.block] < 0) continue;
    const BodyMultipliers& m = multipliers[load.block];
    const Vec3 arm = (load.at - structure.block(load.block).centroid()) / lu;
    // The moment row holds -arm x F / wu.
    out.block_centroid[load.block] += load.force.cross(m.moment) / (lu * wu);
    d_length_unit += m.moment.dot(arm.cross(load.force)) / (wu * lu);
  }
  out.weight_unit = -y.dot(problem.rhs) / wu + d_weight_unit_bounds;
  out.length_unit = d_length_unit;
  return out;
}

}  // namespace ashlar
