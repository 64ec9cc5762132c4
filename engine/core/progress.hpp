// How far a long computation has got, for a progress line: called on the
// calling thread with (units done, units in all), first with 0 done, then
// as units are done. The units are the computation's own: blocks for the
// per-block analyses (load capacity, important weights), digits of the
// bracket for the searches (friction demand, the kinematic load factor and
// friction demand: BracketProgress), the solver's iterations for a
// single program (load factor), whose count is not known ahead: its total
// is kTotalUnknown.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

namespace ashlar {

using ProgressCount = std::function<void(int done, int total)>;
constexpr int kTotalUnknown = -1;

// A search's progress as the digits of its bracket [low, high] (-log10 of
// its width relative to high) against the tolerance's: its count of steps
// is not known ahead, its digits only grow. tolerance in (0, 1).
class BracketProgress {
public:
  BracketProgress(double tolerance, ProgressCount progress)
      : tolerance_(tolerance),
        digits_(std::max(1, static_cast<int>(std::ceil(-std::log10(tolerance))))),
        progress_(std::move(progress)) {}

  // high may be infinite (no digit yet).
  void tell(double low, double high) const {
    if (!progress_) return;
    const double width = std::isfinite(high) && high > 0.0 ? (high - low) / high : 1.0;
    // Done is all digits, though the width's logarithm may round below them.
    const int reached = width <= tolerance_ ? digits_ : static_cast<int>(std::floor(-std::log10(width)));
    progress_(std::clamp(reached, 0, digits_), digits_);
  }

private:
  double tolerance_;
  int digits_;
  ProgressCount progress_;
};

}  // namespace ashlar
