// Charts of (x, y) series for parametric studies: lines, points or steps over
// linear or log axes, with ticks, a grid, a legend, a title and axis labels,
// drawn by PLplot. Format from the extension: .png (sizes in px), .svg or
// .pdf (sizes in pt).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/types.hpp"
#include "io/color.hpp"
#include "io/image_rect.hpp"

namespace ashlar {

enum class ChartKind {
  lines,        // each series a polyline through its points
  points,       // a marker at each point
  linespoints,  // both
  steps,        // each value holds until the next x: horizontal, then vertical
};

// The kind called `name`: "lines", "points", "linespoints" or "steps".
// Throws InvalidArgument naming them and "map" (io/chart_map.hpp) otherwise.
ChartKind chart_kind(const std::string& name);

struct ChartSeries {
  std::string name;          // its legend entry, e.g. "n = 16"
  std::vector<Vec2> points;  // (x, y) in data units, joined in this order
};

struct ChartSpec {
  // Series k is drawn in chart_series_color(k), with the k-th marker shape.
  // At least one point in all, every coordinate finite; a series without
  // points still has its legend entry.
  std::vector<ChartSeries> series;
  ChartKind kind = ChartKind::linespoints;
  std::string title;                  // above the plot; none when empty
  std::string x_label, y_label;       // under the x axis, along the y axis; none when empty
  bool log_x = false, log_y = false;  // log axes take values > 0 only
  // Axes of booleans (0 and 1, not on a log axis): ticks at 0 and 1 only,
  // labelled "false" and "true".
  bool x_boolean = false, y_boolean = false;
  // An axis's ends (lo < hi, finite; > 0 on a log axis) instead of the
  // data's padded range; what lies outside is cut off.
  std::optional<std::pair<double, double>> x_range, y_range;
  int width = 900, height = 600;      // px for .png, pt for .svg and .pdf; each in [200, 16384]
};

// The colour of series k (>= 0): the Okabe-Ito colour-blind-safe palette
// (blue, vermillion, bluish green, reddish purple, orange, sky blue, black,
// yellow), repeated with dashed lines after 8 series and dotted after 16.
Rgb chart_series_color(int k);

// One axis as drawn: the data values at the plot area's edges.
struct ChartAxis {
  // The data's range widened by 4 % of it on each side (of its log10 on a
  // log axis), so that no point sits on the frame. A single value v gets
  // v ± 5 % of |v| (± 0.5 for 0), or a factor 10^0.25 on a log axis. Or
  // the spec's range, when it gives one.
  double lo = 0.0, hi = 1.0;
  bool log = false;

  // Where value lies from lo (0) to hi (1): linear in value, or in log10.
  double fraction(double value) const;
};

// Where draw_chart put the plot: the frame in the image (px, pt for vector
// formats; y down) and the axes' ranges.
struct ChartFrame {
  ImageRect plot;
  ChartAxis x, y;

  // Image position of a data point (x, y).
  Vec2 to_image(const Vec2& data) const;
};

// The axes draw_chart uses for spec. Throws InvalidArgument for a size
// outside [200, 16384], no point, a non-finite coordinate or a value <= 0 on
// a log axis (naming the series and the point), or a bad range.
std::pair<ChartAxis, ChartAxis> chart_axes(const ChartSpec& spec);

// Draws the chart with PLplot and writes it atomically to path: grid lines
// at the ticks, the series, the framed axes with their tick labels (PLplot's:
// 1, 2 or 5 times a power of ten apart; log axes at decades with minor ticks
// at 2-9), the axis labels, the title and, with two series or more, a legend
// right of the plot. Returns where the plot went. Throws InvalidArgument for
// an unknown extension (not .png, .svg or .pdf) or a spec that chart_axes
// rejects, IoError when PLplot fails or the file cannot be written.
// Safe to call from several threads: PLplot's state is global, so charts
// are drawn one at a time.
ChartFrame draw_chart(const std::string& path, const ChartSpec& spec);

}  // namespace ashlar
