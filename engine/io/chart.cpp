// Charts through PLplot (io/plplot_picture). Everything PLplot is given
// (coordinates, text, legend arrays, the layout) is prepared first, in
// plain C++; then one painter makes the PLplot calls.
//
// Sizes that depend on the image (margins, fonts, line widths) follow its
// smaller side, so that a larger image looks the same, only sharper.
#include "io/chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <tuple>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "io/image_format.hpp"
#include "io/chart_layout.hpp"
#include "io/plplot_picture.hpp"

namespace ashlar {
namespace {

constexpr int kMinImageSize = 200;
// Room around the data on each axis, as a fraction of its range.
constexpr double kAxisPadding = 0.04;
// A single value v is shown over v ± this fraction of |v| (± 0.5 for 0), or
// over v / 10^0.25 to v × 10^0.25 on a log axis.
constexpr double kSingleValueHalfRange = 0.05;
constexpr double kSingleValueHalfDecades = 0.25;
// A legend takes at most this fraction of the image's width; longer names
// shrink its text.
constexpr double kLegendWidthShare = 0.35;

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

// Marker k: a filled circle, square, triangle, diamond or upside-down
// triangle (DejaVu Sans has them all), drawn as text by the driver.
const char* const kMarkers[] = {"\u25cf", "\u25a0", "\u25b2", "\u25c6", "\u25bc"};
constexpr int kMarkerShapes = sizeof kMarkers / sizeof kMarkers[0];
// PLplot line styles (pllsty) of the first, second and third 8 series:
// solid, long dashes, short dashes.
constexpr PLINT kLineStyles[] = {1, 3, 2};

// The colour map 0 entries the chart sets; the palette follows them.
enum ColorIndex : PLINT { kBackground, kText, kGrid, kMinorGrid, kLegendBorder, kFirstSeries };
const Rgb kMinorGridColor{0.94, 0.94, 0.94};
const Rgb kLegendBorderColor{0.75, 0.75, 0.75};


// ---------------------------------------------------------------------------
// Checks and ranges

std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

void check_spec(const ChartSpec& spec) {
  check_image_size(spec.width, spec.height, kMinImageSize, "chart");
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

// The spec's range for an axis, checked, or the data's padded range.
ChartAxis chosen_axis(const std::optional<std::pair<double, double>>& range, double lo, double hi,
                      bool log, const char* name) {
  if (!range) return padded_axis(lo, hi, log);
  const auto [from, to] = *range;
  if (!std::isfinite(from) || !std::isfinite(to) || !(from < to) || (log && !(from > 0.0))) {
    throw InvalidArgument(std::string("chart: ") + name + "_range must be finite with lo < hi" +
                          (log ? " and lo > 0 (log axis)" : "") + ", got {" +
                          number_text(from) + ", " + number_text(to) + "}");
  }
  ChartAxis axis;
  axis.lo = from;
  axis.hi = to;
  axis.log = log;
  return axis;
}

// ---------------------------------------------------------------------------
// What PLplot is given

// A value along an axis in PLplot's world coordinates: log10 on log axes.
double world(double value, bool log) { return log ? std::log10(value) : value; }


struct PreparedSeries {
  std::vector<PLFLT> line_x, line_y;      // world coordinates, steps drawn out; empty: no line
  std::vector<PLFLT> marker_x, marker_y;  // empty: no markers
  PLINT color = kFirstSeries;
  PLINT style = 1;
  const char* marker = kMarkers[0];
};

// Everything the PLplot calls need, in their types; the strings and arrays
// outlive the calls.
struct PreparedChart {
  PLINT width = 0, height = 0;
  ChartMetrics metrics{kMinImageSize, kMinImageSize};
  ChartAxis x, y;
  // The plot area in normalised page coordinates (0 to 1, y up).
  PLFLT left = 0, right = 1, bottom = 0, top = 1;
  // Distances of the axis labels from the plot, in PLplot's character
  // heights of their font.
  PLFLT x_label_offset = 0, y_label_offset = 0;
  std::string title, x_label, y_label;
  // The y tick labels are the values over 10^y_power (0: as they are):
  // below 0.01 or from 1e5 up; the label says so. PLplot would write its
  // own power of ten above the axis, where the title is.
  int y_power = 0;
  double title_font = 0.0;  // px: 1.2 times the font, smaller for a long title to fit
  std::vector<PreparedSeries> series;
  // The legend (none when legend_names is empty): names, per-entry arrays
  // as pllegend takes them, its text size relative to the tick font.
  std::vector<std::string> legend_text;
  std::vector<const char*> legend_names, legend_markers;
  std::vector<PLINT> legend_options, legend_text_colors, legend_colors, legend_styles,
      legend_marker_counts;
  std::vector<PLFLT> legend_widths, legend_marker_scales;
  PLFLT legend_scale = 1.0;
  PLFLT legend_sample = 0.0;  // length of a line sample, normalised to the width
  bool x_boolean = false, y_boolean = false;
};

bool has_lines(ChartKind kind) { return kind != ChartKind::points; }
bool has_markers(ChartKind kind) {
  return kind == ChartKind::points || kind == ChartKind::linespoints;
}

bool inside(const ChartAxis& axis, double value) { return value >= axis.lo && value <= axis.hi; }

// The series' line and markers; PLplot cuts lines off at the plot's edges,
// markers outside it (only with a range given) are left out here.
PreparedSeries prepared_series(const ChartSpec& spec, const ChartAxis& x_axis,
                               const ChartAxis& y_axis, int k) {
  PreparedSeries prepared;
  prepared.color = kFirstSeries + k % kPaletteSize;
  prepared.style = kLineStyles[(k / kPaletteSize) % 3];
  prepared.marker = kMarkers[k % kMarkerShapes];
  const std::vector<Vec2>& points = spec.series[k].points;
  for (size_t i = 0; i < points.size(); ++i) {
    const double x = world(points[i].x(), spec.log_x), y = world(points[i].y(), spec.log_y);
    if (has_lines(spec.kind) && points.size() >= 2) {
      if (spec.kind == ChartKind::steps && i > 0) {
        prepared.line_x.push_back(x);
        prepared.line_y.push_back(prepared.line_y.back());
      }
      prepared.line_x.push_back(x);
      prepared.line_y.push_back(y);
    }
    // A lone point has no line to show it.
    const bool shown = inside(x_axis, points[i].x()) && inside(y_axis, points[i].y());
    if (shown && (has_markers(spec.kind) || points.size() == 1)) {
      prepared.marker_x.push_back(x);
      prepared.marker_y.push_back(y);
    }
  }
  return prepared;
}

void prepare_legend(const ChartSpec& spec, PreparedChart& chart) {
  if (spec.series.size() < 2) return;
  const ChartMetrics& m = chart.metrics;
  size_t longest = 0;
  for (const ChartSeries& series : spec.series) {
    chart.legend_text.push_back(plplot_text(series.name));
    longest = std::max(longest, series.name.size());
  }
  // In units of the legend's font: padding, a 2.4 long sample, the name.
  const double width = 0.6 + 2.4 + 0.5 + kCharacterWidth * longest + 0.6;
  const double rows = 1.5 * spec.series.size() + 1.2;
  const double plot_height = (chart.top - chart.bottom) * spec.height;
  chart.legend_scale = std::min({1.0, kLegendWidthShare * spec.width / (width * m.tick_font),
                                 plot_height / (rows * m.tick_font)});
  chart.legend_sample = 2.4 * m.tick_font * chart.legend_scale / spec.width;
  const PLINT shown = (has_lines(spec.kind) ? PL_LEGEND_LINE : 0) |
                      (has_markers(spec.kind) ? PL_LEGEND_SYMBOL : 0);
  for (size_t k = 0; k < spec.series.size(); ++k) {
    const PreparedSeries& series = chart.series[k];
    chart.legend_names.push_back(chart.legend_text[k].c_str());
    chart.legend_markers.push_back(series.marker);
    chart.legend_options.push_back(shown);
    chart.legend_text_colors.push_back(kText);
    chart.legend_colors.push_back(series.color);
    chart.legend_styles.push_back(series.style);
    chart.legend_marker_counts.push_back(1);
    chart.legend_widths.push_back(2.0 * m.line);
    chart.legend_marker_scales.push_back(1.0);
  }
}

PreparedChart prepare(const ChartSpec& spec) {
  PreparedChart chart;
  chart.width = spec.width;
  chart.height = spec.height;
  chart.metrics = ChartMetrics(spec.width, spec.height);
  const ChartMetrics& m = chart.metrics;
  std::tie(chart.x, chart.y) = chart_axes(spec);
  chart.title = plplot_text(spec.title);
  chart.title_font =
      std::min(1.2 * m.font, (spec.width - 2 * m.margin) / (kCharacterWidth * spec.title.size()));
  chart.x_label = plplot_text(spec.x_label);
  chart.x_boolean = spec.x_boolean && !spec.log_x;
  chart.y_boolean = spec.y_boolean && !spec.log_y;
  if (!spec.log_y && !chart.y_boolean) chart.y_power = axis_power(chart.y.lo, chart.y.hi);
  chart.y_label = plplot_text(spec.y_label);
  if (chart.y_power != 0) {
    chart.y_label += (chart.y_label.empty() ? "×10#u" : ", ×10#u") + std::to_string(chart.y_power) + "#d";
  }

  // Top to bottom: title, plot, x tick labels (PLplot's common power of ten
  // goes under them), x label.
  const double top = m.margin + (spec.title.empty() ? 0.6 * m.tick_font : 2.2 * m.font);
  const double x_labels = 2.6 * m.tick_font;
  const double bottom = m.margin + x_labels + (spec.x_label.empty() ? 0.0 : 1.6 * m.font);
  chart.x_label_offset = (x_labels + 0.8 * m.font) / (kPlplotCharacterHeight * m.font);
  // Left to right: y label, y tick labels, plot, legend.
  // "false" is 5 characters long.
  const int label_characters = spec.log_y || spec.y_boolean
                                   ? 5
                                   : linear_label_characters(chart.y.lo / std::pow(10.0, chart.y_power),
                                                             chart.y.hi / std::pow(10.0, chart.y_power));
  const double y_labels = (kCharacterWidth * label_characters + 1.0) * m.tick_font;
  const double left = m.margin + y_labels + (spec.y_label.empty() ? 0.0 : 1.5 * m.font);
  chart.y_label_offset = (y_labels + 0.6 * m.font) / (kPlplotCharacterHeight * m.font);
  chart.top = 1.0 - top / spec.height;
  chart.bottom = bottom / spec.height;
  chart.left = left / spec.width;
  for (size_t k = 0; k < spec.series.size(); ++k) {
    chart.series.push_back(prepared_series(spec, chart.x, chart.y, static_cast<int>(k)));
  }
  prepare_legend(spec, chart);
  // Half a tick label may reach past the last x tick.
  chart.right = 1.0 - (m.margin + 2.0 * m.tick_font) / spec.width;
  if (chart.right - chart.left < 0.1 || chart.top - chart.bottom < 0.1) {
    throw InvalidArgument("chart: no room left for the plot in " + std::to_string(spec.width) +
                          " x " + std::to_string(spec.height) +
                          "; make the image larger or the labels shorter");
  }
  return chart;
}

// ---------------------------------------------------------------------------
// The PLplot calls

// The legend goes first, right of the plot area's top, placed on the page;
// PLplot says how wide it came out, and the plot area ends left of it.
PLFLT paint_legend(const PreparedChart& chart) {
  const ChartMetrics& m = chart.metrics;
  if (chart.legend_names.empty()) return chart.right;
  plplot_font(m.tick_font);
  PLFLT width = 0.0, height = 0.0;
  pllegend(&width, &height, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
           PL_POSITION_RIGHT | PL_POSITION_TOP | PL_POSITION_INSIDE | PL_POSITION_SUBPAGE,
           m.margin / chart.width, 1.0 - chart.top, chart.legend_sample, kBackground,
           kLegendBorder, 1, 0, 0, static_cast<PLINT>(chart.legend_names.size()),
           chart.legend_options.data(), 0.5, chart.legend_scale, 1.5, 0.0,
           chart.legend_text_colors.data(), chart.legend_names.data(), nullptr, nullptr, nullptr,
           nullptr, chart.legend_colors.data(), chart.legend_styles.data(),
           chart.legend_widths.data(), chart.legend_colors.data(),
           chart.legend_marker_scales.data(), chart.legend_marker_counts.data(),
           chart.legend_markers.data());
  return 1.0 - m.margin / chart.width - width - m.font / chart.width;
}

// Box options of an axis: PLplot's log labels and ticks on a log axis,
// plplot_boolean_label's on an axis of booleans.
std::string axis_options(const char* options, const char* log_options, bool log, bool boolean) {
  return log ? log_options : std::string(options) + (boolean ? "o" : "");
}

// plbox's tick spacing and subdivisions: PLplot's choice (0), or 1 and
// none on an axis of booleans.
PLFLT tick_spacing(bool boolean) { return boolean ? 1.0 : 0.0; }
PLINT tick_subdivisions(bool boolean) { return boolean ? 1 : 0; }

// The label function of the frame's axes with 'o': booleans, or the y
// values over 10^y_power, each in its shortest form.
void tick_label(PLINT axis, PLFLT value, char* text, PLINT length, PLPointer data) {
  const PreparedChart& chart = *static_cast<const PreparedChart*>(data);
  if (axis != PL_Y_AXIS || chart.y_boolean) {
    plplot_boolean_label(axis, value, text, length, nullptr);
    return;
  }
  const double scaled = value / std::pow(10.0, chart.y_power);
  // Shortest of up to 6 significant digits: ticks are 1, 2 or 5 times a power of ten.
  std::snprintf(text, static_cast<size_t>(length), "%.6g", std::abs(scaled) < 1e-9 ? 0.0 : scaled);
}

// plbox with the chart's axes.
void chart_box(const PreparedChart& chart, const char* x_options, const char* x_log_options,
               const char* y_options, const char* y_log_options) {
  plbox(axis_options(x_options, x_log_options, chart.x.log, chart.x_boolean).c_str(),
        tick_spacing(chart.x_boolean), tick_subdivisions(chart.x_boolean),
        axis_options(y_options, y_log_options, chart.y.log, chart.y_boolean).c_str(),
        tick_spacing(chart.y_boolean), tick_subdivisions(chart.y_boolean));
}

// What paint_chart is given, and where the plot area ended.
struct ChartPainting {
  const PreparedChart* chart;
  PLFLT right;  // normalised page coordinates
};

// The chart's PLplot calls (a PlplotPainter: plain values only).
void paint_chart(void* context) {
  ChartPainting& painting = *static_cast<ChartPainting*>(context);
  const PreparedChart& chart = *painting.chart;
  const ChartMetrics& m = chart.metrics;
  plscmap0n(kFirstSeries + kPaletteSize);
  plplot_color(kBackground, {1.0, 1.0, 1.0});
  plplot_color(kText, kTextColor);
  plplot_color(kGrid, kGridColor);
  plplot_color(kMinorGrid, kMinorGridColor);
  plplot_color(kLegendBorder, kLegendBorderColor);
  for (int k = 0; k < kPaletteSize; ++k) plplot_color(kFirstSeries + k, kPalette[k]);
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, 1.0, 0.0, 1.0);
  // Text in the text colour (plinit left colour 1 current, as it was then).
  plcol0(kText);
  plplot_page_title(chart.title, chart.title_font, m.margin + 0.7 * m.font);
  const PLFLT right = std::min(chart.right, paint_legend(chart));
  plvpor(chart.left, right, chart.bottom, chart.top);
  plwind(world(chart.x.lo, chart.x.log), world(chart.x.hi, chart.x.log),
         world(chart.y.lo, chart.y.log), world(chart.y.hi, chart.y.log));

  // The grid under everything: minor lines (log axes), then major ones.
  plwidth(0.7 * m.line);
  plcol0(kMinorGrid);
  chart_box(chart, "", "hl", "", "hl");
  plwidth(m.line);
  plcol0(kGrid);
  chart_box(chart, "g", "gl", "g", "gl");

  plplot_font(m.tick_font);
  for (const PreparedSeries& series : chart.series) {
    plcol0(series.color);
    if (!series.line_x.empty()) {
      pllsty(series.style);
      plwidth(2.0 * m.line);
      plline(static_cast<PLINT>(series.line_x.size()), series.line_x.data(),
             series.line_y.data());
    }
    pllsty(1);
    if (!series.marker_x.empty()) {
      plstring(static_cast<PLINT>(series.marker_x.size()), series.marker_x.data(),
               series.marker_y.data(), series.marker);
    }
  }

  // The frame, ticks and tick labels (y labels upright), then the labels.
  plcol0(kText);
  plwidth(m.line);
  plslabelfunc(tick_label, const_cast<PreparedChart*>(&chart));
  // Enough digits that PLplot writes the values as they are (tick_label
  // writes them over a power of ten beyond axis_power's range).
  plsyax(8, 0);
  chart_box(chart, "bcnst", "bcnstl", chart.y_power != 0 ? "bcnstvo" : "bcnstv", "bcnstvl");
  plslabelfunc(nullptr, nullptr);
  plplot_font(m.font);
  if (!chart.x_label.empty()) plmtex("b", chart.x_label_offset, 0.5, 0.5, chart.x_label.c_str());
  if (!chart.y_label.empty()) plmtex("l", chart.y_label_offset, 0.5, 0.5, chart.y_label.c_str());
  painting.right = right;
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
                        "' (allowed: lines, points, linespoints, steps, map)");
}

Rgb chart_series_color(int k) {
  if (k < 0) throw InvalidArgument("chart: series index must be >= 0, got " + std::to_string(k));
  return kPalette[k % kPaletteSize];
}

double ChartAxis::fraction(double value) const {
  if (log) return std::log10(value / lo) / std::log10(hi / lo);
  return (value - lo) / (hi - lo);
}

Vec2 ChartFrame::to_image(const Vec2& data) const {
  return {plot.left + plot.width * x.fraction(data.x()),
          plot.bottom() - plot.height * y.fraction(data.y())};
}

std::pair<ChartAxis, ChartAxis> chart_axes(const ChartSpec& spec) {
  check_spec(spec);
  Vec2 lo = Vec2::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const ChartSeries& series : spec.series) {
    for (const Vec2& p : series.points) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  return {chosen_axis(spec.x_range, lo.x(), hi.x(), spec.log_x, "x"),
          chosen_axis(spec.y_range, lo.y(), hi.y(), spec.log_y, "y")};
}

ChartFrame draw_chart(const std::string& path, const ChartSpec& spec) {
  const ImageFormat format =
      image_format(path, {ImageFormat::png, ImageFormat::svg, ImageFormat::pdf}, "chart");
  const PreparedChart chart = prepare(spec);
  ChartPainting painting{&chart, chart.right};
  write_file_atomically(path, plplot_picture(format, spec.width, spec.height, paint_chart,
                                             &painting, "chart", path));
  ChartFrame frame;
  frame.x = chart.x;
  frame.y = chart.y;
  frame.plot.left = chart.left * spec.width;
  frame.plot.width = (painting.right - chart.left) * spec.width;
  frame.plot.top = (1.0 - chart.top) * spec.height;
  frame.plot.height = (chart.top - chart.bottom) * spec.height;
  return frame;
}

}  // namespace ashlar
