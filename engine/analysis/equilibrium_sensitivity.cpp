#include "analysis/equilibrium_sensitivity.hpp"

#include <Eigen/Geometry>

namespace ashlar {

namespace {

// A block's multipliers as (force, moment) 3-vectors in x, y, z order, with
// zeros for the rows a planar problem leaves out.
struct BlockMultipliers {
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();
};

BlockMultipliers multipliers_of(const EquilibriumProblem& problem, const Eigen::VectorXd& y,
                                int row, const std::array<int, 6>& rows) {
  BlockMultipliers m;
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
                                               const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
  const std::vector<Interface>& interfaces = structure.interfaces();
  const double wu = problem.weight_unit, lu = problem.length_unit;
  const int n = structure.size();
  EquilibriumSensitivity out;
  out.vertex_position.assign(problem.vertices.size(), Vec3::Zero());
  out.vertex_frame.assign(problem.vertices.size(), Mat3::Zero());
  out.block_centroid.assign(n, Vec3::Zero());
  out.block_weight.assign(n, 0.0);
  std::vector<BlockMultipliers> multipliers(n);
  for (int i = 0; i < n; ++i) multipliers[i] = multipliers_of(problem, y, problem.row_of_block[i], rows);

  // -y^T A x: each vertex's force F acts on b at its position, -F on a.
  double d_length_unit = 0.0;
  for (size_t k = 0; k < problem.vertices.size(); ++k) {
    const ContactVertex& v = problem.vertices[k];
    const Interface& contact = interfaces[v.interface_index];
    const Eigen::Vector4d f = x.segment<4>(4 * k);
    const Vec3 force = (f(0) - f(1)) * contact.normal + f(2) * contact.u + f(3) * contact.v;
    Vec3 d_force = Vec3::Zero();  // d(y^T A x)/dF
    const struct { int block, row; double sign; } sides[2] = {{v.block_b, v.row_b, 1.0},
                                                              {v.block_a, v.row_a, -1.0}};
    for (const auto& side : sides) {
      if (side.row < 0) continue;
      const BlockMultipliers& m = multipliers[side.block];
      const Vec3 arm = (v.position - structure.block(side.block).centroid()) / lu;
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

  // +y^T b: weights and point loads, in units of wu and lu.
  double y_dot_rhs = y.dot(problem.rhs);
  for (int i = 0; i < n; ++i) {
    if (problem.row_of_block[i] >= 0) out.block_weight[i] = multipliers[i].force.z() / wu;
  }
  for (const PointLoad& load : structure.loads()) {
    if (problem.row_of_block[load.block] < 0) continue;
    const BlockMultipliers& m = multipliers[load.block];
    const Vec3 arm = (load.at - structure.block(load.block).centroid()) / lu;
    // The moment row holds -arm x F / wu.
    out.block_centroid[load.block] += load.force.cross(m.moment) / (lu * wu);
    d_length_unit += m.moment.dot(arm.cross(load.force)) / (wu * lu);
  }
  out.weight_unit = -y_dot_rhs / wu;
  out.length_unit = d_length_unit;
  return out;
}

}  // namespace ashlar
