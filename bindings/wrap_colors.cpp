#include "wrap_colors.hpp"

#include <algorithm>
#include <tuple>

#include "io/color_map.hpp"

namespace ashlar::lua {

namespace {

// The values table: one number per block, mapped with `map` over `range`
// (default: the values' own range, from 0 when none is negative, so that a
// magnitude's legend starts at nothing rather than at its smallest value).
ColorScale color_scale(lua_State* L, int color, int arg, int block_count) {
  const OptionTable mapped(L, color, arg, "color.", {"values", "map", "range"});
  if (mapped.push("values") != LUA_TTABLE) {
    throw ArgError(arg, "color.values: expected a list of numbers, one per block");
  }
  const int values_index = lua_gettop(L);
  if (lua_rawlen(L, values_index) != static_cast<lua_Unsigned>(block_count)) {
    throw ArgError(arg, "color.values: needs one value per block (" +
                            std::to_string(block_count) + "), got " +
                            std::to_string(lua_rawlen(L, values_index)));
  }
  std::vector<double> values;
  for (int i = 1; i <= block_count; ++i) {
    lua_rawgeti(L, values_index, i);
    if (lua_type(L, -1) != LUA_TNUMBER) {
      throw ArgError(arg, "color.values[" + std::to_string(i) + "]: expected a number, got " +
                              type_name(L, -1));
    }
    values.push_back(lua_tonumber(L, -1));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  double lo = 0.0, hi = 0.0;
  if (!values.empty()) {
    lo = std::min(*std::min_element(values.begin(), values.end()), 0.0);
    hi = *std::max_element(values.begin(), values.end());
  }
  if (mapped.push("range") != LUA_TNIL) std::tie(lo, hi) = to_range(L, -1, arg, "color.range");
  lua_pop(L, 1);
  ColorScale scale;
  scale.values = std::move(values);
  scale.lo = lo;
  scale.hi = hi;
  scale.map = mapped.string("map").value_or("viridis");
  return scale;
}

}  // namespace

Rgb to_rgb(lua_State* L, int idx, int arg, const std::string& what) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE || (lua_rawlen(L, idx) != 3 && lua_rawlen(L, idx) != 4)) {
    throw ArgError(arg, what + ": expected a colour {r, g, b} or {r, g, b, a}, got " + type_name(L, idx) +
                            (lua_type(L, idx) == LUA_TTABLE ? " of " + std::to_string(lua_rawlen(L, idx)) + " values" : ""));
  }
  double c[4] = {0.0, 0.0, 0.0, 1.0};
  const int count = static_cast<int>(lua_rawlen(L, idx));
  for (int k = 0; k < count; ++k) {
    lua_rawgeti(L, idx, k + 1);
    c[k] = check_number(L, -1, arg, (what + "[" + std::to_string(k + 1) + "]").c_str());
    lua_pop(L, 1);
    if (!(c[k] >= 0.0 && c[k] <= 1.0)) {
      throw ArgError(arg, what + ": colour components must lie in [0, 1], got " + number_text(c[k]) +
                              " (component " + std::to_string(k + 1) + ")");
    }
  }
  return {c[0], c[1], c[2], c[3]};
}

// The {lo, hi} table at idx, two finite numbers; `what` names it.
std::pair<double, double> to_range(lua_State* L, int idx, int arg, const std::string& what) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TTABLE || lua_rawlen(L, idx) != 2) {
    throw ArgError(arg, what + ": expected {lo, hi}, got " + type_name(L, idx));
  }
  lua_rawgeti(L, idx, 1);
  lua_rawgeti(L, idx, 2);
  const double lo = check_number(L, -2, arg, (what + "[1]").c_str());
  const double hi = check_number(L, -1, arg, (what + "[2]").c_str());
  lua_pop(L, 2);
  return {lo, hi};
}

std::vector<Rgb> block_colors(lua_State* L, const OptionTable& options, int block_count) {
  return block_coloring(L, options, block_count).colors;
}

BlockColoring block_coloring(lua_State* L, const OptionTable& options, int block_count) {
  const int arg = options.arg();
  if (options.push("color") == LUA_TNIL) {
    lua_pop(L, 1);
    return {};
  }
  const int color = lua_gettop(L);
  if (lua_type(L, color) != LUA_TTABLE) {
    throw ArgError(arg, "color: expected {r, g, b} (or {r, g, b, a}), a list of them per block, or "
                        "{values = {...}, map = name, range = {lo, hi}}, got " +
                            type_name(L, color));
  }
  BlockColoring coloring;
  std::vector<Rgb>& colors = coloring.colors;
  lua_rawgeti(L, color, 1);
  const int first = lua_type(L, -1);
  lua_pop(L, 1);
  if (first == LUA_TNUMBER) {
    colors.assign(block_count, to_rgb(L, color, arg, "color"));
  } else if (first == LUA_TTABLE) {
    if (lua_rawlen(L, color) != static_cast<lua_Unsigned>(block_count)) {
      throw ArgError(arg, "color: a list of colours needs one per block (" +
                              std::to_string(block_count) + "), got " +
                              std::to_string(lua_rawlen(L, color)));
    }
    for (int i = 1; i <= block_count; ++i) {
      lua_rawgeti(L, color, i);
      colors.push_back(to_rgb(L, -1, arg, "color[" + std::to_string(i) + "]"));
      lua_pop(L, 1);
    }
  } else {
    coloring.scale = color_scale(L, color, arg, block_count);
    colors = map_colors(coloring.scale->values, coloring.scale->lo, coloring.scale->hi, coloring.scale->map);
  }
  lua_pop(L, 1);
  return coloring;
}

}  // namespace ashlar::lua
