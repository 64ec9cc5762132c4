// Colour maps that turn values into colours for export.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "io/mesh_io.hpp"

namespace ashlar {

// Maps values into colours with the named map; values are scaled from
// [lo, hi] to [0, 1] and clamped. Throws InvalidArgument for an unknown map.
std::vector<Rgb> map_colors(const std::vector<double>& values, double lo, double hi,
                            const std::string& map_name);

// The range a colour map spans for `values` when none is given: their
// smallest and largest finite value, except that it starts at 0 when every
// value is >= 0 (a tension of 3e-11 is none: it gets the colour of 0).
// {0, 0} when no value is finite.
std::pair<double, double> value_range(const std::vector<double>& values);

// Throws InvalidArgument, naming the available maps, unless `name` is one.
void check_color_map(const std::string& name);

// Names of the available maps, e.g. "viridis", for error messages.
const std::vector<std::string>& color_map_names();

}  // namespace ashlar
