// Charts with cairo. The layout is decided before anything is drawn, with
// text measured on a scratch context, so that chart_layout tells exactly
// where draw_chart puts things. Sizes that depend on the image (margins,
// fonts, line widths) follow its smaller side, so that a larger image looks
// the same, only sharper.
#include "io/chart.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/error.hpp"
#include "io/cairo_canvas.hpp"

namespace ashlar {
namespace {

constexpr int kMinImageSize = 200;
constexpr int kMaxImageSize = 16384;
// Room around the data on each axis, as a fraction of its range.
constexpr double kAxisPadding = 0.04;
// A single value v is shown over v ± this fraction of |v| (± 0.5 for 0), or
// over v / 10^0.25 to v × 10^0.25 on a log axis.
constexpr double kSingleValueHalfRange = 0.05;
constexpr double kSingleValueHalfDecades = 0.25;
// Labelled ticks on an axis: at most this many.
constexpr int kMostTicks = 10;
// A legend takes at most this fraction of the image's width; longer names
// shrink its text.
constexpr double kLegendWidthShare = 0.35;
constexpr int kMarkerShapes = 5;

// Okabe & Ito (2008), "Color universal design", in an order whose first
// colours differ most, yellow last (it is faint on white).
const Rgb kPalette[] = {{0.0, 114 / 255.0, 178 / 255.0},          // blue
                        {213 / 255.0, 94 / 255.0, 0.0},           // vermillion
                        {0.0, 158 / 255.0, 115 / 255.0},          // bluish green
                        {204 / 255.0, 121 / 255.0, 167 / 255.0},  // reddish purple
                        {230 / 255.0, 159 / 255.0, 0.0},          // orange
                        {86 / 255.0, 180 / 255.0, 233 / 255.0},   // sky blue
                        {0.0, 0.0, 0.0},                          // black
                        {240 / 255.0, 228 / 255.0, 66 / 255.0}};  // yellow
constexpr int kPaletteSize = sizeof kPalette / sizeof kPalette[0];

const Rgb kTextColor{0.1, 0.1, 0.1};
const Rgb kFrameColor{0.25, 0.25, 0.25};
const Rgb kGridColor{0.87, 0.87, 0.87};
const Rgb kMinorGridColor{0.94, 0.94, 0.94};
const Rgb kLegendBorder{0.75, 0.75, 0.75};

// Sizes that follow the image's smaller side (px).
struct ChartMetrics {
  double line;         // unit of line widths: 1 px for a smaller side of 600 px
  double font;         // title and axis labels: 15 px at 600 px, at least 11
  double tick_font;    // tick labels and legend
  double margin;       // around everything
  double tick_length;  // outward from the frame
  double gap;          // between a tick and its label
  double marker;       // marker radius

  ChartMetrics(int width, int height) {
    const double side = std::min(width, height);
    line = std::max(0.75, side / 600.0);
    font = std::max(11.0, side / 40.0);
    tick_font = 0.85 * font;
    margin = std::max(6.0, 0.025 * side);
    tick_length = 0.45 * tick_font;
    gap = 0.4 * tick_font;
    marker = 0.3 * tick_font;
  }
};

// The layout and what painting needs besides it.
struct ChartGeometry {
  ChartLayout layout;
  ChartMetrics metrics;
  double legend_font = 0.0;
  double legend_row = 0.0;     // height of a legend entry
  double legend_sample = 0.0;  // length of the line sample in a legend entry
};

// ---------------------------------------------------------------------------
// Checks and ranges

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

void check_spec(const ChartSpec& spec) {
  for (const int size : {spec.width, spec.height}) {
    if (size < kMinImageSize || size > kMaxImageSize) {
      throw InvalidArgument("chart: width and height must lie in [" +
                            std::to_string(kMinImageSize) + ", " + std::to_string(kMaxImageSize) +
                            "], got " + std::to_string(spec.width) + " x " +
                            std::to_string(spec.height));
    }
  }
  bool any_point = false;
  for (const ChartSeries& series : spec.series) {
    for (size_t k = 0; k < series.points.size(); ++k) {
      const Vec2& p = series.points[k];
      const auto where = [&] {
        return "series '" + series.name + "' point " + std::to_string(k + 1) +
               " (x = " + number_text(p.x()) + ", y = " + number_text(p.y()) + ")";
      };
      if (!p.allFinite()) throw InvalidArgument("chart: " + where() + " is not finite");
      if ((spec.log_x && !(p.x() > 0.0)) || (spec.log_y && !(p.y() > 0.0))) {
        throw InvalidArgument(std::string("chart: ") +
                              (spec.log_x && !(p.x() > 0.0) ? "log_x" : "log_y") +
                              " takes values > 0 only, got " + where());
      }
      any_point = true;
    }
  }
  if (!any_point) throw InvalidArgument("chart: nothing to plot: no series has a point");
}

// The axis over data values from lo to hi (lo <= hi), padded.
ChartAxis padded_axis(double lo, double hi, bool log) {
  ChartAxis axis;
  axis.log = log;
  // Work on log10 of the values on a log axis.
  const double a = log ? std::log10(lo) : lo, b = log ? std::log10(hi) : hi;
  double from, to;
  // Ranges below double resolution count as a single value.
  if (b - a <= 1e-12 * std::max(std::abs(a), std::abs(b))) {
    const double half =
        log ? kSingleValueHalfDecades : (a == 0.0 ? 0.5 : kSingleValueHalfRange * std::abs(a));
    from = a - half;
    to = b + half;
  } else {
    from = a - kAxisPadding * (b - a);
    to = b + kAxisPadding * (b - a);
  }
  axis.lo = log ? std::pow(10.0, from) : from;
  axis.hi = log ? std::pow(10.0, to) : to;
  return axis;
}

AxisTicks axis_ticks(const ChartAxis& axis, int max_count) {
  return axis.log ? log_ticks(axis.lo, axis.hi, max_count)
                  : linear_ticks(axis.lo, axis.hi, max_count);
}

double widest(cairo_t* cr, const std::vector<std::string>& texts) {
  double width = 0.0;
  for (const std::string& text : texts) width = std::max(width, text_width(cr, text));
  return width;
}

// x ticks: as many as fit (at most kMostTicks, about one per five label
// heights), then fewer while two neighbouring labels come closer than a
// label height.
AxisTicks fitted_x_ticks(cairo_t* cr, const ChartLayout& layout, const ChartMetrics& metrics) {
  const int most =
      std::clamp(static_cast<int>(layout.plot.width / (5 * metrics.tick_font)), 2, kMostTicks);
  AxisTicks ticks;
  for (int count = most; count >= 2; --count) {
    ticks = axis_ticks(layout.x, count);
    bool fits = true;
    for (size_t k = 0; k + 1 < ticks.values.size(); ++k) {
      const double apart = layout.plot.width * (layout.x.fraction(ticks.values[k + 1]) -
                                                layout.x.fraction(ticks.values[k]));
      const double needed =
          (text_width(cr, ticks.labels[k]) + text_width(cr, ticks.labels[k + 1])) / 2 +
          metrics.tick_font;
      fits = fits && apart >= needed;
    }
    if (fits) break;
  }
  return ticks;
}

// An axis label with the axis's common factor: "load (×10⁶)", or the factor
// alone without a label.
std::string axis_title(const std::string& label, const AxisTicks& ticks) {
  if (ticks.power == 0) return label;
  const std::string factor = "\u00d7" + power_of_ten_text(ticks.power);
  return label.empty() ? factor : label + " (" + factor + ")";
}

// Long tick labels or legend names can leave a small image no plot.
void check_room(double plot_size, const ChartSpec& spec) {
  if (!(plot_size > 0)) {
    throw InvalidArgument("chart: no room left for the plot in " + std::to_string(spec.width) +
                          " x " + std::to_string(spec.height) +
                          "; make the image larger or the labels shorter");
  }
}

ChartGeometry chart_geometry(const ChartSpec& spec) {
  check_spec(spec);
  ChartGeometry geometry{ChartLayout{}, ChartMetrics(spec.width, spec.height)};
  const ChartMetrics& m = geometry.metrics;
  ChartLayout& layout = geometry.layout;
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const ChartSeries& series : spec.series) {
    for (const Vec2& p : series.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  layout.x = padded_axis(lo.x(), hi.x(), spec.log_x);
  layout.y = padded_axis(lo.y(), hi.y(), spec.log_y);
  const CairoContext measure = measuring_context();
  cairo_t* cr = measure.get();

  // Top to bottom: title, plot, x tick labels, x label.
  ImageRect& plot = layout.plot;
  plot.top = m.margin + (spec.title.empty() ? 0.6 * m.tick_font : 2.0 * m.font);
  // The x ticks are not known yet, but their common factor is.
  const bool x_title = !spec.x_label.empty() || linear_label_power(layout.x.lo, layout.x.hi) != 0;
  const double below_plot =
      m.tick_length + m.gap + 1.1 * m.tick_font + (x_title ? m.gap + 1.4 * m.font : 0.0);
  plot.height = spec.height - m.margin - below_plot - plot.top;
  check_room(plot.height, spec);
  const int most_y_ticks =
      std::clamp(static_cast<int>(plot.height / (3.2 * m.tick_font)), 2, kMostTicks);
  layout.y.ticks = axis_ticks(layout.y, most_y_ticks);

  // Left to right: y label, y tick labels, plot, legend.
  set_font(cr, m.tick_font);
  plot.left = m.margin + (axis_title(spec.y_label, layout.y.ticks).empty() ? 0.0 : 1.5 * m.font) +
              widest(cr, layout.y.ticks.labels) + m.gap + m.tick_length;
  double right_end = spec.width - m.margin;
  if (spec.series.size() >= 2) {
    std::vector<std::string> names;
    for (const ChartSeries& series : spec.series) names.push_back(series.name);
    // Sizes in units of the legend's font: padding 0.6, a 2.4 long sample,
    // 0.5 before the name, rows 1.5 high.
    const double name_width = widest(cr, names) / m.tick_font;
    const double width = 0.6 + 2.4 + 0.5 + name_width + 0.6;
    const double height = 2 * 0.6 + 1.5 * spec.series.size();
    geometry.legend_font =
        m.tick_font * std::min({1.0, kLegendWidthShare * spec.width / (width * m.tick_font),
                                plot.height / (height * m.tick_font)});
    geometry.legend_row = 1.5 * geometry.legend_font;
    geometry.legend_sample = 2.4 * geometry.legend_font;
    layout.legend.width = width * geometry.legend_font;
    layout.legend.height = height * geometry.legend_font;
    layout.legend.left = right_end - layout.legend.width;
    layout.legend.top = plot.top;
    right_end = layout.legend.left - m.font;
  }
  plot.width = right_end - plot.left;
  layout.x.ticks = fitted_x_ticks(cr, layout, m);
  // The last x tick label may reach past the plot's right edge: narrow the
  // plot so that it stays clear of the legend or the image's edge.
  const double overhang = plot.left + plot.width * layout.x.fraction(layout.x.ticks.values.back()) +
                          text_width(cr, layout.x.ticks.labels.back()) / 2 - right_end;
  if (overhang > 0) {
    plot.width -= overhang;
    layout.x.ticks = fitted_x_ticks(cr, layout, m);
  }
  check_room(plot.width, spec);
  return geometry;
}

// ---------------------------------------------------------------------------
// Painting

void line_between(cairo_t* cr, double x0, double y0, double x1, double y1) {
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
}

// Image x of an x axis value, image y of a y axis value.
double image_x(const ChartLayout& layout, double value) {
  return layout.plot.left + layout.plot.width * layout.x.fraction(value);
}
double image_y(const ChartLayout& layout, double value) {
  return layout.plot.bottom() - layout.plot.height * layout.y.fraction(value);
}

void paint_grid(cairo_t* cr, const ChartLayout& layout, const ChartMetrics& m) {
  const ImageRect& plot = layout.plot;
  const auto lines = [&](const std::vector<double>& x_values, const std::vector<double>& y_values,
                         const Rgb& color, double width) {
    for (const double value : x_values) {
      const double x = image_x(layout, value);
      line_between(cr, x, plot.top, x, plot.bottom());
    }
    for (const double value : y_values) {
      const double y = image_y(layout, value);
      line_between(cr, plot.left, y, plot.right(), y);
    }
    set_color(cr, color);
    cairo_set_line_width(cr, width);
    cairo_stroke(cr);
  };
  lines(layout.x.ticks.minor, layout.y.ticks.minor, kMinorGridColor, 0.7 * m.line);
  lines(layout.x.ticks.values, layout.y.ticks.values, kGridColor, m.line);
}

// Marker k (a circle, square, triangle, diamond or upside-down triangle of
// about equal area) centred at p, as a path.
void marker_path(cairo_t* cr, int k, const Vec2& p, double radius) {
  const double x = p.x(), y = p.y();
  switch (k % kMarkerShapes) {
    case 0:
      cairo_new_sub_path(cr);
      cairo_arc(cr, x, y, radius, 0.0, 2 * kPi);
      return;
    case 1: {
      const double half = 0.89 * radius;
      cairo_rectangle(cr, x - half, y - half, 2 * half, 2 * half);
      return;
    }
    case 2:
    case 4: {
      const double r = 1.25 * radius, up = (k % kMarkerShapes == 2) ? -1.0 : 1.0;
      cairo_move_to(cr, x, y + up * r);
      cairo_line_to(cr, x + 0.866 * r, y - up * 0.5 * r);
      cairo_line_to(cr, x - 0.866 * r, y - up * 0.5 * r);
      cairo_close_path(cr);
      return;
    }
    default: {
      const double r = 1.25 * radius;
      cairo_move_to(cr, x, y - r);
      cairo_line_to(cr, x + r, y);
      cairo_line_to(cr, x, y + r);
      cairo_line_to(cr, x - r, y);
      cairo_close_path(cr);
      return;
    }
  }
}

// Solid for the first 8 series, then dashed, then dotted.
void set_series_line(cairo_t* cr, int k, const ChartMetrics& m) {
  cairo_set_line_width(cr, 2.0 * m.line);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  const int style = (k / kPaletteSize) % 3;
  const double dashed[] = {6 * m.line, 3.5 * m.line};
  const double dotted[] = {0.0, 3.5 * m.line};  // round caps make the dots
  cairo_set_line_cap(cr, style == 2 ? CAIRO_LINE_CAP_ROUND : CAIRO_LINE_CAP_BUTT);
  cairo_set_dash(cr, style == 1 ? dashed : dotted, style == 0 ? 0 : 2, 0.0);
}

void paint_markers(cairo_t* cr, int k, const std::vector<Vec2>& points, double radius,
                   const ChartMetrics& m) {
  cairo_set_dash(cr, nullptr, 0, 0.0);
  for (const Vec2& p : points) marker_path(cr, k, p, radius);
  set_color(cr, chart_series_color(k));
  cairo_fill_preserve(cr);
  // A thin white rim keeps overlapping markers apart.
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_set_line_width(cr, 0.6 * m.line);
  cairo_stroke(cr);
}

bool has_lines(ChartKind kind) { return kind != ChartKind::points; }
bool has_markers(ChartKind kind) {
  return kind == ChartKind::points || kind == ChartKind::linespoints;
}

void paint_series(cairo_t* cr, const ChartSpec& spec, const ChartLayout& layout,
                  const ChartMetrics& m) {
  cairo_save(cr);
  cairo_rectangle(cr, layout.plot.left, layout.plot.top, layout.plot.width, layout.plot.height);
  cairo_clip(cr);
  for (size_t k = 0; k < spec.series.size(); ++k) {
    std::vector<Vec2> points;
    for (const Vec2& p : spec.series[k].points) points.push_back(layout.to_image(p));
    if (points.empty()) continue;
    const int index = static_cast<int>(k);
    if (has_lines(spec.kind) && points.size() >= 2) {
      cairo_move_to(cr, points[0].x(), points[0].y());
      for (size_t i = 1; i < points.size(); ++i) {
        if (spec.kind == ChartKind::steps) cairo_line_to(cr, points[i].x(), points[i - 1].y());
        cairo_line_to(cr, points[i].x(), points[i].y());
      }
      set_series_line(cr, index, m);
      set_color(cr, chart_series_color(index));
      cairo_stroke(cr);
    }
    // A lone point has no line to show it.
    if (has_markers(spec.kind) || points.size() == 1) paint_markers(cr, index, points, m.marker, m);
  }
  cairo_restore(cr);
}

void paint_axes(cairo_t* cr, const ChartLayout& layout, const ChartMetrics& m) {
  const ImageRect& plot = layout.plot;
  set_color(cr, kFrameColor);
  cairo_set_line_width(cr, m.line);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_SQUARE);
  cairo_rectangle(cr, plot.left, plot.top, plot.width, plot.height);
  cairo_stroke(cr);
  // Ticks point out of the frame; minor ones are shorter.
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
  const auto x_ticks = [&](const std::vector<double>& values, double length) {
    for (const double value : values) {
      const double x = image_x(layout, value);
      line_between(cr, x, plot.bottom(), x, plot.bottom() + length);
    }
  };
  const auto y_ticks = [&](const std::vector<double>& values, double length) {
    for (const double value : values) {
      const double y = image_y(layout, value);
      line_between(cr, plot.left, y, plot.left - length, y);
    }
  };
  x_ticks(layout.x.ticks.values, m.tick_length);
  x_ticks(layout.x.ticks.minor, 0.6 * m.tick_length);
  y_ticks(layout.y.ticks.values, m.tick_length);
  y_ticks(layout.y.ticks.minor, 0.6 * m.tick_length);
  cairo_stroke(cr);

  set_color(cr, kTextColor);
  set_font(cr, m.tick_font);
  const double label_middle = plot.bottom() + m.tick_length + m.gap + 0.5 * m.tick_font;
  for (size_t k = 0; k < layout.x.ticks.values.size(); ++k) {
    show_text(cr, layout.x.ticks.labels[k], image_x(layout, layout.x.ticks.values[k]), label_middle,
              0.5);
  }
  for (size_t k = 0; k < layout.y.ticks.values.size(); ++k) {
    show_text(cr, layout.y.ticks.labels[k], plot.left - m.tick_length - m.gap,
              image_y(layout, layout.y.ticks.values[k]), 1.0);
  }
}

// Sets the font to `size`, smaller if need be for text to fit in `room`.
void set_font_to_fit(cairo_t* cr, const std::string& text, double size, double room) {
  set_font(cr, size);
  const double needed = text_width(cr, text);
  if (needed > room) set_font(cr, size * room / needed);
}

void paint_labels(cairo_t* cr, const ChartSpec& spec, const ChartLayout& layout,
                  const ChartMetrics& m) {
  const ImageRect& plot = layout.plot;
  set_color(cr, kTextColor);
  if (!spec.title.empty()) {
    // Centred over the plot, moved in to stay inside the image.
    const double room = spec.width - 2 * m.margin;
    set_font_to_fit(cr, spec.title, 1.2 * m.font, room);
    const double half = text_width(cr, spec.title) / 2;
    const double middle =
        std::clamp(plot.left + plot.width / 2, m.margin + half, spec.width - m.margin - half);
    show_text(cr, spec.title, middle, m.margin + 0.7 * m.font, 0.5);
  }
  const std::string x_title = axis_title(spec.x_label, layout.x.ticks);
  if (!x_title.empty()) {
    set_font_to_fit(cr, x_title, m.font, spec.width - 2 * m.margin);
    show_text(cr, x_title, plot.left + plot.width / 2, spec.height - m.margin - 0.6 * m.font, 0.5);
  }
  const std::string y_title = axis_title(spec.y_label, layout.y.ticks);
  if (!y_title.empty()) {
    set_font_to_fit(cr, y_title, m.font, spec.height - 2 * m.margin);
    cairo_save(cr);
    cairo_translate(cr, m.margin + 0.6 * m.font, plot.top + plot.height / 2);
    cairo_rotate(cr, -kPi / 2);
    show_text(cr, y_title, 0.0, 0.0, 0.5);
    cairo_restore(cr);
  }
}

void paint_legend(cairo_t* cr, const ChartSpec& spec, const ChartGeometry& geometry) {
  const ImageRect& box = geometry.layout.legend;
  if (box.width == 0.0) return;
  const ChartMetrics& m = geometry.metrics;
  const double font = geometry.legend_font;
  cairo_rectangle(cr, box.left, box.top, box.width, box.height);
  cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
  cairo_fill_preserve(cr);
  set_color(cr, kLegendBorder);
  cairo_set_line_width(cr, 0.8 * m.line);
  cairo_set_dash(cr, nullptr, 0, 0.0);
  cairo_stroke(cr);
  for (size_t k = 0; k < spec.series.size(); ++k) {
    const int index = static_cast<int>(k);
    const double middle = box.top + 0.6 * font + (k + 0.5) * geometry.legend_row;
    const double start = box.left + 0.6 * font, end = start + geometry.legend_sample;
    if (has_lines(spec.kind)) {
      line_between(cr, start, middle, end, middle);
      set_series_line(cr, index, m);
      set_color(cr, chart_series_color(index));
      cairo_stroke(cr);
    }
    if (has_markers(spec.kind)) {
      paint_markers(cr, index, {Vec2((start + end) / 2, middle)}, m.marker * font / m.tick_font, m);
    }
    set_color(cr, kTextColor);
    set_font(cr, font);
    show_text(cr, spec.series[k].name, end + 0.5 * font, middle, 0.0);
  }
}

}  // namespace

// ---------------------------------------------------------------------------
// Public functions

ChartKind chart_kind(const std::string& name) {
  if (name == "lines") return ChartKind::lines;
  if (name == "points") return ChartKind::points;
  if (name == "linespoints") return ChartKind::linespoints;
  if (name == "steps") return ChartKind::steps;
  throw InvalidArgument("chart: unknown kind '" + name +
                        "' (allowed: lines, points, linespoints, steps)");
}

double ChartAxis::fraction(double value) const {
  if (log) return std::log10(value / lo) / std::log10(hi / lo);
  return (value - lo) / (hi - lo);
}

Vec2 ChartLayout::to_image(const Vec2& data) const {
  return {image_x(*this, data.x()), image_y(*this, data.y())};
}

ChartLayout chart_layout(const ChartSpec& spec) { return chart_geometry(spec).layout; }

Rgb chart_series_color(int k) {
  if (k < 0) throw InvalidArgument("chart: series index must be >= 0, got " + std::to_string(k));
  return kPalette[k % kPaletteSize];
}

void draw_chart(const std::string& path, const ChartSpec& spec) {
  const ImageFormat format =
      image_format(path, {ImageFormat::png, ImageFormat::svg, ImageFormat::pdf}, "chart");
  const ChartGeometry geometry = chart_geometry(spec);
  render_file(path, format, spec.width, spec.height, "chart", [&](cairo_t* cr) {
    paint_grid(cr, geometry.layout, geometry.metrics);
    paint_series(cr, spec, geometry.layout, geometry.metrics);
    paint_axes(cr, geometry.layout, geometry.metrics);
    paint_labels(cr, spec, geometry.layout, geometry.metrics);
    paint_legend(cr, spec, geometry);
  });
}

}  // namespace ashlar
