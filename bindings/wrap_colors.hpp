// Colour options shared by ashlar.export and ashlar.draw.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <lua.hpp>

#include "io/mesh_io.hpp"
#include "luax.hpp"

namespace ashlar::lua {

// {r, g, b} at idx, each in [0, 1]; `what` names it in errors.
Rgb to_rgb(lua_State* L, int idx, int arg, const std::string& what);
// The {lo, hi} table at idx, two finite numbers; `what` names it.
std::pair<double, double> to_range(lua_State* L, int idx, int arg, const std::string& what);
// The list of numbers at idx (finite or not, never NaN); `what` names it.
std::vector<double> to_numbers(lua_State* L, int idx, int arg, const std::string& what);
// The `color` option: {r, g, b} for every block, a list with one {r, g, b}
// per block, or {values = {...}, map = "viridis", range = {lo, hi}}. Empty
// when absent.
std::vector<Rgb> block_colors(lua_State* L, const OptionTable& options, int block_count);

struct BlockColoring {
  std::vector<Rgb> colors;          // as block_colors
  std::optional<ColorScale> scale;  // with values: the values, range and map
};
// The `color` option with, when it gives values, what they were mapped by.
BlockColoring block_coloring(lua_State* L, const OptionTable& options, int block_count);

}  // namespace ashlar::lua
