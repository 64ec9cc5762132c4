// Lua bindings of parametric studies: ashlar.study, ashlar.range,
// ashlar.latin_hypercube and the Study type.
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

void register_Study(lua_State* L);
// Adds study, range and latin_hypercube to the library table on top of the stack.
void set_study_functions(lua_State* L);

}  // namespace ashlar::lua
