// Tick values and labels for chart axes: steps of 1, 2 or 5 times a power
// of ten on linear axes, decades (or 1, 2 and 5 times them) on log axes.
#pragma once

#include <string>
#include <vector>

namespace ashlar {

struct AxisTicks {
  std::vector<double> values;       // labelled ticks, increasing, inside the range
  std::vector<std::string> labels;  // one per value, UTF-8 ("−" for minus, "2×10⁻⁵")
  // Labels show value / 10^power: a factor common to the axis, to be
  // written once (e.g. with the axis label); 0 for the values themselves.
  int power = 0;
  // Unlabelled ticks of a log axis whose every decade is labelled: 2, 3, ...,
  // 9 times each power of ten inside the range; empty otherwise.
  std::vector<double> minor;
};

// The power of ten that linear_ticks divides its labels by over [lo, hi]:
// that of the larger of |lo| and |hi| when it is 1e6 or more, or below 1e-4
// (and not 0); 0 otherwise.
int linear_label_power(double lo, double hi);

// Ticks k × step inside [lo, hi] (finite, lo < hi) for the smallest step of
// 1, 2 or 5 × 10^n that gives at most max_count (>= 2) of them, and at least
// one: e.g. [0.073, 0.207] with 8 -> 0.08, 0.10, ..., 0.20. Values are the
// decimal numbers they stand for (4 × 0.02 == 0.08 exactly). Labels show
// value / 10^power (power = linear_label_power(lo, hi)) with the decimals of
// the step: "0.08", "0.10"; [-5e6, 1.5e7] with 5 -> "−0.5", "0.0", ...,
// "1.5" and power 7. Throws InvalidArgument otherwise.
AxisTicks linear_ticks(double lo, double hi, int max_count);

// Ticks for a log axis over [lo, hi] (finite, 0 < lo < hi), at most
// max_count (>= 2):
// - when three or more powers of ten lie inside, those of every 1, 2, 5,
//   10, 20, ... decades so that at most max_count do (0.001, 0.01, ..., or
//   10⁻¹⁰, 10⁻⁵, 10⁰);
// - else 1, 2 and 5 times powers of ten, when at least two and at most
//   max_count lie inside ([3, 40]: 5, 10, 20);
// - else the two powers of ten inside, if there are two;
// - else linear_ticks(lo, hi, max_count) (under a decade, e.g. [1.2, 1.8]).
// Minor ticks go with labelled powers of ten that skip no decade.
// Labels are plain numbers with the digits each needs ("0.002", "20") while
// every tick lies in [1e-4, 1e6), powers of ten otherwise ("10⁻⁶", "2×10⁻⁵"),
// with power 0, except for linear ticks. Throws InvalidArgument otherwise.
AxisTicks log_ticks(double lo, double hi, int max_count);

// "10" and the exponent in superscript digits: "10⁷", "10⁻⁵".
std::string power_of_ten_text(int exponent);

}  // namespace ashlar
