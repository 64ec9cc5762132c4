// ashlar.load_factor and ashlar.friction_demand: how far a structure is
// from collapse.
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

// Sets the functions into the table on top of the stack.
void set_margin_functions(lua_State* L);

}  // namespace ashlar::lua
