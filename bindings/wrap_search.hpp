// ashlar.tilt, ashlar.geometric_factor, ashlar.refine.
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

// Sets the functions into the table on top of the stack.
void set_search_functions(lua_State* L);

}  // namespace ashlar::lua
