#include "analysis/equilibrium.hpp"

#include <chrono>
#include <cmath>

#include "core/error.hpp"

namespace ashlar {

namespace {

void check_settings(const AnalysisSettings& settings) {
  const InteriorPointSettings& solver = settings.solver;
  if (solver.max_iterations < 1) throw InvalidArgument("max_iterations must be at least 1");
  if (!(solver.tolerance > 0.0) || !std::isfinite(solver.tolerance)) {
    throw InvalidArgument("tolerance must be a finite number > 0");
  }
  if (!(solver.step_fraction > 0.0 && solver.step_fraction < 1.0)) {
    throw InvalidArgument("step_fraction must lie strictly between 0 and 1");
  }
  if (!(settings.stable_tolerance > 0.0) || !std::isfinite(settings.stable_tolerance)) {
    throw InvalidArgument("stable_tolerance must be a finite number > 0");
  }
}

// How far the forces x, with every tension set to zero, are from a
// compression-only equilibrium that respects friction: the largest
// imbalance of a block relative to its own load (or the mean block weight
// when larger), or of a compression or friction bound relative to the mean
// block weight. Small means the forces certify stability, whatever the
// solver's status.
double distance_from_compression_only_equilibrium(const EquilibriumProblem& problem,
                                                  const Eigen::VectorXd& x) {
  Eigen::VectorXd imbalance = -problem.rhs;
  double worst = 0.0;
  for (size_t k = 0; k < problem.vertices.size(); ++k) {
    const ContactVertex& v = problem.vertices[k];
    Eigen::Vector4d forces = x.segment<4>(4 * static_cast<Eigen::Index>(k));
    forces(1) = 0.0;
    problem.add_effect(v, forces, imbalance);
    worst = std::max(worst, -(problem.vertex_rows * forces).minCoeff());
  }
  const int d = problem.block_rows;
  for (int row = 0; row < problem.row_count; row += d) {
    const double load = std::max(1.0, problem.rhs.segment(row, d).lpNorm<Eigen::Infinity>());
    worst = std::max(worst, imbalance.segment(row, d).lpNorm<Eigen::Infinity>() / load);
  }
  return worst;
}

}  // namespace

EquilibriumResult analyze_equilibrium(const Structure& structure, const AnalysisSettings& settings,
                                      const EquilibriumResult* warm_start) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  check_settings(settings);
  const EquilibriumProblem problem = build_equilibrium_problem(structure, settings.problem);
  EquilibriumSolver solver(problem);
  EquilibriumResult result;
  result.timings.setup = std::chrono::duration<double>(Clock::now() - start).count();
  if (warm_start) result.solution = warm_start->solution;
  const InteriorPointInfo info =
      solver.solve(problem, settings.solver, result.solution, warm_start != nullptr);
  result.status = info.status;
  result.iterations = info.iterations;
  result.factorizations = info.factorizations;
  result.objective = info.objective;
  result.timings.assembly = info.assembly_seconds;
  result.timings.factorization = info.factorization_seconds;
  result.timings.solve = info.solve_seconds;
  result.floating_blocks = problem.floating_blocks;

  const std::vector<Interface>& interfaces = structure.interfaces(settings.problem.contact);
  result.interfaces.resize(interfaces.size());
  for (size_t i = 0; i < interfaces.size(); ++i) {
    result.interfaces[i].a = interfaces[i].a;
    result.interfaces[i].b = interfaces[i].b;
  }
  std::vector<double> pressure_weight(interfaces.size(), 0.0);
  std::vector<Vec3> pressure_moment(interfaces.size(), Vec3::Zero());
  result.block_tension.assign(structure.size(), 0.0);
  double total_tension = 0.0;
  const Eigen::VectorXd& x = result.solution.x;
  for (size_t k = 0; k < problem.vertices.size(); ++k) {
    const ContactVertex& v = problem.vertices[k];
    const Eigen::Vector4d forces = x.segment<4>(4 * static_cast<Eigen::Index>(k)) * problem.weight_unit;
    const Interface& contact = interfaces[v.interface_index];
    InterfaceForces& through = result.interfaces[v.interface_index];
    const double normal = forces(0) - forces(1);
    through.compression += forces(0);
    through.tension += forces(1);
    through.normal_force += normal;
    through.resultant += normal * contact.normal + forces(2) * contact.u + forces(3) * contact.v;
    pressure_weight[v.interface_index] += normal;
    pressure_moment[v.interface_index] += normal * v.position;
    result.block_tension[v.block_a] += forces(1);
    result.block_tension[v.block_b] += forces(1);
    total_tension += forces(1);
    result.vertex_forces.push_back(forces);
    result.vertex_positions.push_back(v.position);
    result.vertex_interface.push_back(v.interface_index);
  }
  for (size_t i = 0; i < interfaces.size(); ++i) {
    result.interfaces[i].center_of_pressure = pressure_weight[i] > 0.0
                                                  ? Vec3(pressure_moment[i] / pressure_weight[i])
                                                  : interfaces[i].center;
  }

  result.imbalance_without_tension = distance_from_compression_only_equilibrium(problem, x);
  // Stability is a question of feasibility: forces that balance every block
  // without tension prove it, converged or not. Without such forces only a
  // converged optimum (whose tension is then needed) proves instability.
  result.stable = result.floating_blocks.empty() &&
                  result.imbalance_without_tension <= settings.stable_tolerance;
  // Floating blocks cannot be balanced at all; a numerical failure (also what
  // a problem with no equilibrium even with tension, e.g. no friction under
  // a sideways load, ends in) leaves no usable equilibrium either.
  if (!result.floating_blocks.empty() || result.status == SolverStatus::numerical_error) {
    result.infeasibility = std::numeric_limits<double>::infinity();
  } else if (result.stable) {
    result.infeasibility = 0.0;
  } else {
    result.infeasibility = problem.total_weight > 0.0 ? total_tension / problem.total_weight : 0.0;
  }
  result.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return result;
}

std::vector<Vec3> thrust_line(const Structure& structure, const EquilibriumResult& result) {
  const int n = structure.size();
  std::vector<std::vector<int>> touching(n);
  for (size_t i = 0; i < result.interfaces.size(); ++i) {
    const InterfaceForces& f = result.interfaces[i];
    if (structure.is_support(f.a) && structure.is_support(f.b)) continue;
    touching[f.a].push_back(static_cast<int>(i));
    touching[f.b].push_back(static_cast<int>(i));
  }
  std::vector<int> order;
  bool chain = true;
  int start = -1;
  for (int i = 0; i < n && chain; ++i) {
    if (structure.is_support(i)) continue;
    if (touching[i].size() > 2) chain = false;
    for (int f : touching[i]) {
      const InterfaceForces& contact = result.interfaces[f];
      if (start < 0 && structure.is_support(contact.a == i ? contact.b : contact.a)) start = f;
    }
  }
  if (chain && start >= 0) {
    // Walk from a support through blocks with two interfaces each.
    std::vector<bool> used(result.interfaces.size(), false);
    int f = start;
    const InterfaceForces& first = result.interfaces[f];
    int block = structure.is_support(first.a) ? first.b : first.a;
    while (f >= 0 && !used[f]) {
      used[f] = true;
      order.push_back(f);
      if (structure.is_support(block)) break;
      int next = -1;
      for (int g : touching[block]) {
        if (!used[g]) next = g;
      }
      if (next < 0) break;
      const InterfaceForces& contact = result.interfaces[next];
      block = contact.a == block ? contact.b : contact.a;
      f = next;
    }
    size_t reachable = 0;
    for (size_t i = 0; i < result.interfaces.size(); ++i) {
      const InterfaceForces& c = result.interfaces[i];
      reachable += !(structure.is_support(c.a) && structure.is_support(c.b));
    }
    chain = order.size() == reachable;
  }
  if (!chain || start < 0) {
    order.clear();
    for (size_t i = 0; i < result.interfaces.size(); ++i) order.push_back(static_cast<int>(i));
  }
  std::vector<Vec3> points;
  for (int f : order) {
    if (result.interfaces[f].normal_force > 0.0) points.push_back(result.interfaces[f].center_of_pressure);
  }
  return points;
}

}  // namespace ashlar
