// Setting up a Lua state the way the `ashlar` host does, so that a study's
// worker threads can run the host's script again in states of their own.
#pragma once

#include <string>
#include <vector>

#include <lua.hpp>

namespace ashlar::lua {

// The command line of the script the host is running: argv as the host got
// it and the index of the script's name in it.
struct ScriptInvocation {
  std::vector<std::string> argv;
  int script = 0;
  const std::string& path() const { return argv[static_cast<std::size_t>(script)]; }
};

// Opens the standard libraries, preloads `ashlar`, puts the model library
// and the folder of `script` (when not null) on package.path.
void set_up_state(lua_State* L, const char* script);

// Prepends the folder of `script` to package.path, so a script can require
// the modules beside it wherever it is run from.
void prepend_script_folder(lua_State* L, const char* script);

// Global `arg` as lua.c builds it: arg[0] is the script, arg[1..] its
// arguments, negative indices the interpreter and the options before it.
// `script` may equal argv.size() (no script): then arg[0] is the program.
void create_arg_table(lua_State* L, const std::vector<std::string>& argv, int script);

// Remembers (in the registry) the script file the host runs; studies read
// it back to start worker states. Not called for stdin or -e chunks, which
// cannot be run again.
void remember_script(lua_State* L, const ScriptInvocation& invocation);
// The remembered script, or nullptr (the C module, stdin, -e).
const ScriptInvocation* remembered_script(lua_State* L);

}  // namespace ashlar::lua
