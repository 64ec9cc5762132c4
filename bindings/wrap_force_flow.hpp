// ashlar.trace_loads.
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

// Sets the functions into the table on top of the stack.
void set_force_flow_functions(lua_State* L);

}  // namespace ashlar::lua
