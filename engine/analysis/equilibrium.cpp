#include "analysis/equilibrium.hpp"

#include <array>
#include <cmath>

#include "core/clock.hpp"
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

// "caller: " before a message, or nothing for an unnamed caller.
std::string message_prefix(const std::string& caller) { return caller.empty() ? "" : caller + ": "; }

}  // namespace

void check_free_block(const Structure& structure, int block, const std::string& caller) {
  const std::string prefix = message_prefix(caller);
  if (block < 0 || block >= structure.size()) {
    throw InvalidArgument(prefix + "block " + std::to_string(block + 1) +
                          " is out of range (the structure has " + std::to_string(structure.size()) +
                          " blocks)");
  }
  if (structure.is_support(block)) {
    throw InvalidArgument(prefix + "block " + std::to_string(block + 1) + " ('" + structure.name(block) +
                          "') is a support: its weight goes straight to the ground");
  }
}

void check_analysed_block(const EquilibriumProblem& problem, const Structure& structure, int block,
                          const std::string& caller) {
  if (problem.row_of_block[block] < 0) {
    throw InvalidArgument(message_prefix(caller) + "block " + std::to_string(block + 1) + " ('" +
                          structure.name(block) + "') touches nothing that leads to a support");
  }
}

EquilibriumResult analyze_equilibrium(const Structure& structure, const AnalysisSettings& settings,
                                      const EquilibriumResult* warm_start,
                                      EquilibriumProblem* problem_out) {
  const auto start = Clock::now();
  check_settings(settings);
  EquilibriumProblem problem = build_equilibrium_problem(structure, settings.problem);
  EquilibriumSolver solver(problem);
  EquilibriumResult result;
  result.timings.setup = seconds_since(start);
  if (warm_start) result.solution = warm_start->solution;
  InteriorPointSettings solver_settings = settings.solver;
  if (settings.verdict_only) solver_settings.certify_below = settings.stable_tolerance;
  const InteriorPointInfo info =
      solver.solve(problem, solver_settings, result.solution, warm_start != nullptr);
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
  const Eigen::VectorXd& x = result.solution.x;
  const double wu = problem.weight_unit;
  result.cables.resize(structure.cables().size());
  result.virtual_torques.assign(structure.size(), Vec3::Zero());
  const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
  double penalised = 0.0;  // scaled
  for (size_t k = 0; k < problem.groups.size(); ++k) {
    const ForceGroup& v = problem.groups[k];
    const Eigen::Vector4d scaled = x.segment<4>(4 * static_cast<Eigen::Index>(k));
    // The penalised unknowns are bounded below by 0; an iterate short of
    // convergence may still sit a little outside, which must not make the
    // infeasibility negative.
    penalised += problem.rules_of(v).linear.dot(scaled.cwiseMax(0.0));
    if (v.kind == GroupKind::cable || v.kind == GroupKind::bounded_cable) {
      result.cables[v.source].tension = (scaled(0) - scaled(1)) * wu;
      result.cables[v.source].compression = scaled(1) * wu;
      continue;
    }
    if (v.kind == GroupKind::slack) {
      if (v.block_a >= 0) {
        result.virtual_torques[v.block_a](rows[v.component] - 3) =
            (scaled(0) - scaled(1)) * wu * problem.length_unit;
      }
      continue;
    }
    const Eigen::Vector4d forces = scaled * wu;
    const Interface& contact = interfaces[v.source];
    InterfaceForces& through = result.interfaces[v.source];
    const double normal = forces(0) - forces(1);
    through.compression += forces(0);
    through.tension += forces(1);
    through.normal_force += normal;
    through.resultant += normal * contact.normal + forces(2) * contact.u + forces(3) * contact.v;
    pressure_weight[v.source] += normal;
    pressure_moment[v.source] += normal * v.position;
    result.block_tension[v.block_a] += forces(1);
    result.block_tension[v.block_b] += forces(1);
    result.vertex_forces.push_back(forces);
    result.vertex_positions.push_back(v.position);
    result.vertex_interface.push_back(v.source);
  }
  for (size_t i = 0; i < interfaces.size(); ++i) {
    result.interfaces[i].center_of_pressure = pressure_weight[i] > 0.0
                                                  ? Vec3(pressure_moment[i] / pressure_weight[i])
                                                  : interfaces[i].center;
  }

  result.imbalance_without_tension = compression_only_imbalance(problem, x);
  // Stability is a question of feasibility: forces that balance every block
  // without tension prove it, converged or not. Without such forces only a
  // converged optimum (whose tension is then needed) proves instability.
  const bool floating = problem.has_floating_bodies();
  result.stable = !floating && result.status != SolverStatus::interrupted &&
                  result.imbalance_without_tension <= settings.stable_tolerance;
  result.borderline = !floating &&
                      result.imbalance_without_tension > settings.stable_tolerance * kBorderlineBelow &&
                      result.imbalance_without_tension <= settings.stable_tolerance * kBorderlineAbove;
  // Floating blocks cannot be balanced at all; a numerical failure (also what
  // a problem with no equilibrium even with tension, e.g. no friction under
  // a sideways load, ends in) leaves no usable equilibrium either.
  const int bodies = std::max(problem.body_count, 1);
  if (floating || has_no_answer(result.status)) {
    result.infeasibility = std::numeric_limits<double>::infinity();
    result.penalty = std::numeric_limits<double>::infinity();
  } else {
    result.infeasibility = result.stable ? 0.0 : penalised / bodies;
    result.penalty = info.objective / bodies;
  }
  result.seconds = seconds_since(start);
  if (problem_out) *problem_out = std::move(problem);
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
