// Layout shared by the charts PLplot draws (io/chart.cpp, io/chart_map.cpp):
// sizes that follow the image, text widths estimated before PLplot draws.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "io/color.hpp"

namespace ashlar {

// About the advance of an average character of DejaVu Sans (lowercase,
// digits, spaces), in font sizes: to leave room for text before PLplot has
// drawn it.
constexpr double kCharacterWidth = 0.5;

// Text, ticks and the frame; grid lines.
inline const Rgb kTextColor{0.15, 0.15, 0.15};
inline const Rgb kGridColor{0.87, 0.87, 0.87};

// Sizes that follow the image's smaller side (px).
struct ChartMetrics {
  double line;       // unit of line widths: 1 px for a smaller side of 600 px
  double font;       // title and axis labels: 15 px at 600 px, at least 11
  double tick_font;  // tick labels and legend
  double margin;     // around everything

  ChartMetrics(int width, int height) {
    const double side = std::min(width, height);
    line = std::max(0.75, side / 600.0);
    font = std::max(11.0, side / 40.0);
    tick_font = 0.85 * font;
    margin = std::max(6.0, 0.025 * side);
  }
};

// The widest tick label PLplot writes on a linear axis over [lo, hi], in
// characters: its step is 1, 2 or 5 times a power of ten (pldtik), its
// labels have the step's decimals, and past 5 digits it writes the values
// over a common power of ten, shown once at the axis's end.
inline int linear_label_characters(double lo, double hi) {
  const double largest = std::max(std::abs(lo), std::abs(hi));
  if (largest >= 1e5 || largest < 1e-4) return 5;
  const int decimals = std::max(0, 1 - static_cast<int>(std::floor(std::log10(hi - lo))));
  const int digits = std::max(1, static_cast<int>(std::floor(std::log10(largest))) + 1);
  return digits + (decimals > 0 ? decimals + 1 : 0) + (lo < 0 ? 1 : 0);
}

// The power of ten a linear axis over [lo, hi] writes its values over:
// the largest value's, where that is below 0.01 or from 1e5 up; else 0.
inline int axis_power(double lo, double hi) {
  const double largest = std::max(std::abs(lo), std::abs(hi));
  if (!(largest > 0.0) || (largest >= 1e-2 && largest < 1e5)) return 0;
  return static_cast<int>(std::floor(std::log10(largest)));
}

}  // namespace ashlar
