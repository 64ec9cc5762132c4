#include "analysis/equilibrium.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/cra.hpp"
#include "analysis/equilibrium_analysis.hpp"
#include "analysis/kinematic.hpp"
#include "analysis/verdict_notes.hpp"
#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar {

namespace {

// Interfaces whose normal force is under this fraction of the largest are
// left out of the thrust line: round-off, blocks that merely touch.
constexpr double kNegligibleThrust = 1e-3;

}  // namespace

void check_analysis_settings(const AnalysisSettings& settings) {
  const InteriorPointSettings& solver = settings.solver;
  if (solver.max_iterations < 1) throw InvalidArgument("max_iterations must be at least 1, got " + std::to_string(solver.max_iterations));
  if (!(solver.tolerance > 0.0) || !std::isfinite(solver.tolerance)) {
    throw InvalidArgument("tolerance must be a finite number > 0, got " + shortest_number(solver.tolerance));
  }
  if (!(solver.step_fraction > 0.0 && solver.step_fraction < 1.0)) {
    throw InvalidArgument("step_fraction must lie strictly between 0 and 1, got " + shortest_number(solver.step_fraction));
  }
  if (!(settings.stable_tolerance > 0.0) || !std::isfinite(settings.stable_tolerance)) {
    throw InvalidArgument("stable_tolerance must be a finite number > 0, got " + shortest_number(settings.stable_tolerance));
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
    throw InvalidArgument(prefix + structure.label(block) + " is a support: its weight goes straight to the ground");
  }
}

void check_analysed_block(const EquilibriumProblem& problem, const Structure& structure, int block,
                          const std::string& caller) {
  if (problem.row_of_block[block] < 0) {
    throw InvalidArgument(message_prefix(caller) + structure.label(block) + " touches nothing that leads to a support");
  }
}

std::vector<char> asked_blocks(const Structure& structure, const std::vector<int>& blocks, const std::string& caller) {
  std::vector<char> asked(structure.size(), blocks.empty() ? 1 : 0);
  for (size_t k = 0; k < blocks.size(); ++k) {
    const int block = blocks[k];
    const std::string entry = message_prefix(caller) + "blocks[" + std::to_string(k + 1) + "]: block " +
                              std::to_string(block + 1);
    if (block < 0 || block >= structure.size()) {
      throw InvalidArgument(entry + " is out of range (the structure has " + std::to_string(structure.size()) +
                            " blocks)");
    }
    if (asked[block]) throw InvalidArgument(entry + " is listed twice");
    asked[block] = 1;
  }
  return asked;
}

namespace {

EquilibriumResult analyze_by_method(const Structure& structure, const AnalysisSettings& settings,
                                    const EquilibriumResult* warm_start, EquilibriumProblem* problem_out) {
  if (settings.method == AnalysisMethod::kinematic) {
    if (warm_start || problem_out) {
      throw InvalidArgument("the kinematic method takes no warm start and gives no problem out");
    }
    return analyze_kinematic(structure, settings);
  }
  if (is_cra(settings.method)) {
    if (warm_start || problem_out) {
      throw InvalidArgument(std::string("method ") + kAnalysisMethodNames.name(settings.method) +
                            " takes no warm start and gives no problem out");
    }
    return analyze_cra(structure, settings);
  }
  EquilibriumAnalysis analysis(structure, settings);
  if (warm_start) analysis.set_starting_point(warm_start->solution);
  EquilibriumResult result = analysis.solve(warm_start != nullptr);
  result.solution = analysis.take_solution();  // moved: the object ends here
  if (problem_out) *problem_out = analysis.take_problem();
  return result;
}

}  // namespace

Verdict verdict_of(const EquilibriumResult& result) {
  if (result.stable) return Verdict::stands;
  if (!result.floating_blocks.empty()) return Verdict::falls;
  switch (result.status) {
    case SolverStatus::converged:
    case SolverStatus::certified:
    case SolverStatus::infeasible:
      return Verdict::falls;
    default:
      return Verdict::no_verdict;
  }
}

EquilibriumResult analyze_equilibrium(const Structure& structure, const AnalysisSettings& settings,
                                      const EquilibriumResult* warm_start,
                                      EquilibriumProblem* problem_out) {
  EquilibriumResult result = analyze_by_method(structure, settings, warm_start, problem_out);
  annotate_verdict(structure, settings, result);
  return result;
}

std::vector<std::vector<Vec3>> thrust_polylines(const Structure& structure,
                                                const EquilibriumResult& result) {
  // The graph: a node per compressed interface, an edge per pair of them on
  // one free block.
  const int count = static_cast<int>(result.interfaces.size());
  double largest = 0.0;
  for (const InterfaceForces& f : result.interfaces) {
    if (std::isfinite(f.normal_force)) largest = std::max(largest, f.normal_force);
  }
  std::vector<bool> compressed(count, false);
  std::vector<std::vector<int>> compressed_of_block(structure.size());
  for (int i = 0; i < count; ++i) {
    const InterfaceForces& f = result.interfaces[i];
    compressed[i] = f.normal_force > kNegligibleThrust * largest && std::isfinite(f.normal_force) &&
                    f.center_of_pressure.allFinite();
    if (!compressed[i]) continue;
    for (const int block : {f.a, f.b}) {
      if (!structure.is_support(block)) compressed_of_block[block].push_back(i);
    }
  }
  struct Edge {
    int to, id;
  };
  std::vector<std::vector<Edge>> edges(count);
  int edge_count = 0;
  for (const std::vector<int>& nodes : compressed_of_block) {
    for (size_t p = 0; p < nodes.size(); ++p) {
      for (size_t q = p + 1; q < nodes.size(); ++q) {
        edges[nodes[p]].push_back({nodes[q], edge_count});
        edges[nodes[q]].push_back({nodes[p], edge_count});
        ++edge_count;
      }
    }
  }
  // Walks from a node along unused edges, through nodes with two edges.
  std::vector<bool> used(edge_count, false);
  const auto walk = [&](int node) {
    std::vector<Vec3> polyline{result.interfaces[node].center_of_pressure};
    while (true) {
      const auto next = std::find_if(edges[node].begin(), edges[node].end(),
                                     [&](const Edge& e) { return !used[e.id]; });
      if (next == edges[node].end()) break;
      used[next->id] = true;
      node = next->to;
      polyline.push_back(result.interfaces[node].center_of_pressure);
      if (edges[node].size() != 2) break;
    }
    return polyline;
  };
  const auto has_unused = [&](int node) {
    return std::any_of(edges[node].begin(), edges[node].end(),
                       [&](const Edge& e) { return !used[e.id]; });
  };
  std::vector<std::vector<Vec3>> polylines;
  // Ends and branch points first, so that open lines are never cut; then
  // whatever is left is closed loops.
  for (const bool loops : {false, true}) {
    for (int node = 0; node < count; ++node) {
      if (!loops && edges[node].size() == 2) continue;
      while (has_unused(node)) polylines.push_back(walk(node));
    }
  }
  for (int node = 0; node < count; ++node) {
    if (compressed[node] && edges[node].empty()) {
      polylines.push_back({result.interfaces[node].center_of_pressure});
    }
  }
  return polylines;
}

std::vector<Vec3> thrust_line(const Structure& structure, const EquilibriumResult& result) {
  const std::vector<std::vector<Vec3>> polylines = thrust_polylines(structure, result);
  if (polylines.empty()) return {};
  // A chain from a support: from that end, as the line is walked.
  std::vector<Vec3> line = *std::max_element(polylines.begin(), polylines.end(), [](const auto& x, const auto& y) {
    return x.size() < y.size();
  });
  const auto near_support = [&](const Vec3& p) {
    for (const InterfaceForces& f : result.interfaces) {
      if ((structure.is_support(f.a) || structure.is_support(f.b)) && f.center_of_pressure == p) return true;
    }
    return false;
  };
  if (!near_support(line.front()) && near_support(line.back())) std::reverse(line.begin(), line.end());
  return line;
}

}  // namespace ashlar
