#include "analysis/verdict_notes.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ashlar {

namespace {

// An interface uses all its friction when its friction is within this
// fraction of what mu times its compression allows.
constexpr double kAtLimit = 1e-3;
// Interfaces carrying less than this fraction of the mean block weight are
// not what a block stands on.
constexpr double kCarriesLoad = 1e-3;

// The friction a force uses as a fraction of what mu times its compression
// allows: 1 on the pyramid's (or box's) surface. For an interface, of its
// vertices' summed forces: a vertex with little compression may use all of
// its own friction while the joint as a whole is far from sliding.
double friction_used(const EquilibriumOptions& options, double fu, double fv, double compression) {
  const double allowed = options.friction * compression;
  if (!(allowed > 0.0)) return 0.0;
  if (options.friction_model == FrictionModel::box) return std::max(std::abs(fu), std::abs(fv)) / allowed;
  // The inscribed pyramid of n sides, one edge along u: its side j faces the
  // direction at angle (2j + 1) pi / n, at distance cos(pi / n).
  const int n = options.friction_sides;
  double used = 0.0;
  for (int j = 0; j < n; ++j) {
    const double angle = (2 * j + 1) * M_PI / n;
    used = std::max(used, (fu * std::cos(angle) + fv * std::sin(angle)) / std::cos(M_PI / n));
  }
  return used / allowed;
}

void name_failing_blocks(const Structure& structure, const AnalysisSettings& settings, EquilibriumResult& result) {
  double largest = 0.0;
  for (double tension : result.block_tension) largest = std::max(largest, tension);
  if (!(largest > 0.0)) return;
  std::vector<int> failing;
  for (size_t i = 0; i < result.block_tension.size(); ++i) {
    if (result.block_tension[i] > 1e-3 * largest) failing.push_back(static_cast<int>(i));
  }
  std::stable_sort(failing.begin(), failing.end(),
                   [&](int a, int b) { return result.block_tension[a] > result.block_tension[b]; });
  if (failing.size() > static_cast<size_t>(kFailingBlocksShown)) failing.resize(kFailingBlocksShown);
  result.failing_gaps =
      structure.missed_contacts(failing, kNearMiss * structure.bounds().diagonal(), settings.problem.contact);
  result.failing_blocks = std::move(failing);
}

void warn_of_friction_at_limit(const Structure& structure, const AnalysisSettings& settings,
                               EquilibriumResult& result) {
  const EquilibriumOptions& options = settings.problem;
  if (!std::isfinite(options.friction) || options.friction_law != FrictionLaw::coulomb) return;
  double weight = 0.0;
  int free_blocks = 0;
  for (int i = 0; i < structure.size(); ++i) {
    if (structure.is_support(i)) continue;
    weight += kGravity * structure.block(i).mass();
    ++free_blocks;
  }
  if (free_blocks == 0) return;
  const double load = kCarriesLoad * weight / free_blocks;
  std::vector<Eigen::Vector4d> totals(result.interfaces.size(), Eigen::Vector4d::Zero());
  for (size_t k = 0; k < result.vertex_forces.size(); ++k) totals[result.vertex_interface[k]] += result.vertex_forces[k];
  std::vector<bool> at_limit(result.interfaces.size(), false);
  for (size_t i = 0; i < totals.size(); ++i) {
    const Eigen::Vector4d& f = totals[i];
    at_limit[i] = f[0] > load && friction_used(options, f[2], f[3], f[0]) >= 1.0 - kAtLimit;
  }
  const long count = std::count(at_limit.begin(), at_limit.end(), true);
  if (count == 0) return;
  std::ostringstream text;
  text << "friction is at its limit (mu = " << options.friction << ") at " << count << " of "
       << result.interfaces.size() << " interfaces, e.g. between blocks ";
  const size_t first = static_cast<size_t>(std::find(at_limit.begin(), at_limit.end(), true) - at_limit.begin());
  text << result.interfaces[first].a + 1 << " and " << result.interfaces[first].b + 1
       << ": the equilibrium method may rest on friction that no load presses in; "
          "method = \"kinematic\" or ashlar.compare_methods checks it";
  result.warnings.push_back(text.str());
}

}  // namespace

void annotate_verdict(const Structure& structure, const AnalysisSettings& settings, EquilibriumResult& result) {
  if (has_no_answer(result.status)) return;
  if (!result.stable && result.floating_blocks.empty()) name_failing_blocks(structure, settings, result);
  if (result.stable && result.method == AnalysisMethod::equilibrium) {
    warn_of_friction_at_limit(structure, settings, result);
  }
}

}  // namespace ashlar
