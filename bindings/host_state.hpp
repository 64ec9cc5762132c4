// The Lua state as the `ashlar` host program sets it up, shared by the host's
// script runner and `ashlar test`, which runs every check script in a fresh
// state of its own.
#pragma once

#include <lua.hpp>

namespace ashlar::host {

// Opens the standard libraries and preloads `ashlar`, with the model library
// on package.path and the collector in stock lua5.4's mode (so scripts time
// alike in both).
void open_host_libraries(lua_State* L);

// Lets a script `require` the modules beside it wherever it is run from.
void prepend_script_folder_to_path(lua_State* L, const char* script);

// lua_pcall with a traceback on errors and Ctrl-C turned into a Lua error.
// Expects the function and its arguments on the stack, like lua_pcall.
int call_with_traceback(lua_State* L, int argument_count, int result_count);

// Whether Ctrl-C stopped a call of call_with_traceback since the program
// started: a runner of many scripts stops instead of going on to the next.
bool interrupted();

}  // namespace ashlar::host
