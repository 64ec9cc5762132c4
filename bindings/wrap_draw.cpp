// ashlar.draw (elevation drawings with the line of thrust) and ashlar.legend
// (colour-map legend images).
#include "wrap_draw.hpp"

#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "io/color_map.hpp"
#include "io/color_legend.hpp"
#include "io/drawing.hpp"
#include "luax.hpp"
#include "sandbox.hpp"
#include "wrap_colors.hpp"
#include "wrap_Result.hpp"
#include "wrap_Structure.hpp"
#include "wrap_margins.hpp"

namespace ashlar::lua {
namespace {

// The `view` option: "front" (looking along +y at the x-z plane), "side"
// (looking along -x at the y-z plane) or a horizontal direction {x, y, z}.
Vec3 view_direction(const OptionTable& options) {
  lua_State* L = options.state();
  const int type = options.push("view");
  Vec3 direction(0.0, 1.0, 0.0);
  if (type == LUA_TSTRING) {
    const std::string name = lua_tostring(L, -1);
    if (name == "side") {
      direction = Vec3(-1.0, 0.0, 0.0);
    } else if (name != "front") {
      throw ArgError(options.arg(), "view: expected 'front', 'side' or a horizontal direction "
                                    "{x, y, z}, got '" + name + "'");
    }
  } else if (type == LUA_TTABLE) {
    direction = to_vec3(L, -1, options.arg(), "view");
  } else if (type != LUA_TNIL) {
    throw ArgError(options.arg(), "view: expected 'front', 'side' or a horizontal direction "
                                  "{x, y, z}, got " + type_name(L, -1));
  }
  lua_pop(L, 1);
  return direction;
}

int w_draw(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<Structure> structure = luax_checkStructure(L, 1);
    const Structure& s = *structure;
    const std::string path = sandbox::checked_path(L, 2, "path", sandbox::Access::write);
    const OptionTable options(L, 3, {"result", "thrust", "forces", "force_scale", "view", "width",
                                     "height", "title", "color", "thrust_color", "tolerance", "limit", "mechanism",
                                     "mechanism_color"});
    ElevationOptions drawing;
    drawing.block_colors = block_colors(L, options, s.size());
    drawing.contact.tolerance = options.positive("tolerance", 0.0, true);
    const ResultOption result = result_with_mechanism(L, options, s, drawing.contact);
    drawing.result = result.analysis.get();
    // An analysis's drawing keeps its look; a load factor's is of its limit state.
    if (options.boolean("limit").value_or(result.factor.has_value())) drawing.limit = result.limit();
    drawing.mechanism = result.mechanism();
    drawing.mechanism_scale = options.positive("mechanism", 0.0, true);
    if (options.push("mechanism_color") != LUA_TNIL) {
      drawing.mechanism_color = to_rgb(L, -1, options.arg(), "mechanism_color");
    }
    lua_pop(L, 1);
    // Drawing a result mostly means drawing its line of thrust.
    drawing.thrust = options.boolean("thrust").value_or(drawing.result != nullptr);
    drawing.forces = options.boolean("forces").value_or(false);
    drawing.force_scale = options.positive("force_scale", 0.0, true);
    drawing.view_direction = view_direction(options);
    drawing.width = image_size(options, "width", drawing.width);
    drawing.height = image_size(options, "height", drawing.height);
    drawing.title = options.string("title").value_or("");
    if (options.push("thrust_color") != LUA_TNIL) {
      drawing.thrust_color = to_rgb(L, -1, options.arg(), "thrust_color");
    }
    lua_pop(L, 1);
    draw_elevation(s, path, drawing);
    return 0;
  });
}

int w_legend(lua_State* L) {
  return guard(L, [&] {
    const std::string path = sandbox::checked_path(L, 1, "path", sandbox::Access::write);
    const OptionTable options(L, 2,
                              {"map", "range", "values", "label", "width", "height", "orientation"});
    LegendOptions legend;
    legend.map = options.string("map").value_or(legend.map);
    if (options.push("range") != LUA_TNIL) {
      std::tie(legend.lo, legend.hi) = to_range(L, -1, 2, "range");
    } else if (options.push("values") != LUA_TNIL) {
      std::tie(legend.lo, legend.hi) = value_range(to_numbers(L, -1, 2, "values"));
      if (!(legend.lo < legend.hi)) {
        throw ArgError(2, "values: their range [" + number_text(legend.lo) + ", " +
                              number_text(legend.hi) +
                              "] is empty; give range = {lo, hi}");
      }
      lua_pop(L, 1);
    } else {
      throw ArgError(2, "range: expected {lo, hi}, the values at the ends of the colour bar "
                        "(or values = {...}, the values the colours stand for)");
    }
    lua_pop(L, 1);
    legend.label = options.string("label").value_or("");
    const std::string orientation = options.string("orientation").value_or("vertical");
    if (orientation != "vertical" && orientation != "horizontal") {
      throw ArgError(2, "orientation: expected 'vertical' or 'horizontal', got '" + orientation +
                            "'");
    }
    legend.vertical = orientation == "vertical";
    legend.width = image_size(options, "width", 0);
    legend.height = image_size(options, "height", 0);
    draw_legend(path, legend);
    return 0;
  });
}

}  // namespace

void set_draw_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"draw", w_draw}, {"legend", w_legend}, {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
