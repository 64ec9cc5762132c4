// Colour legends through PLplot (io/plplot_picture): a gradient colour bar
// (plcolorbar) over colour map 1, set from the map's colours. PLplot puts
// ticks at multiples of their spacing, so the bar runs over tick numbers 0
// .. 4 and a label function (plslabelfunc) writes the value of each, which
// keeps the five ticks at lo, hi and evenly between whatever lo is.
//
// Sizes follow the legend's length (its longer side), so that both
// orientations of the same length look alike.
#include "io/color_legend.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "io/color_map.hpp"
#include "io/image_format.hpp"
#include "io/plplot_picture.hpp"

namespace ashlar {
namespace {

constexpr int kMinImageSize = 100;
constexpr int kLegendTicks = 5;
// The maps are piecewise linear over at most 17 control points; 65 evenly
// spaced ones reproduce them to well under an 8-bit step.
constexpr int kColorPoints = 65;
// About the advance of a digit of DejaVu Sans, in font sizes.
constexpr double kDigitWidth = 0.64;

std::string trimmed_fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  std::string label = text;
  if (label.find('.') != std::string::npos) {
    label.erase(label.find_last_not_of('0') + 1);
    if (label.back() == '.') label.pop_back();
  }
  return label == "-0" ? "0" : label;
}

std::string tick_label(double value, double spacing, double largest) {
  // Round-off of lo + k * spacing must not print as "-2.8e-17".
  if (std::abs(value) < 1e-9 * spacing) return "0";
  const int spacing_exponent = static_cast<int>(std::floor(std::log10(spacing)));
  if (largest >= 1e6 || largest < 1e-3) {
    const int largest_exponent = static_cast<int>(std::floor(std::log10(largest)));
    const int digits = std::clamp(largest_exponent - spacing_exponent + 3, 3, 15);
    char text[64];
    std::snprintf(text, sizeof text, "%.*g", digits, value);
    return text;
  }
  return trimmed_fixed(value, std::clamp(2 - spacing_exponent, 0, 15));
}

void check_legend(const LegendOptions& options) {
  if (!std::isfinite(options.lo) || !std::isfinite(options.hi) || !(options.lo < options.hi)) {
    std::ostringstream message;
    message << "legend: range must be finite with lo < hi, got [" << options.lo << ", "
            << options.hi << "]";
    throw InvalidArgument(message.str());
  }
  check_color_map(options.map);
}

// Everything the PLplot calls need, in their types.
struct PreparedLegend {
  bool vertical = true;
  double font = 0.0, line = 0.0;
  // Colour map 1's control points: positions 0 .. 1 and their colours.
  std::vector<PLFLT> positions, red, green, blue;
  std::vector<std::string> tick_labels;
  std::string label;
  // The bar in normalised page coordinates: its offset from the page's
  // top left corner (to its labels' box, as plcolorbar places it) and size.
  PLFLT x = 0, y = 0, length_x = 0, length_y = 0;
};

PreparedLegend prepare(const LegendOptions& options, int width, int height) {
  PreparedLegend legend;
  legend.vertical = options.vertical;
  const double side = std::min(width, height), length = std::max(width, height);
  legend.font = std::clamp(0.025 * length, 9.0, 32.0);
  legend.line = std::max(1.0, side / 800.0);
  const double margin = std::max(12.0, 0.04 * side);
  for (int k = 0; k < kColorPoints; ++k) legend.positions.push_back(k / double(kColorPoints - 1));
  std::vector<double> values(legend.positions.begin(), legend.positions.end());
  for (const Rgb& color : map_colors(values, 0.0, 1.0, options.map)) {
    legend.red.push_back(color.r);
    legend.green.push_back(color.g);
    legend.blue.push_back(color.b);
  }
  size_t widest = 0;
  for (const LegendTick& tick : legend_ticks(options.lo, options.hi, kLegendTicks)) {
    legend.tick_labels.push_back(tick.label);
    widest = std::max(widest, tick.label.size());
  }
  legend.label = plplot_text(options.label);
  const double font = legend.font;
  const double label_band = options.label.empty() ? 0.0 : 1.8 * font;
  const double thickness_cap = 2.5 * font;
  if (options.vertical) {
    // Label (turned), bar, tick labels side by side, centred.
    const double labels = font + kDigitWidth * widest * font;
    const double bar = std::clamp(width - 2 * margin - label_band - labels, 6.0, thickness_cap);
    const double group = label_band + bar + labels;
    legend.x = std::max(margin, (width - group) / 2) / width;
    legend.y = margin / height;
    legend.length_x = bar / width;
    legend.length_y = (height - 2 * (margin + font)) / height;
  } else {
    // Label above the bar, tick labels below, centred.
    const double labels = 2.0 * font;
    const double bar = std::clamp(height - 2 * margin - label_band - labels, 6.0, thickness_cap);
    const double group = label_band + bar + labels;
    // Room for half of the end labels beyond the bar's ends.
    const double overhang = std::max(0.5 * kDigitWidth * widest * font, font);
    legend.x = (margin + overhang) / width;
    legend.y = std::max(margin, (height - group) / 2) / height;
    legend.length_x = (width - 2 * (margin + overhang)) / width;
    legend.length_y = bar / height;
  }
  return legend;
}

// Tick k of the bar (at k = 0 .. 4) is labelled with the value it stands for.
void tick_text(PLINT, PLFLT value, char* text, PLINT length, PLPointer data) {
  const auto& labels = *static_cast<const std::vector<std::string>*>(data);
  const long k = std::lround(value);
  const bool known = k >= 0 && k < static_cast<long>(labels.size());
  std::snprintf(text, static_cast<size_t>(length), "%s", known ? labels[k].c_str() : "");
}

// The legend's PLplot calls (a PlplotPainter: plain values only).
void paint_legend(void* context) {
  const PreparedLegend& legend = *static_cast<const PreparedLegend*>(context);
  plscmap0n(2);
  plplot_color(0, {1.0, 1.0, 1.0});
  plplot_color(1, {0.0, 0.0, 0.0});
  plscmap1l(1, static_cast<PLINT>(legend.positions.size()), legend.positions.data(),
            legend.red.data(), legend.green.data(), legend.blue.data(), nullptr);
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, 1.0, 0.0, 1.0);
  plslabelfunc(tick_text, const_cast<std::vector<std::string>*>(&legend.tick_labels));
  plplot_font(legend.font);
  plwidth(legend.line);
  plcol0(1);
  // The bar runs over tick numbers 0 .. 4: a tick each, labelled by tick_text
  // ('o'); vertical labels right of the bar ('m'), upright ('v').
  const PLFLT span[] = {0.0, static_cast<PLFLT>(legend.tick_labels.size() - 1)};
  const PLFLT* values[] = {span};
  const PLINT value_counts[] = {2};
  const char* axis[] = {legend.vertical ? "bcmtvo" : "bcnto"};
  const PLFLT ticks[] = {1.0};
  const PLINT sub_ticks[] = {0};
  const PLINT label_side[] = {legend.vertical ? PL_COLORBAR_LABEL_LEFT : PL_COLORBAR_LABEL_TOP};
  const char* labels[] = {legend.label.c_str()};
  PLFLT bar_width = 0.0, bar_height = 0.0;
  plcolorbar(&bar_width, &bar_height,
             PL_COLORBAR_GRADIENT |
                 (legend.vertical ? PL_COLORBAR_ORIENT_TOP : PL_COLORBAR_ORIENT_RIGHT),
             PL_POSITION_SUBPAGE | PL_POSITION_INSIDE | PL_POSITION_LEFT | PL_POSITION_TOP,
             legend.x, legend.y, legend.length_x, legend.length_y, 0, 1, 1, 0.0, 0.0, 0, 0.0,
             legend.label.empty() ? 0 : 1, label_side, labels, 1, axis, ticks, sub_ticks,
             value_counts, values);
  plslabelfunc(nullptr, nullptr);
}

}  // namespace

std::vector<LegendTick> legend_ticks(double lo, double hi, int count) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi) || count < 2) {
    std::ostringstream message;
    message << "legend ticks: need a finite range with lo < hi and at least 2 ticks, got [" << lo
            << ", " << hi << "] and " << count;
    throw InvalidArgument(message.str());
  }
  const double spacing = (hi - lo) / (count - 1);
  const double largest = std::max(std::abs(lo), std::abs(hi));
  std::vector<LegendTick> ticks;
  for (int k = 0; k < count; ++k) {
    const double value = k == count - 1 ? hi : lo + k * spacing;
    ticks.push_back({value, tick_label(value, spacing, largest)});
  }
  return ticks;
}

void draw_legend(const std::string& path, const LegendOptions& options) {
  const ImageFormat format = image_format(path, {ImageFormat::svg, ImageFormat::png}, "legend");
  check_legend(options);
  const int width = options.width != 0 ? options.width : (options.vertical ? 300 : 600);
  const int height = options.height != 0 ? options.height : (options.vertical ? 600 : 150);
  check_image_size(width, height, kMinImageSize, "legend");
  PreparedLegend legend = prepare(options, width, height);
  write_file_atomically(
      path, plplot_picture(format, width, height, paint_legend, &legend, "legend", path));
}

}  // namespace ashlar
