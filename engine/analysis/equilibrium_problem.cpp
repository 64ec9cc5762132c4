#include "analysis/equilibrium_problem.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/error.hpp"
#include "core/text.hpp"
#include "core/union_find.hpp"

namespace ashlar {

namespace {

void check_options(const EquilibriumOptions& options) {
  if (std::isnan(options.friction) || options.friction < 0.0) {
    throw InvalidArgument("friction must be a number >= 0 (math.huge for no sliding), got " +
                          shortest_number(options.friction));
  }
  if (options.friction_sides < 3 || options.friction_sides > 1024) {
    throw InvalidArgument("friction_sides must be an integer from 3 to 1024, got " +
                          std::to_string(options.friction_sides));
  }
  if (!std::isfinite(options.tension_weight) || options.tension_weight < 0.0) {
    throw InvalidArgument("tension_weight must be a finite number >= 0, got " + shortest_number(options.tension_weight));
  }
  if (!std::isfinite(options.force_weight) || options.force_weight < 0.0) {
    throw InvalidArgument("force_weight must be a finite number >= 0, got " + shortest_number(options.force_weight));
  }
}

// Which bodies (blocks, then junctions) are joined to a support by a path of
// contacts and cables.
std::vector<bool> grounded_bodies(const Structure& structure,
                                  const std::vector<Interface>& interfaces,
                                  const std::vector<std::array<int, 2>>& cable_bodies,
                                  int junction_count) {
  const int n = structure.size();
  const int bodies = n + junction_count;
  UnionFind components(bodies);
  for (const Interface& contact : interfaces) components.join(contact.a, contact.b);
  for (const std::array<int, 2>& ends : cable_bodies) components.join(ends[0], ends[1]);
  std::vector<bool> root_grounded(bodies, false);
  for (int i = 0; i < n; ++i) {
    if (structure.is_support(i)) root_grounded[components.root(i)] = true;
  }
  std::vector<bool> grounded(bodies);
  for (int i = 0; i < bodies; ++i) grounded[i] = root_grounded[components.root(i)];
  return grounded;
}

// Junctions: cable ends away from blocks, merged where they coincide (within
// `tolerance`, m). Fills the body of every cable end (block index, or block
// count + junction index) and returns the junction positions. A junction
// with a single cable end is an error: that end hangs from nothing.
std::vector<Vec3> find_junctions(const Structure& structure, double tolerance,
                                 std::vector<std::array<int, 2>>& cable_bodies) {
  const std::vector<Cable>& cables = structure.cables();
  const int n = structure.size();
  cable_bodies.assign(cables.size(), {-1, -1});
  struct LooseEnd {
    Vec3 point;
    int cable, end;
  };
  std::vector<LooseEnd> loose;
  for (size_t c = 0; c < cables.size(); ++c) {
    const CableEnd* ends[2] = {&cables[c].from, &cables[c].to};
    for (int e = 0; e < 2; ++e) {
      if (ends[e]->block >= 0) cable_bodies[c][e] = ends[e]->block;
      else loose.push_back({ends[e]->point, static_cast<int>(c), e});
    }
  }
  std::sort(loose.begin(), loose.end(),
            [](const LooseEnd& p, const LooseEnd& q) { return p.point.x() < q.point.x(); });
  std::vector<Vec3> junctions;
  std::vector<int> junction_of(loose.size(), -1), ends_at(0);
  for (size_t i = 0; i < loose.size(); ++i) {
    // Ends sorted by x: only those within tolerance in x can coincide.
    for (size_t j = i; j-- > 0 && loose[i].point.x() - loose[j].point.x() <= tolerance;) {
      if ((loose[i].point - loose[j].point).norm() <= tolerance) {
        junction_of[i] = junction_of[j];
        break;
      }
    }
    if (junction_of[i] < 0) {
      junction_of[i] = static_cast<int>(junctions.size());
      junctions.push_back(loose[i].point);
      ends_at.push_back(0);
    }
    ++ends_at[junction_of[i]];
    cable_bodies[loose[i].cable][loose[i].end] = n + junction_of[i];
  }
  for (size_t i = 0; i < loose.size(); ++i) {
    if (ends_at[junction_of[i]] < 2) {
      throw InvalidArgument("cable " + std::to_string(loose[i].cable + 1) + " '" +
                            (loose[i].end == 0 ? "from" : "to") +
                            "': the end is on no block and meets no other cable end; "
                            "give it a block, or end it where another cable ends");
    }
  }
  return junctions;
}

void check_planar_loads_and_cables(const Structure& structure, double tolerance) {
  const std::vector<Cable>& cables = structure.cables();
  for (size_t c = 0; c < cables.size(); ++c) {
    const CableEnd* ends[2] = {&cables[c].from, &cables[c].to};
    for (const CableEnd* end : ends) {
      const double plane_y =
          end->block >= 0 ? structure.block(end->block).centroid().y() : cables[c].from.point.y();
      if (std::abs(end->point.y() - plane_y) > tolerance) {
        throw InvalidArgument("planar structure: cable " + std::to_string(c + 1) +
                              " leaves the x-z plane (its ends must lie in the mid-plane of "
                              "their blocks, y = " + std::to_string(plane_y) + ")");
      }
    }
  }
  for (size_t k = 0; k < structure.loads().size(); ++k) {
    const PointLoad& load = structure.loads()[k];
    const Block& block = structure.block(load.block);
    const double size = block.bounds().diagonal();
    if (std::abs(load.force.y()) > 1e-12 * load.force.norm() ||
        std::abs(load.at.y() - block.centroid().y()) > 1e-9 * size) {
      throw InvalidArgument("planar structure: load " + std::to_string(k + 1) + " on block " +
                            std::to_string(load.block + 1) +
                            " is out of the x-z plane (a y force, or applied off the block's "
                            "mid-plane y = " + std::to_string(block.centroid().y()) + ")");
    }
  }
}

}  // namespace

// The balance rows a problem keeps, in order: all six, or for a planar
// structure (x-z plane) the in-plane force and moment Fx, Fz, My.
const std::array<int, 6>& balance_rows(bool planar) {
  static const std::array<int, 6> all = {0, 1, 2, 3, 4, 5};
  static const std::array<int, 6> planar_first = {0, 2, 4, 1, 3, 5};
  return planar ? planar_first : all;
}

Eigen::Matrix<double, 6, 4> contact_vertex_effect(const Interface& contact, const Vec3& position,
                                          const Vec3& centroid, double length_unit,
                                          const std::array<int, 6>& rows) {
  const Vec3 arm = (position - centroid) / length_unit;
  Eigen::Matrix<double, 6, 4> effect;
  const Vec3 directions[3] = {contact.normal, contact.u, contact.v};
  const int columns[3] = {0, 2, 3};
  for (int k = 0; k < 3; ++k) {
    effect.block<3, 1>(0, columns[k]) = directions[k];
    effect.block<3, 1>(3, columns[k]) = arm.cross(directions[k]);
  }
  effect.col(1) = -effect.col(0);  // tension pulls where compression pushes
  Eigen::Matrix<double, 6, 4> ordered;
  for (int r = 0; r < 6; ++r) ordered.row(r) = effect.row(rows[r]);
  return ordered;
}

bool EquilibriumProblem::contacts_only() const {
  return junctions.empty() && std::all_of(groups.begin(), groups.end(), [](const ForceGroup& group) {
           return group.kind == GroupKind::contact_vertex || group.kind == GroupKind::slack;
         });
}

Eigen::Matrix<double, Eigen::Dynamic, 3> friction_rows(const EquilibriumOptions& options) {
  const double mu = options.friction;
  Eigen::Matrix<double, Eigen::Dynamic, 3> rows;
  if (std::isinf(mu)) return rows;
  if (options.friction_model == FrictionModel::box) {
    rows.resize(4, 3);
    rows << mu, -1, 0, mu, 1, 0, mu, 0, -1, mu, 0, 1;
  } else {
    // Inscribed pyramid: edges on the cone at angles 2 pi j / m (one along
    // u); side j faces the direction (2j + 1) pi / m at distance
    // mu c cos(pi / m).
    const int m = options.friction_sides;
    rows.resize(m, 3);
    for (int j = 0; j < m; ++j) {
      const double facing = (2 * j + 1) * kPi / m;
      rows.row(j) << mu * std::cos(kPi / m), -std::cos(facing), -std::sin(facing);
    }
  }
  // Unit rows: the same cone, but with mu = 100 or 1e4 the rows' scale
  // would otherwise spread the slacks and multipliers over mu^2 and stall
  // the interior point (a large mu then behaves like an infinite one).
  rows.rowwise().normalize();
  return rows;
}

namespace {

// Columns (t, k) of a cable pulling body `row`'s attachment point `at` (m)
// along `direction`; moments about `centroid` for blocks, none for junctions.
Eigen::Matrix<double, 6, 4> cable_effect(const Vec3& direction, const Vec3& at,
                                         const Vec3* centroid, double length_unit,
                                         const std::array<int, 6>& rows) {
  Eigen::Matrix<double, 6, 1> pull = Eigen::Matrix<double, 6, 1>::Zero();
  pull.head<3>() = direction;
  if (centroid) pull.tail<3>() = ((at - *centroid) / length_unit).cross(direction);
  Eigen::Matrix<double, 6, 4> effect = Eigen::Matrix<double, 6, 4>::Zero();
  for (int r = 0; r < 6; ++r) effect(r, 0) = pull(rows[r]);
  effect.col(1) = -effect.col(0);  // compression pushes where tension pulls
  return effect;
}

// With given friction strengths, what a unit of friction beyond them costs
// against a unit of virtual force on a block: far more, so that the best
// equilibrium puts what the joints cannot carry on the blocks themselves
// (where it creates no moments that joints would balance with normal forces
// nothing presses in). The excess only keeps the QP strictly feasible.
constexpr double kExcessFrictionCost = 10.0;
// The linear cost of virtual loads with given friction strengths, against
// their kinetic energy of about half a unit per block. It only has to exceed
// the balance multipliers of a structure that stands (of the order of the
// force regularisation) to keep zero virtual load exact. Larger, it is a dead
// zone that departs from least constraint: a block whose fall is blocked by a
// steep face (normal 85 degrees from vertical) gets no contact force from it
// in the first round, since a unit of that force trades 0.08 of vertical
// virtual load for 1.4 of horizontal; the joint then never gets strength
// (the Armadillo vault's voussoir C-11-1 fell at any finite friction).
constexpr double kLeastConstraintExactness = 1e-2;

void set_rules(EquilibriumProblem& problem, const EquilibriumOptions& options) {
  const bool given_strength = options.friction_law == FrictionLaw::given_strength;
  // The regularisation's pull on the multipliers grows with the forces,
  // which grow with the number of blocks sharing the load (an arch's thrust
  // is a fraction of its whole weight). Dividing it by the body count keeps
  // the tension penalty exact on large structures, while staying far above
  // the scale at which near-free friction unknowns spoil the factorisation.
  const double regularisation = options.force_weight / std::max(problem.body_count, 1);
  const double tension = options.tension_weight;
  const Eigen::Matrix<double, Eigen::Dynamic, 3> friction = friction_rows(options);
  GroupRules& contact = problem.rules[static_cast<int>(GroupKind::contact_vertex)];
  contact.rows = Eigen::Matrix<double, Eigen::Dynamic, 4>::Zero(2 + friction.rows(), 4);
  contact.rows(0, 0) = 1.0;
  contact.rows(1, 1) = 1.0;
  if (given_strength && friction.rows() > 0) contact.bound_coefficients = Eigen::VectorXd::Zero(2 + friction.rows());
  // With a given strength the pyramid's sides stand where mu c would put
  // them: at strength x cos(pi / m) (the box's at strength); the tension
  // unknown, which then acts on no block, adds to the strength.
  const double side_reach =
      options.friction_model == FrictionModel::box ? 1.0 : std::cos(kPi / options.friction_sides);
  for (int j = 0; j < friction.rows(); ++j) {
    if (given_strength) {
      const double tangential = Eigen::Vector2d(friction(j, 1), friction(j, 2)).norm();
      contact.rows(2 + j, 1) = side_reach;
      contact.rows(2 + j, 2) = friction(j, 1) / tangential;
      contact.rows(2 + j, 3) = friction(j, 2) / tangential;
      contact.bound_coefficients(2 + j) = side_reach;
      continue;
    }
    contact.rows(2 + j, 0) = friction(j, 0);
    contact.rows(2 + j, 2) = friction(j, 1);
    contact.rows(2 + j, 3) = friction(j, 2);
  }
  contact.hessian << regularisation, tension, regularisation, regularisation;
  contact.linear << 0.0, given_strength ? kExcessFrictionCost : 1.0, 0.0, 0.0;

  GroupRules& cable = problem.rules[static_cast<int>(GroupKind::cable)];
  cable.rows = Eigen::Matrix<double, Eigen::Dynamic, 4>::Zero(2, 4);
  cable.rows(0, 0) = 1.0;
  cable.rows(1, 1) = 1.0;
  cable.hessian = contact.hessian;
  cable.linear = contact.linear;
  GroupRules& bounded = problem.rules[static_cast<int>(GroupKind::bounded_cable)];
  bounded = cable;
  bounded.rows.conservativeResize(3, 4);
  bounded.rows.row(2) << -1.0, 0.0, 0.0, 0.0;
  bounded.bound_coefficients = Eigen::Vector3d(0.0, 0.0, 1.0);

  GroupRules& slack = problem.rules[static_cast<int>(GroupKind::slack)];
  slack.rows = cable.rows;
  if (given_strength) {
    // Least constraint: the kinetic energy (above), and a small linear part
    // that makes zero virtual load exact when the joints carry everything.
    slack.hessian << 1.0, 1.0, regularisation, regularisation;
    slack.linear << kLeastConstraintExactness, kLeastConstraintExactness, 0.0, 0.0;
  } else {
    slack.hessian << tension, tension, regularisation, regularisation;
    slack.linear << 1.0, 1.0, 0.0, 0.0;
  }

  // Weights are regularised like forces: the thesis's eq. 8 minimises the
  // squares of both, and tension stays far dearer than any weight.
  GroupRules& weight = problem.rules[static_cast<int>(GroupKind::weight)];
  weight.rows = Eigen::Matrix<double, Eigen::Dynamic, 4>::Zero(1, 4);
  weight.rows(0, 0) = 1.0;
  weight.hessian = Eigen::Vector4d::Constant(regularisation);
}

// The balance rows' right-hand side of `structure`'s loads (block weights,
// point loads, half of each cable's weight at either end) in `problem`'s
// units and rows; cable_bodies and cable_weight (N) as the build finds them.
Eigen::VectorXd balance_rhs(const Structure& structure, const EquilibriumProblem& problem,
                            const std::vector<std::array<int, 2>>& cable_bodies,
                            const std::vector<double>& cable_weight) {
  const int n = structure.size();
  const int junction_count = static_cast<int>(problem.junctions.size());
  const std::vector<Cable>& cables = structure.cables();
  const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
  const int d = problem.block_rows;
  const double wu = problem.weight_unit, lu = problem.length_unit;
  auto row_of_body = [&](int body) {
    return body < n ? problem.row_of_block[body] : problem.row_of_junction[body - n];
  };
  // Each body's external force and moment, then the rows the problem keeps.
  const int bodies = n + junction_count;
  std::vector<Eigen::Matrix<double, 6, 1>> external(bodies, Eigen::Matrix<double, 6, 1>::Zero());
  for (int i = 0; i < n; ++i) external[i](2) = structure.block(i).mass() * kGravity / wu;
  auto add_force = [&](int body, const Vec3& force, const Vec3& at) {
    const Vec3* centroid = body < n ? &structure.block(body).centroid() : nullptr;
    external[body] += applied_force_rhs(force, at, centroid, wu, lu);
  };
  for (const PointLoad& load : structure.loads()) add_force(load.block, load.force, load.at);
  for (size_t c = 0; c < cables.size(); ++c) {
    const CableEnd* ends[2] = {&cables[c].from, &cables[c].to};
    for (int e = 0; e < 2; ++e) {
      add_force(cable_bodies[c][e], Vec3(0.0, 0.0, -0.5 * cable_weight[c]), ends[e]->point);
    }
  }
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(problem.row_count);
  for (int body = 0; body < bodies; ++body) {
    const int row = row_of_body(body);
    if (row < 0) continue;
    for (int r = 0; r < d; ++r) rhs(row + r) = external[body](rows[r]);
  }
  return rhs;
}

}  // namespace

EquilibriumProblem build_equilibrium_problem(const Structure& structure,
                                             const EquilibriumOptions& options) {
  check_options(options);
  structure.require_free_block("analysis");
  structure.require_no_overlaps(options.contact, "analysis");
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces(options.contact);
  const std::vector<Interface>& interfaces = *interfaces_list;
  const int n = structure.size();
  const std::vector<Cable>& cables = structure.cables();
  const double size = structure.bounds().diagonal();
  std::vector<std::array<int, 2>> cable_bodies;
  EquilibriumProblem problem;
  problem.junctions = find_junctions(structure, 1e-9 * size, cable_bodies);
  const int junction_count = static_cast<int>(problem.junctions.size());
  const std::vector<bool> grounded =
      grounded_bodies(structure, interfaces, cable_bodies, junction_count);

  const bool planar = structure.planar();
  if (planar) check_planar_loads_and_cables(structure, 1e-9 * size);
  const std::array<int, 6>& rows = balance_rows(planar);
  problem.block_rows = planar ? 3 : 6;
  const int d = problem.block_rows;
  problem.row_of_block.assign(n, -1);
  problem.row_of_junction.assign(junction_count, -1);
  double size_sum = 0.0;
  int analysed_blocks = 0;
  for (int i = 0; i < n; ++i) {
    if (structure.is_support(i)) continue;
    if (!grounded[i]) {
      problem.floating_blocks.push_back(i);
      continue;
    }
    problem.row_of_block[i] = problem.row_count;
    problem.row_count += d;
    problem.total_weight += structure.block(i).mass() * kGravity;
    size_sum += block_size(structure.block(i));
    ++analysed_blocks;
  }
  for (int j = 0; j < junction_count; ++j) {
    if (!grounded[n + j]) {
      problem.floating_junctions.push_back(j);
      continue;
    }
    problem.row_of_junction[j] = problem.row_count;
    problem.row_count += d;
  }
  auto row_of_body = [&](int body) {
    return body < n ? problem.row_of_block[body] : problem.row_of_junction[body - n];
  };
  std::vector<double> cable_weight(cables.size()), cable_length(cables.size());
  double cable_length_sum = 0.0;
  for (size_t c = 0; c < cables.size(); ++c) {
    cable_length[c] = (cables[c].to.point - cables[c].from.point).norm();
    cable_weight[c] = cables[c].mass_per_length * cable_length[c] * kGravity;
    for (int e = 0; e < 2; ++e) {
      if (row_of_body(cable_bodies[c][e]) >= 0) problem.total_weight += 0.5 * cable_weight[c];
    }
    cable_length_sum += cable_length[c];
  }
  problem.body_count = problem.row_count / d;
  if (problem.body_count > 0 && problem.total_weight > 0.0) {
    problem.weight_unit = problem.total_weight / problem.body_count;
  }
  if (analysed_blocks > 0) problem.length_unit = size_sum / analysed_blocks;
  else if (!cables.empty()) problem.length_unit = cable_length_sum / cables.size();
  const double wu = problem.weight_unit, lu = problem.length_unit;

  problem.rhs = balance_rhs(structure, problem, cable_bodies, cable_weight);
  const int bodies = n + junction_count;

  // Reserved exactly (slacks: at most d per end of each cable): the groups
  // are most of a large problem's memory, and growing by doubling left up to
  // half of it unused (a 100,052-block vault: 940 MB at the peak).
  const bool given_strength = options.friction_law == FrictionLaw::given_strength;
  size_t group_count = cables.size() * (1 + 2 * d) + (given_strength ? static_cast<size_t>(n) * d : 0);
  for (const Interface& contact : interfaces) group_count += contact.vertices.size();
  problem.groups.reserve(group_count);
  problem.interfaces = interfaces_list;
  for (size_t k = 0; k < interfaces.size(); ++k) {
    const Interface& contact = interfaces[k];
    const int row_a = problem.row_of_block[contact.a], row_b = problem.row_of_block[contact.b];
    if (row_a < 0 && row_b < 0) continue;  // between supports, or floating
    const Vec3& centroid_a = structure.block(contact.a).centroid();
    const Vec3& centroid_b = structure.block(contact.b).centroid();
    for (size_t corner = 0; corner < contact.vertices.size(); ++corner) {
      const Vec3& p = contact.vertices[corner];
      ForceGroup vertex;
      vertex.source = static_cast<int>(k);
      vertex.component = static_cast<int>(corner);
      vertex.block_a = contact.a;
      vertex.block_b = contact.b;
      vertex.row_a = row_a;
      vertex.row_b = row_b;
      vertex.on_b = contact_vertex_effect(contact, p, centroid_b, lu, rows);
      vertex.lever = (centroid_a - centroid_b) / lu;  // (p - centroid_b) - (p - centroid_a)
      if (given_strength) vertex.on_b.col(1).setZero();  // joints without tension: its unknown only pays for excess friction
      problem.groups.push_back(vertex);
    }
  }
  problem.contact_vertex_count = static_cast<int>(problem.groups.size());

  std::vector<bool> has_cable(bodies, false);
  for (size_t c = 0; c < cables.size(); ++c) {
    const int body_a = cable_bodies[c][0], body_b = cable_bodies[c][1];
    ForceGroup cable;
    cable.source = static_cast<int>(c);
    cable.kind = std::isinf(cables[c].max_tension) ? GroupKind::cable : GroupKind::bounded_cable;
    cable.bound = std::isinf(cables[c].max_tension) ? 0.0 : cables[c].max_tension / wu;
    cable.row_a = row_of_body(body_a);
    cable.row_b = row_of_body(body_b);
    if (cable.row_a < 0 && cable.row_b < 0) continue;  // between supports, or floating
    cable.block_a = body_a < n ? body_a : -1;
    cable.block_b = body_b < n ? body_b : -1;
    const Vec3 along = (cables[c].to.point - cables[c].from.point) / cable_length[c];
    const Vec3* centroid_a = body_a < n ? &structure.block(body_a).centroid() : nullptr;
    const Vec3* centroid_b = body_b < n ? &structure.block(body_b).centroid() : nullptr;
    cable.on_b = cable_effect(-along, cables[c].to.point, centroid_b, lu, rows);
    const Vec3 arm_a = centroid_a ? Vec3(cables[c].from.point - *centroid_a) : Vec3::Zero();
    const Vec3 arm_b = centroid_b ? Vec3(cables[c].to.point - *centroid_b) : Vec3::Zero();
    cable.lever = (arm_b - arm_a) / lu;
    problem.groups.push_back(cable);
    has_cable[body_a] = has_cable[body_a] || cable.row_a >= 0;
    has_cable[body_b] = has_cable[body_b] || cable.row_b >= 0;
  }

  // Virtual torques on blocks with cables, virtual forces and torques on
  // junctions (whose torque rows have nothing else and stay zero). With
  // given friction strengths every free block gets virtual forces and
  // torques instead, each scaled by the square root of the block's mass or
  // moment of inertia: their quadratic cost is then the kinetic energy of
  // the motion the unbalanced loads start (Gauss's least constraint).
  for (int body = 0; body < bodies; ++body) {
    const bool inertial = given_strength && body < n;
    if (!has_cable[body] && !inertial) continue;
    if (inertial && problem.row_of_block[body] < 0) continue;
    // Mass in weight units, and the square of a radius of gyration (a
    // cube's, from the block's size) in length units.
    const double mass = inertial ? structure.block(body).mass() * kGravity / wu : 1.0;
    const double gyration = inertial ? block_size(structure.block(body)) / lu : 0.0;
    for (int r = 0; r < d; ++r) {
      if (body < n && rows[r] < 3 && !inertial) continue;
      ForceGroup slack;
      slack.kind = GroupKind::slack;
      slack.source = body;
      slack.component = r;
      slack.block_a = body < n ? body : -1;
      slack.row_a = row_of_body(body);
      const double scale = !inertial ? 1.0 : std::sqrt(rows[r] < 3 ? mass : mass * gyration * gyration / 18.0);
      slack.set_alone_on_a(r, 0, scale);
      slack.set_alone_on_a(r, 1, -scale);
      problem.groups.push_back(slack);
    }
  }
  set_rules(problem, options);
  return problem;
}

Eigen::Matrix<double, 6, 1> applied_force_rhs(const Vec3& force, const Vec3& at,
                                              const Vec3* centroid, double weight_unit,
                                              double length_unit) {
  // The contact forces balance what is applied: it enters with a minus.
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  rhs.head<3>() = -force / weight_unit;
  if (centroid) rhs.tail<3>() = -((at - *centroid) / length_unit).cross(force / weight_unit);
  return rhs;
}

Eigen::VectorXd load_rhs(const Structure& structure, const EquilibriumProblem& problem) {
  if (static_cast<int>(problem.row_of_block.size()) != structure.size()) {
    throw InvalidArgument("loads: the structure has " + std::to_string(structure.size()) +
                          " blocks, the problem was built for " + std::to_string(problem.row_of_block.size()));
  }
  const double size = structure.bounds().diagonal();
  std::vector<std::array<int, 2>> cable_bodies;
  const std::vector<Vec3> junctions = find_junctions(structure, 1e-9 * size, cable_bodies);
  if (junctions.size() != problem.junctions.size()) {
    throw InvalidArgument("loads: the structure's cables meet at other junctions than the problem's");
  }
  if (structure.planar()) check_planar_loads_and_cables(structure, 1e-9 * size);
  const std::vector<Cable>& cables = structure.cables();
  std::vector<double> cable_weight(cables.size());
  for (size_t c = 0; c < cables.size(); ++c) {
    cable_weight[c] = cables[c].mass_per_length * (cables[c].to.point - cables[c].from.point).norm() * kGravity;
  }
  return balance_rhs(structure, problem, cable_bodies, cable_weight);
}

double compression_only_imbalance(const EquilibriumProblem& problem, const Eigen::VectorXd& x) {
  Eigen::VectorXd imbalance = -problem.rhs;
  double worst = 0.0;
  for (size_t k = 0; k < problem.groups.size(); ++k) {
    const ForceGroup& v = problem.groups[k];
    const GroupRules& rules = problem.rules_of(v);
    // Without the penalised unknowns (tension, cable compression, virtual
    // torques and forces).
    const Eigen::Vector4d forces = (rules.linear.array() > 0.0)
                                       .select(0.0, x.segment<4>(4 * static_cast<Eigen::Index>(k)));
    problem.add_effect(v, forces, imbalance);
    for (Eigen::Index i = 0; i < rules.rows.rows(); ++i) {
      const double lower = rules.lower(i, v.bound);
      worst = std::max(worst, lower - rules.rows.row(i).dot(forces));
    }
  }
  const int d = problem.block_rows;
  for (int row = 0; row < problem.row_count; row += d) {
    const double load = std::max(1.0, problem.rhs.segment(row, d).lpNorm<Eigen::Infinity>());
    worst = std::max(worst, imbalance.segment(row, d).lpNorm<Eigen::Infinity>() / load);
  }
  return worst;
}

Eigen::Matrix<double, 6, 4> ForceGroup::on_a(int block_rows) const {
  const std::array<int, 6>& order = balance_rows(block_rows == 3);  // row r holds component order[r]
  Eigen::Matrix<double, 6, 4> at_b, out;
  for (int r = 0; r < 6; ++r) at_b.row(order[r]) = on_b.row(r);
  Eigen::Matrix<double, 6, 4> at_a = Eigen::Matrix<double, 6, 4>::Zero();
  for (int c = 0; c < 4; ++c) add_effect_at_a<6>(at_b.col(c), at_a.col(c));
  for (int r = 0; r < 6; ++r) out.row(r) = at_a.row(order[r]);
  return out;
}

int EquilibriumProblem::vertical_row() const {
  const std::array<int, 6>& rows = balance_rows(block_rows == 3);
  return static_cast<int>(std::find(rows.begin(), rows.end(), 2) - rows.begin());
}

Eigen::SparseMatrix<double> EquilibriumProblem::equality_matrix() const {
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(groups.size() * 48);
  for (size_t k = 0; k < groups.size(); ++k) {
    const ForceGroup& v = groups[k];
    const Eigen::Matrix<double, 6, 4> on_a = v.on_a(block_rows);
    for (int col = 0; col < 4; ++col) {
      const int variable = 4 * static_cast<int>(k) + col;
      for (int r = 0; r < block_rows; ++r) {
        if (v.row_b >= 0 && v.on_b(r, col) != 0.0) {
          entries.emplace_back(v.row_b + r, variable, v.on_b(r, col));
        }
        if (v.row_a >= 0 && on_a(r, col) != 0.0) {
          entries.emplace_back(v.row_a + r, variable, on_a(r, col));
        }
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(row_count, variable_count());
  matrix.setFromTriplets(entries.begin(), entries.end());
  return matrix;
}

}  // namespace ashlar
