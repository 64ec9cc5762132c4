// Charts of (x, y) series for parametric studies: lines, points or steps over
// linear or log axes, with ticks, a grid, a legend, a title and axis labels,
// drawn with cairo. Format from the extension: .png (sizes in px), .svg or
// .pdf (sizes in pt). Image coordinates have x to the right and y down.
#pragma once

#include <string>
#include <vector>

#include "core/types.hpp"
#include "io/axis_ticks.hpp"
#include "io/image_rect.hpp"
#include "io/color.hpp"

namespace ashlar {

enum class ChartKind {
  lines,        // each series a polyline through its points
  points,       // a marker at each point
  linespoints,  // both
  steps,        // each value holds until the next x: horizontal, then vertical
};

// The kind called `name`: "lines", "points", "linespoints" or "steps".
// Throws InvalidArgument naming them otherwise.
ChartKind chart_kind(const std::string& name);

struct ChartSeries {
  std::string name;          // its legend entry, e.g. "n = 16"
  std::vector<Vec2> points;  // (x, y) in data units, joined in this order
};

struct ChartSpec {
  // Series k is drawn in chart_series_color(k), with the k-th marker shape.
  // At least one point in all, every coordinate finite.
  std::vector<ChartSeries> series;
  ChartKind kind = ChartKind::linespoints;
  std::string title;  // above the plot; none when empty
  // Under the x axis, along the y axis; none when empty. An axis whose tick
  // labels show value / 10^n (AxisTicks::power) gets " (×10ⁿ)" after it.
  std::string x_label, y_label;
  bool log_x = false, log_y = false;  // log axes take values > 0 only
  int width = 900, height = 600;      // px for .png, pt for .svg and .pdf; each in [200, 16384]
};

// One axis of a chart: the data values at its ends and its ticks.
struct ChartAxis {
  // Values at the plot area's edges (left/bottom, right/top): the data's
  // range widened by 4 % of it on each side (of its log10 on a log axis),
  // so that no point sits on the frame. A single value v gets v ± 5 % of
  // |v| (± 0.5 for 0), or a factor 10^0.25 on a log axis.
  double lo = 0.0, hi = 1.0;
  bool log = false;
  AxisTicks ticks;  // linear_ticks or log_ticks of [lo, hi], as many as fit

  // Where value lies from lo (0) to hi (1): linear in value, or in log10.
  double fraction(double value) const;
};

// Where a chart puts things (px, pt for vector formats).
struct ChartLayout {
  ImageRect plot;  // the plot area, framed; x.lo on its left, y.lo at its bottom
  ChartAxis x, y;
  // The legend's box, right of the plot; zero width and height when there
  // is no legend (one series only: the y label names it).
  ImageRect legend;

  // Image position of a data point (x, y).
  Vec2 to_image(const Vec2& data) const;
};

// The layout draw_chart uses for spec. Throws InvalidArgument for a size
// outside [200, 16384], no point, a non-finite coordinate or a value <= 0 on
// a log axis, naming the series and the point.
ChartLayout chart_layout(const ChartSpec& spec);

// The colour of series k (>= 0): the Okabe-Ito colour-blind-safe palette
// (blue, vermillion, bluish green, reddish purple, orange, sky blue, black,
// yellow), repeated with dashed lines after 8 series and dotted after 16.
Rgb chart_series_color(int k);

// Draws the chart and writes it atomically to path: grid lines at the ticks,
// the series (clipped to the plot area), the framed axes with their tick
// labels, the axis labels, the title and the legend. Throws InvalidArgument
// for an unknown extension (not .png, .svg or .pdf) or a spec that
// chart_layout rejects, IoError when the file cannot be written.
void draw_chart(const std::string& path, const ChartSpec& spec);

}  // namespace ashlar
