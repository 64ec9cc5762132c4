// ashlar.fea and its result type "ashlar.FeaResult": linear-elastic FEA with
// contact ties and constraint relaxation (engine/fea).
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

void register_FeaResult(lua_State* L);
// ashlar.fea: set into the table on top of the stack.
void set_fea_functions(lua_State* L);

}  // namespace ashlar::lua
