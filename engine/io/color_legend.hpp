// Legend images for the colour maps: a colour bar from lo to hi with its
// ticks and label, drawn by PLplot, to go with a drawing or an export
// coloured by values. Format from the extension: .svg (sizes in pt) or .png
// (sizes in px).
#pragma once

#include <string>
#include <vector>

namespace ashlar {

struct LegendOptions {
  std::string map = "viridis";  // one of color_map_names()
  double lo = 0.0, hi = 1.0;    // values at the ends of the bar, lo < hi, finite
  std::string label;            // what the colours mean, with units; none when empty
  bool vertical = true;         // lo at the bottom; horizontal: lo at the left
  // px for .png, pt for .svg, each in [100, 16384]; 0 takes the default of
  // the orientation: 300 x 600 vertical, 600 x 150 horizontal.
  int width = 0, height = 0;
};

struct LegendTick {
  double value = 0.0;
  std::string label;
};

// `count` (>= 2) evenly spaced ticks from lo to hi (finite, lo < hi), both
// included. Labels carry three significant digits of the spacing, trailing
// zeros dropped ("0", "0.25", "1000"); values of magnitude 1e6 and more, or
// all below 1e-3, use %.3g ("1.5e+07"). Throws InvalidArgument otherwise.
std::vector<LegendTick> legend_ticks(double lo, double hi, int count = 5);

// A colour bar of the map from lo to hi with 5 labelled ticks and the
// label, written atomically by PLplot (io/plplot_picture). Throws InvalidArgument for an unknown
// extension or map, a bad range or size, IoError when the file cannot be
// written.
void draw_legend(const std::string& path, const LegendOptions& options);

}  // namespace ashlar
