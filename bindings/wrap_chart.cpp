// ashlar.chart: the option table's rows become engine ChartRows, the engine
// splits them into series and draws them.
#include "wrap_chart.hpp"

#include <string>
#include <vector>

#include "io/chart.hpp"
#include "io/chart_map.hpp"
#include "io/chart_rows.hpp"
#include "luax.hpp"
#include "sandbox.hpp"
#include "wrap_colors.hpp"

namespace ashlar::lua {
namespace {

std::string required_string(const OptionTable& options, const char* key, const char* what) {
  const std::optional<std::string> value = options.string(key);
  if (!value) throw ArgError(options.arg(), std::string(key) + ": required, " + what);
  return *value;
}

// A column name or a list of them; empty when absent.
std::vector<std::string> column_names(const OptionTable& options, const char* key) {
  lua_State* L = options.state();
  const int type = options.push(key);
  std::vector<std::string> names;
  const std::string expected =
      std::string(key) + ": expected a column name or a list of them, got ";
  if (type == LUA_TSTRING) {
    names.push_back(lua_tostring(L, -1));
  } else if (type == LUA_TTABLE) {
    const lua_Unsigned count = lua_rawlen(L, -1);
    if (count == 0) throw ArgError(options.arg(), expected + "an empty table");
    for (lua_Unsigned k = 1; k <= count; ++k) {
      if (lua_rawgeti(L, -1, static_cast<lua_Integer>(k)) != LUA_TSTRING) {
        throw ArgError(options.arg(), std::string(key) + "[" + std::to_string(k) +
                                          "]: expected a column name, got " + type_name(L, -1));
      }
      names.push_back(lua_tostring(L, -1));
      lua_pop(L, 1);
    }
  } else if (type != LUA_TNIL) {
    throw ArgError(options.arg(), expected + type_name(L, -1));
  }
  lua_pop(L, 1);
  return names;
}

// The value at the top of the stack as a cell.
ChartCell to_cell(lua_State* L) {
  ChartCell cell;
  switch (lua_type(L, -1)) {
    case LUA_TNUMBER:
      cell.number = lua_tonumber(L, -1);
      break;
    case LUA_TBOOLEAN:
      cell.type = ChartCell::Type::boolean;
      cell.number = lua_toboolean(L, -1) ? 1.0 : 0.0;
      break;
    case LUA_TSTRING:
      cell.type = ChartCell::Type::text;
      cell.text = lua_tostring(L, -1);
      break;
    default:
      cell.type = ChartCell::Type::other;
      cell.text = type_name(L, -1);
  }
  return cell;
}

// `data`: a list of row tables; their string keys are the columns.
std::vector<ChartRow> chart_rows(const OptionTable& options) {
  lua_State* L = options.state();
  const int type = options.push("data");
  if (type == LUA_TNIL) throw ArgError(options.arg(), "data: required, a list of row tables");
  if (type != LUA_TTABLE) {
    throw ArgError(options.arg(), "data: expected a list of row tables, got " + type_name(L, -1));
  }
  const lua_Unsigned count = lua_rawlen(L, -1);
  std::vector<ChartRow> rows(count);
  for (lua_Unsigned i = 1; i <= count; ++i) {
    if (lua_rawgeti(L, -1, static_cast<lua_Integer>(i)) != LUA_TTABLE) {
      throw ArgError(options.arg(), "data[" + std::to_string(i) + "]: expected a row table, got " +
                                        type_name(L, -1));
    }
    lua_pushnil(L);
    while (lua_next(L, -2) != 0) {
      if (lua_type(L, -2) == LUA_TSTRING) rows[i - 1][lua_tostring(L, -2)] = to_cell(L);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return rows;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (size_t k = 0; k < names.size(); ++k) text += (k ? ", " : "") + names[k];
  return text;
}

void push_chart_result(lua_State* L, const std::string& path, const RowSeries& lines) {
  lua_createtable(L, 0, 3);
  set_string(L, "path", path.c_str());
  lua_createtable(L, static_cast<int>(lines.series.size()), 0);
  for (size_t k = 0; k < lines.series.size(); ++k) {
    lua_createtable(L, 0, 2);
    set_string(L, "name", lines.series[k].name.c_str());
    lua_pushinteger(L, static_cast<lua_Integer>(lines.series[k].points.size()));
    lua_setfield(L, -2, "points");
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  lua_setfield(L, -2, "series");
  lua_pushinteger(L, lines.skipped);
  lua_setfield(L, -2, "skipped");
}

// Options of one kind of chart only, and the kind that takes them.
const std::vector<std::pair<const char*, bool>> kKindOptions = {
    {"series", false}, {"log_x", false}, {"log_y", false}, {"x_range", false},
    {"y_range", false}, {"z", true},     {"levels", true}, {"boundary", true},
    {"map", true},      {"z_label", true}, {"curves", true}};

void check_kind_options(const OptionTable& options, bool map) {
  lua_State* L = options.state();
  for (const auto& [key, for_map] : kKindOptions) {
    const bool given = options.push(key) != LUA_TNIL;
    lua_pop(L, 1);
    if (given && for_map != map) {
      throw ArgError(options.arg(), std::string(key) + ": taken by " +
                                        (for_map ? "kind = \"map\" only" : "line charts only, not kind = \"map\""));
    }
  }
}

void push_pair(lua_State* L, const char* key, double a, double b) {
  lua_createtable(L, 2, 0);
  lua_pushnumber(L, a);
  lua_rawseti(L, -2, 1);
  lua_pushnumber(L, b);
  lua_rawseti(L, -2, 2);
  lua_setfield(L, -2, key);
}

void push_map_result(lua_State* L, const std::string& path, const MapSpec& spec,
                     const MapDrawing& drawing) {
  lua_createtable(L, 0, 7);
  set_string(L, "path", path.c_str());
  lua_createtable(L, static_cast<int>(drawing.boundary.size()), 0);
  for (size_t k = 0; k < drawing.boundary.size(); ++k) {
    const std::vector<Vec2>& line = drawing.boundary[k];
    lua_createtable(L, static_cast<int>(line.size()), 0);
    for (size_t i = 0; i < line.size(); ++i) {
      lua_createtable(L, 2, 0);
      lua_pushnumber(L, line[i].x());
      lua_rawseti(L, -2, 1);
      lua_pushnumber(L, line[i].y());
      lua_rawseti(L, -2, 2);
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  }
  lua_setfield(L, -2, "boundary");
  push_pair(L, "range", drawing.lo, drawing.hi);
  push_pair(L, "x_range", drawing.frame.x.lo, drawing.frame.x.hi);
  push_pair(L, "y_range", drawing.frame.y.lo, drawing.frame.y.hi);
  lua_createtable(L, 0, 4);
  set_field(L, "left", drawing.frame.plot.left);
  set_field(L, "top", drawing.frame.plot.top);
  set_field(L, "width", drawing.frame.plot.width);
  set_field(L, "height", drawing.frame.plot.height);
  lua_setfield(L, -2, "plot");
  set_field(L, "cells", static_cast<int>(spec.grid.z.size()));
  set_field(L, "no_data", spec.grid.no_data);
}

// kind = "map": the rows' grid over x and y, coloured by z.
int chart_map(lua_State* L, const OptionTable& options, const std::string& path,
              const std::vector<ChartRow>& rows) {
  const std::string x = required_string(options, "x", "the column plotted along x");
  const std::string y = required_string(options, "y", "the column plotted along y (one column)");
  const std::string z = required_string(options, "z", "the column the colours show");
  MapSpec spec;
  spec.grid = grid_from_rows(rows, x, y, z);
  if (options.push("levels") != LUA_TNIL) spec.levels = to_numbers(L, -1, 1, "levels");
  lua_pop(L, 1);
  spec.boundary = options.number("boundary");
  if (options.push("curves") != LUA_TNIL) {
    if (!lua_istable(L, -1)) throw ArgError(1, "curves: expected a list of curves, each a list of {x, y}, got " + type_name(L, -1));
    const lua_Unsigned count = lua_rawlen(L, -1);
    for (lua_Unsigned k = 1; k <= count; ++k) {
      lua_rawgeti(L, -1, static_cast<lua_Integer>(k));
      const std::string what = "curves[" + std::to_string(k) + "]";
      if (!lua_istable(L, -1)) throw ArgError(1, what + ": expected a list of {x, y}, got " + type_name(L, -1));
      std::vector<Vec2> curve;
      const lua_Unsigned points = lua_rawlen(L, -1);
      for (lua_Unsigned i = 1; i <= points; ++i) {
        lua_rawgeti(L, -1, static_cast<lua_Integer>(i));
        const std::string point = what + "[" + std::to_string(i) + "]";
        if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2) {
          throw ArgError(1, point + ": expected {x, y}, got " + type_name(L, -1));
        }
        lua_rawgeti(L, -1, 1);
        lua_rawgeti(L, -2, 2);
        curve.emplace_back(check_number(L, -2, 1, (point + "[1]").c_str()), check_number(L, -1, 1, (point + "[2]").c_str()));
        lua_pop(L, 3);
      }
      spec.curves.push_back(std::move(curve));
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  spec.map = options.string("map").value_or(spec.map);
  spec.title = options.string("title").value_or("");
  spec.x_label = options.string("x_label").value_or(x);
  spec.y_label = options.string("y_label").value_or(y);
  spec.z_label = options.string("z_label").value_or(z);
  spec.width = image_size(options, "width", spec.width);
  spec.height = image_size(options, "height", spec.height);
  const MapDrawing drawing = draw_map(path, spec);
  return call_protected(L, 0, [&](lua_State* L) {
    push_map_result(L, path, spec, drawing);
    return 1;
  });
}

int w_chart(lua_State* L) {
  return guard(L, [&] {
    if (lua_type(L, 1) != LUA_TTABLE) {
      throw ArgError(1,
                     "expected an option table {path = ..., data = rows, x = ..., y = ...}, "
                     "got " +
                         type_name(L, 1));
    }
    const OptionTable options(L, 1,
                              {"path", "data", "x", "y", "z", "series", "kind", "title", "x_label",
                               "y_label", "z_label", "log_x", "log_y", "x_range", "y_range",
                               "levels", "boundary", "map", "curves", "width", "height"});
    const std::string path = sandbox::require_access(
        L, 1, "path", required_string(options, "path", "the file to write (.png, .svg or .pdf)"),
        sandbox::Access::write);
    const std::string kind = options.string("kind").value_or("linespoints");
    check_kind_options(options, kind == "map");
    const std::vector<ChartRow> rows = chart_rows(options);
    if (kind == "map") return chart_map(L, options, path, rows);
    ChartColumns columns;
    columns.x = required_string(options, "x", "the column plotted along x");
    columns.y = column_names(options, "y");
    if (columns.y.empty()) throw ArgError(1, "y: required, a column or a list of columns");
    columns.series = column_names(options, "series");
    ChartSpec spec;
    spec.kind = chart_kind(kind);
    spec.title = options.string("title").value_or("");
    spec.x_label = options.string("x_label").value_or(columns.x);
    spec.y_label = options.string("y_label").value_or(joined(columns.y));
    spec.log_x = options.boolean("log_x").value_or(false);
    spec.log_y = options.boolean("log_y").value_or(false);
    if (options.push("x_range") != LUA_TNIL) spec.x_range = to_range(L, -1, 1, "x_range");
    lua_pop(L, 1);
    if (options.push("y_range") != LUA_TNIL) spec.y_range = to_range(L, -1, 1, "y_range");
    lua_pop(L, 1);
    spec.width = image_size(options, "width", spec.width);
    spec.height = image_size(options, "height", spec.height);
    RowSeries lines = series_from_rows(rows, columns);
    spec.series = lines.series;
    spec.x_boolean = lines.x_boolean;
    spec.y_boolean = lines.y_boolean;
    draw_chart(path, spec);
    return call_protected(L, 0, [&](lua_State* L) {
      push_chart_result(L, path, lines);
      return 1;
    });
  });
}

}  // namespace

void set_chart_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"chart", w_chart}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
