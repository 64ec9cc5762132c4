// The Lua state as the `ashlar` host program sets it up, shared by the host's
// script runner and `ashlar test`, which runs every check script in a fresh
// state of its own.
#pragma once

#include <csignal>
#include <string>
#include <vector>

#include <lua.hpp>

namespace ashlar::host {

// The command line of the script the host is running: argv as the host got
// it and the index of the script's name in it.
struct ScriptInvocation {
  std::vector<std::string> argv;
  int script = 0;
  const std::string& path() const { return argv[static_cast<std::size_t>(script)]; }
};

// Global `arg` as lua.c builds it: arg[0] is the script, arg[1..] its
// arguments, negative indices the interpreter and the options before it.
// `script` may equal argv.size() (no script): then arg[0] is the program.
void create_arg_table(lua_State* L, const std::vector<std::string>& argv, int script);

// Remembers (in the registry) the script file the host runs; a study reads
// it back to start worker states that run it again. Not called for stdin or
// -e chunks, which cannot be run again.
void remember_script(lua_State* L, const ScriptInvocation& invocation);
// The remembered script, or nullptr (the C module, stdin, -e). Throws
// lua::LuaError when Lua raises while reading it (no memory).
const ScriptInvocation* remembered_script(lua_State* L);

// Opens the standard libraries and preloads `ashlar`, with the model library
// on package.path and the collector in stock lua5.4's mode (so scripts time
// alike in both).
void open_host_libraries(lua_State* L);

// Lets a script `require` the modules beside it wherever it is run from.
void prepend_script_folder_to_path(lua_State* L, const char* script);

// lua_pcall with a traceback on errors and Ctrl-C turned into a Lua error
// (and ashlar::interrupt_requested for the engine's loops). An outermost
// call starts with no interrupt pending: a Ctrl-C stops the chunk it came
// in, not those after it.
// Expects the function and its arguments on the stack, like lua_pcall.
int call_with_traceback(lua_State* L, int argument_count, int result_count);

// Whether Ctrl-C stopped a call of call_with_traceback since the program
// started: a runner of many scripts stops instead of going on to the next.
bool interrupted();

// SIGTERM (what Slurm sends on scancel and at a job's time limit; kill's
// default) stops the running chunk at a safe point as Ctrl-C does, with the
// error "terminated (SIGTERM)"; with no chunk running, or at a second
// SIGTERM, the process ends at once. One per process, made first thing in
// main; its end puts back the handlers it found. Linux gives a signal sent
// to the process to the main thread unless that thread blocks it, so the
// handler runs there, where the Lua state is; a SIGTERM another thread
// takes is handed on to the main thread.
class TerminationWatch {
public:
  TerminationWatch();
  ~TerminationWatch();
  TerminationWatch(const TerminationWatch&) = delete;
  TerminationWatch& operator=(const TerminationWatch&) = delete;

private:
  struct sigaction saved_terminate_ {}, saved_handed_ {};
};
// Whether SIGTERM stopped the program: it then ends by SIGTERM itself
// (end_if_terminated), so its parent sees the conventional status.
bool terminated();
// Ends the process by SIGTERM when terminated(); returns otherwise.
void end_if_terminated();

}  // namespace ashlar::host
