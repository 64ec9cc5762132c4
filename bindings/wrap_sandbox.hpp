// ashlar.sandbox (an untrusted script run in a sandboxed state of its own).
#pragma once

#include <lua.hpp>

namespace ashlar::lua {

// Sets the functions into the table on top of the stack.
void set_sandbox_functions(lua_State* L);

}  // namespace ashlar::lua
