// ashlar.draw (elevation drawings) and legend (colour-map legend images).
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

// Sets the functions into the table on top of the stack.
void set_draw_functions(lua_State* L);

}  // namespace ashlar::lua
