// ashlar.chart (result columns of parametric studies plotted against
// parameters, as PNG, SVG or PDF).
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

// Sets the functions into the table on top of the stack.
void set_chart_functions(lua_State* L);

}  // namespace ashlar::lua
