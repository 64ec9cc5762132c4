// Charts through PLplot. Everything PLplot is given (coordinates, text,
// legend arrays, the layout) is prepared first, in plain C++; then one
// function makes the PLplot calls on a stream of its own, under a mutex,
// since PLplot keeps global state (the current stream, its error handlers,
// the LC_NUMERIC switches around each driver call). PLplot writes into
// memory (open_memstream); the file is then written whole or not at all.
//
// Devices: the cairo drivers for .png and .pdf (pango text, antialiased),
// PLplot's own svg driver for .svg, which writes text as <text> elements
// (cairo's SVG surface turns every glyph into a path, so the labels could
// not be searched, selected or checked).
//
// Sizes that depend on the image (margins, fonts, line widths) follow its
// smaller side, so that a larger image looks the same, only sharper. The
// cairo and svg drivers take the page in px (pt) at 72 dpi, and write text
// at 4/3 of PLplot's character height (pango's 96 dpi, the svg driver's
// ratio 1.34): a font of s px is a character height of s * 25.4 / 96 mm.
#include "io/chart.hpp"

#include <plplot.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <mutex>
#include <tuple>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "io/image_format.hpp"

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
// A legend takes at most this fraction of the image's width; longer names
// shrink its text.
constexpr double kLegendWidthShare = 0.35;
// About the advance of an average character of DejaVu Sans (lowercase,
// digits, spaces), in font sizes: to leave room for text before PLplot has
// drawn it.
constexpr double kCharacterWidth = 0.5;
// PLplot's character height over the drivers' font size.
constexpr double kCharacterHeight = 0.75;
constexpr double kMillimetresPerPoint = 25.4 / 72.0;

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
const Rgb kTextColor{0.15, 0.15, 0.15};
const Rgb kGridColor{0.87, 0.87, 0.87};
const Rgb kMinorGridColor{0.94, 0.94, 0.94};
const Rgb kLegendBorderColor{0.75, 0.75, 0.75};

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

// PLplot reads '#' as the start of an escape sequence (#u: superscript, ...).
std::string plplot_text(const std::string& text) {
  std::string escaped;
  for (const char c : text) escaped += c == '#' ? "##" : std::string(1, c);
  return escaped;
}

// A value along an axis in PLplot's world coordinates: log10 on log axes.
double world(double value, bool log) { return log ? std::log10(value) : value; }

// The widest tick label PLplot writes on a linear axis over [lo, hi], in
// characters: its step is 1, 2 or 5 times a power of ten (pldtik), its
// labels have the step's decimals, and past 5 digits it writes the values
// over a common power of ten, shown once at the axis's end.
int linear_label_characters(double lo, double hi) {
  const double largest = std::max(std::abs(lo), std::abs(hi));
  if (largest >= 1e5 || largest < 1e-4) return 5;
  const int decimals = std::max(0, 1 - static_cast<int>(std::floor(std::log10(hi - lo))));
  const int digits = std::max(1, static_cast<int>(std::floor(std::log10(largest))) + 1);
  return digits + (decimals > 0 ? decimals + 1 : 0) + (lo < 0 ? 1 : 0);
}

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
  const char* device = nullptr;
  PLINT width = 0, height = 0;
  ChartMetrics metrics{kMinImageSize, kMinImageSize};
  ChartAxis x, y;
  // The plot area in normalised page coordinates (0 to 1, y up).
  PLFLT left = 0, right = 1, bottom = 0, top = 1;
  // Distances of the axis labels from the plot, in PLplot's character
  // heights of their font.
  PLFLT x_label_offset = 0, y_label_offset = 0;
  std::string title, x_label, y_label;
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
};

const char* device_of(ImageFormat format) {
  switch (format) {
    case ImageFormat::png:
      return "pngcairo";
    case ImageFormat::pdf:
      return "pdfcairo";
    case ImageFormat::svg:
      break;
  }
  return "svg";
}

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

PreparedChart prepare(const ChartSpec& spec, ImageFormat format) {
  PreparedChart chart;
  chart.device = device_of(format);
  chart.width = spec.width;
  chart.height = spec.height;
  chart.metrics = ChartMetrics(spec.width, spec.height);
  const ChartMetrics& m = chart.metrics;
  std::tie(chart.x, chart.y) = chart_axes(spec);
  chart.title = plplot_text(spec.title);
  chart.title_font =
      std::min(1.2 * m.font, (spec.width - 2 * m.margin) / (kCharacterWidth * spec.title.size()));
  chart.x_label = plplot_text(spec.x_label);
  chart.y_label = plplot_text(spec.y_label);

  // Top to bottom: title, plot, x tick labels (PLplot's common power of ten
  // goes under them), x label.
  const double top = m.margin + (spec.title.empty() ? 0.6 * m.tick_font : 2.2 * m.font);
  const double x_labels = 2.6 * m.tick_font;
  const double bottom = m.margin + x_labels + (spec.x_label.empty() ? 0.0 : 1.6 * m.font);
  chart.x_label_offset = (x_labels + 0.8 * m.font) / (kCharacterHeight * m.font);
  // Left to right: y label, y tick labels, plot, legend.
  const int label_characters =
      spec.log_y ? 5 : linear_label_characters(chart.y.lo, chart.y.hi);
  const double y_labels = (kCharacterWidth * label_characters + 1.0) * m.tick_font;
  const double left = m.margin + y_labels + (spec.y_label.empty() ? 0.0 : 1.5 * m.font);
  chart.y_label_offset = (y_labels + 0.6 * m.font) / (kCharacterHeight * m.font);
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

// PLplot calls its exit handler on errors it cannot go on from (no driver,
// no memory) and exit()s the process when the handler returns. The handler
// jumps back to draw_with_plplot instead; between the two there are only
// PLplot's C frames and paint_chart's, which holds nothing with a
// destructor. Guarded by the mutex, like everything else of PLplot's.
std::mutex plplot_mutex;
std::jmp_buf* plplot_exit_jump = nullptr;
char plplot_exit_message[512];

int on_plplot_exit(const char* message) {
  std::snprintf(plplot_exit_message, sizeof plplot_exit_message, "%s", message);
  if (plplot_exit_jump) std::longjmp(*plplot_exit_jump, 1);
  return 1;  // unreachable: PLplot is called only by draw_with_plplot
}

PLINT rgb_byte(double channel) { return static_cast<PLINT>(std::lround(channel * 255)); }

void set_color(PLINT index, const Rgb& color) {
  plscol0(index, rgb_byte(color.r), rgb_byte(color.g), rgb_byte(color.b));
}

void set_font(double size_px) { plschr(kCharacterHeight * size_px * kMillimetresPerPoint, 1.0); }

// The legend goes first, right of the plot area's top, placed on the page;
// PLplot says how wide it came out, and the plot area ends left of it.
PLFLT paint_legend(const PreparedChart& chart) {
  const ChartMetrics& m = chart.metrics;
  if (chart.legend_names.empty()) return chart.right;
  set_font(m.tick_font);
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

// Box options of an axis: PLplot's log labels and ticks on a log axis.
const char* axis_options(const char* options, const char* log_options, bool log) {
  return log ? log_options : options;
}

// Whether PLplot found `device` among its drivers: asked for one it does not
// have, it would ask for another on stdin.
bool has_device(const char* device) {
  const char* menus[128];
  const char* names[128];
  const char** menu_list = menus;
  const char** name_list = names;
  int count = 128;
  plgDevs(&menu_list, &name_list, &count);
  for (int k = 0; k < count; ++k) {
    if (std::strcmp(names[k], device) == 0) return true;
  }
  return false;
}

// Draws the chart on the current stream, from plinit to plend1. Locals are
// plain values only (see on_plplot_exit). Returns the plot area's right end.
PLFLT paint_chart(const PreparedChart& chart, FILE* file) {
  const ChartMetrics& m = chart.metrics;
  plsdev(chart.device);
  plsfile(file);
  plspage(0.0, 0.0, chart.width, chart.height, 0, 0);
  plspause(0);
  plscmap0n(kFirstSeries + kPaletteSize);
  set_color(kBackground, {1.0, 1.0, 1.0});
  set_color(kText, kTextColor);
  set_color(kGrid, kGridColor);
  set_color(kMinorGrid, kMinorGridColor);
  set_color(kLegendBorder, kLegendBorderColor);
  for (int k = 0; k < kPaletteSize; ++k) set_color(kFirstSeries + k, kPalette[k]);
  plinit();
  pladv(0);
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, 1.0, 0.0, 1.0);
  // The title, centred on the page (measured down from its top edge).
  if (!chart.title.empty()) {
    set_font(chart.title_font);
    plmtex("t", -(m.margin + 0.7 * m.font) / (kCharacterHeight * chart.title_font), 0.5, 0.5,
           chart.title.c_str());
  }
  const PLFLT right = std::min(chart.right, paint_legend(chart));
  plvpor(chart.left, right, chart.bottom, chart.top);
  plwind(world(chart.x.lo, chart.x.log), world(chart.x.hi, chart.x.log),
         world(chart.y.lo, chart.y.log), world(chart.y.hi, chart.y.log));

  // The grid under everything: minor lines (log axes), then major ones.
  plwidth(0.7 * m.line);
  plcol0(kMinorGrid);
  plbox(axis_options("", "hl", chart.x.log), 0.0, 0, axis_options("", "hl", chart.y.log), 0.0, 0);
  plwidth(m.line);
  plcol0(kGrid);
  plbox(axis_options("g", "gl", chart.x.log), 0.0, 0, axis_options("g", "gl", chart.y.log), 0.0,
        0);

  set_font(m.tick_font);
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
  plbox(axis_options("bcnst", "bcnstl", chart.x.log), 0.0, 0,
        axis_options("bcnstv", "bcnstvl", chart.y.log), 0.0, 0);
  set_font(m.font);
  if (!chart.x_label.empty()) plmtex("b", chart.x_label_offset, 0.5, 0.5, chart.x_label.c_str());
  if (!chart.y_label.empty()) plmtex("l", chart.y_label_offset, 0.5, 0.5, chart.y_label.c_str());
  plend1();
  return right;
}

struct PlplotOutcome {
  bool drawn = false;
  PLFLT right = 1.0;   // where the plot area ended, normalised
  std::string error;   // what PLplot said when not drawn
};

// Runs paint_chart on a new PLplot stream with output into `file`, which
// PLplot closes when it ends the stream. Call with plplot_mutex held.
PlplotOutcome draw_with_plplot(const PreparedChart& chart, FILE* file) {
  static char abort_message[2048];  // plsError: PLplot writes what failed here
  PLINT abort_code = 0;
  PlplotOutcome outcome;
  std::jmp_buf jump;
  volatile int stage = 0;  // 1: the stream exists, 2: ending it after an exit
  plsexit(on_plplot_exit);
  plplot_exit_jump = &jump;
  if (setjmp(jump) == 0) {
    if (!has_device(chart.device)) {
      outcome.error = std::string("its '") + chart.device +
                      "' device is missing (Debian: plplot-driver-cairo, libplplot17)";
      std::fclose(file);
      plplot_exit_jump = nullptr;
      return outcome;
    }
    PLINT stream = 0;
    plmkstrm(&stream);
    stage = 1;
    // Errors PLplot can go on from are written here instead of stderr.
    abort_message[0] = '\0';
    plsError(&abort_code, abort_message);
    outcome.right = paint_chart(chart, file);
    outcome.drawn = abort_code == 0;
    if (!outcome.drawn) outcome.error = abort_message;
  } else {
    outcome.error = plplot_exit_message;
    if (stage == 1) {
      stage = 2;
      PLINT level = 0;
      plglevel(&level);
      plend1();
      // Before plinit took it, the file is still ours.
      if (level == 0) std::fclose(file);
    }
  }
  plplot_exit_jump = nullptr;
  return outcome;
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
  const PreparedChart chart = prepare(spec, format);
  char* buffer = nullptr;
  size_t size = 0;
  PlplotOutcome outcome;
  {
    const std::lock_guard<std::mutex> lock(plplot_mutex);
    FILE* file = open_memstream(&buffer, &size);
    if (!file) throw IoError("chart: cannot draw '" + path + "': out of memory");
    outcome = draw_with_plplot(chart, file);
  }
  const std::string bytes = buffer ? std::string(buffer, size) : std::string();
  std::free(buffer);
  if (!outcome.drawn) {
    throw IoError("chart: PLplot could not draw '" + path + "': " + outcome.error);
  }
  write_file_atomically(path, bytes);
  ChartFrame frame;
  frame.x = chart.x;
  frame.y = chart.y;
  frame.plot.left = chart.left * spec.width;
  frame.plot.width = (outcome.right - chart.left) * spec.width;
  frame.plot.top = (1.0 - chart.top) * spec.height;
  frame.plot.height = (chart.top - chart.bottom) * spec.height;
  return frame;
}

}  // namespace ashlar
