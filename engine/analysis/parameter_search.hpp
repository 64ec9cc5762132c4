// Searches over one parameter of a model, each step asking a callback about
// one value: the smallest value at which the model stands (find_threshold;
// with a model's dimension, Heyman's geometric factor of safety is the
// current value over it) and the coarsest discretisation whose answer has
// settled (refine_count).
//
// The callbacks build the model and judge it (an equilibrium analysis, or a
// user's criterion), so these functions run no analysis themselves, and an
// exception from a callback ends the search and propagates unchanged.
//
// Units: values, floor and ceiling are in the parameter's own units (metres
// of thickness, a ratio, ...); tolerances are relative and dimensionless;
// times are in seconds.
//
// find_threshold's statuses:
//   converged          the bracket [unstable, stable] is within the tolerance
//   stable_at_lower    it stands at the floor: no change from falling to
//                      standing in range (unstable is NaN)
//   unstable_at_upper  it falls at the ceiling (stable is NaN)
//   max_analyses       the evaluation budget ran out; the bracket so far
//                      (either end NaN if not met yet)
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "core/enum_names.hpp"
#include "analysis/interior_point.hpp"

namespace ashlar {

// ----------------------------------------------------------------------------
// The smallest value at which a model stands.

enum class ThresholdStatus { converged, stable_at_lower, unstable_at_upper, max_analyses };
inline constexpr EnumNames<ThresholdStatus, 4> kThresholdStatusNames{
    {{{ThresholdStatus::converged, "converged"},
      {ThresholdStatus::stable_at_lower, "stable_at_lower"},
      {ThresholdStatus::unstable_at_upper, "unstable_at_upper"},
      {ThresholdStatus::max_analyses, "max_analyses"}}}};

// "converged", "stable_at_lower", "unstable_at_upper" or "max_analyses".
const char* threshold_status_name(ThresholdStatus status);

// Requires floor <= start <= ceiling.
struct ThresholdSettings {
  double bracket_tolerance = 1e-6;  // final bracket width relative to its upper end, in (0, 1)
  double floor = 0.0;               // smallest value tried
  double ceiling = std::numeric_limits<double>::infinity();  // largest value tried
  int max_evaluations = 200;  // calls of the criterion, the first included
};

// The range a search for a model's geometric factor of safety tries when
// not told, relative to the as-built value `start`: down to a millionth of
// it (a model that still stands there has a factor of a million or more,
// as good as unbounded, and no generator is asked for a zero or negative
// value), and up to a thousand times it.
constexpr double kThresholdFloorFraction = 1e-6;
constexpr double kThresholdCeilingMultiple = 1e3;

// The figures of the equilibrium analysis behind a verdict, kept for the
// history.
struct VerdictAnalysis {
  double infeasibility = 0.0;
  int iterations = 0;
  SolverStatus status = SolverStatus::converged;
};

struct ThresholdVerdict {
  bool stands = false;
  std::optional<VerdictAnalysis> analysis;  // empty when the criterion ran no analysis
};

struct ThresholdProbe {
  double value = 0.0;
  ThresholdVerdict verdict;
  double seconds = 0.0;  // of the criterion, building the model included
};

// The last bracket: `unstable` falls and `stable` stands; NaN where no such
// value was met.
struct Threshold {
  ThresholdStatus status = ThresholdStatus::converged;
  double unstable = std::numeric_limits<double>::quiet_NaN();
  double stable = std::numeric_limits<double>::quiet_NaN();
  int evaluations = 0;
  std::vector<ThresholdProbe> history;  // one per evaluation, in order
};

// The smallest value in [floor, ceiling] at which the criterion says the
// model stands, for a criterion that is monotone in the value (what stands
// at v stands above v; otherwise this finds one change from falling to
// standing). From `start` it halves while the model stands, or doubles
// while it falls, to bracket the change, never past floor or ceiling; then
// it bisects the bracket until its width is `tolerance` of its upper end.
Threshold find_threshold(double start, const ThresholdSettings& settings,
                         const std::function<ThresholdVerdict(double)>& criterion);

// ----------------------------------------------------------------------------
// The coarsest count whose answer has settled.

struct RefineSettings {
  double tolerance = 0.01;  // relative
  int start = 4;            // first count, >= 1 and <= max
  double growth = 2.0;      // from one count to the next, >= 1
  int max = 1024;           // finest count evaluated
  int confirm = 2;          // consecutive settled changes needed to stop, >= 1: one agreement can be luck
};

struct RefineStep {
  int count = 0;
  double value = 0.0;
  // |previous step's value - value| / |value| (infinite when only the value
  // is zero); NaN for the first step.
  double change = std::numeric_limits<double>::quiet_NaN();
  double seconds = 0.0;  // of the metric, building the model included
};

struct Refinement {
  std::vector<RefineStep> history;
  std::size_t adequate = 0;  // index in history of the count to use
  bool converged = false;
};

// Evaluates metric(count) for count = start, then max(n + 1, ceil(n *
// growth)) capped at max, until `confirm` consecutive changes are within
// the tolerance (converged) or max was evaluated. The adequate count is the
// coarsest from which every value, its own included, is within the
// tolerance of the finest: counts are not monotone (hinges form only at
// joints), so a lucky coarse count followed by a poor one does not qualify.
// Unconverged, the finest count is the only one known to be adequate.
Refinement refine_count(const RefineSettings& settings, const std::function<double(int)>& metric);

}  // namespace ashlar
