#include "analysis/equilibrium.hpp"

#include <cmath>

#include "analysis/equilibrium_analysis.hpp"
#include "analysis/kinematic.hpp"
#include "core/error.hpp"

namespace ashlar {

void check_analysis_settings(const AnalysisSettings& settings) {
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

namespace {

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

const char* method_name(AnalysisMethod method) {
  return method == AnalysisMethod::kinematic ? "kinematic" : "equilibrium";
}

EquilibriumResult analyze_equilibrium(const Structure& structure, const AnalysisSettings& settings,
                                      const EquilibriumResult* warm_start,
                                      EquilibriumProblem* problem_out) {
  if (settings.method == AnalysisMethod::kinematic) {
    if (warm_start || problem_out) {
      throw InvalidArgument("the kinematic method takes no warm start and gives no problem out");
    }
    return analyze_kinematic(structure, settings);
  }
  EquilibriumAnalysis analysis(structure, settings);
  if (warm_start) analysis.set_starting_point(warm_start->solution);
  EquilibriumResult result = analysis.solve(warm_start != nullptr);
  result.solution = analysis.take_solution();  // moved: the object ends here
  if (problem_out) *problem_out = analysis.take_problem();
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
