// ashlar.optimize: geometry (vertex positions) or a generator's parameters
// moved down the structural gradient until the structure stands.
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

// ashlar.optimize: set into the table on top of the stack.
void set_optimize_functions(lua_State* L);

}  // namespace ashlar::lua
