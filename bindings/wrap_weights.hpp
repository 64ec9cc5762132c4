// ashlar.weight_sensitivity, load_capacity, necessary_weights, important_weights.
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

// Sets the functions into the table on top of the stack.
void set_weights_functions(lua_State* L);

}  // namespace ashlar::lua
