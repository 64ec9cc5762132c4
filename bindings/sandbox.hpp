// Lua states for untrusted scripts: `ashlar --sandbox script.lua` and
// `ashlar.sandbox{...}` run scripts in them.
//
// A sandboxed state has
//   - no os.execute, io.popen, io.tmpfile, os.tmpname, os.getenv,
//     os.setlocale, os.exit, package.loadlib, string.dump, no C modules and
//     no debug library (each stub raises "<name> is not allowed in the
//     sandbox");
//   - text chunks only: load, loadfile, dofile and require refuse binary
//     (precompiled) chunks;
//   - files (io.open, io.lines, io.input, io.output, os.remove, os.rename,
//     dofile, loadfile, require and every ashlar function that takes a path)
//     only under the allowed folders, after symlinks and ".." are resolved;
//     a relative path is taken from the base folder (the script's), not
//     from the current folder; a refused io.open, os.remove, os.rename or
//     loadfile returns nil and the reason as stock Lua does when the system
//     refuses, the others raise it;
//   - a cap on its Lua heap, kept by the state's allocator;
//   - an instruction budget and a wall-clock deadline, checked every
//     kHookInterval instructions by a count hook and, for the deadline, by
//     the engine's long C++ loops, which poll ashlar::interrupt_requested().
// Exceeding a limit is a Lua error naming the limit. Once a limit is
// exceeded, every further instruction raises it again, so pcall cannot
// swallow it.
//
// What it does not contain: memory the C++ engine allocates (models, solver
// matrices) is outside the Lua heap, and a C function that never returns
// (a pathological string pattern) is not reached by the hook. The `ashlar
// --sandbox` host therefore also caps the process's data segment and ends
// the process at a hard deadline; run untrusted scripts through it (in a
// process of their own) when that matters.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <lua.hpp>

#include "core/clock.hpp"

namespace ashlar::sandbox {

// What a sandboxed state may do. Folders may be relative (to the current
// folder) and need not be canonical; they are resolved when the state is
// made. Zero means "no limit" for every limit.
struct Settings {
  std::vector<std::string> read_folders;   // read-only, besides the write folders
  std::vector<std::string> write_folders;  // read and write
  // Where the script's relative paths start: the script's folder, or empty
  // for the current folder (a chunk with no file).
  std::string base_folder;
  std::size_t memory_bytes = std::size_t{1} << 30;  // Lua heap of each state, bytes
  std::uint64_t instructions = 0;                   // Lua VM instructions of each state
  double seconds = 0;                               // wall-clock seconds from the start
};

// Which limit stopped a script.
enum class Limit { none, memory, instructions, time };
const char* limit_name(Limit limit);  // "none", "memory", "instructions", "time"

// What a sandboxed state used so far.
struct Usage {
  std::size_t memory_bytes = 0;       // Lua heap now
  std::size_t memory_peak_bytes = 0;  // Lua heap at its largest
  std::uint64_t instructions = 0;     // to within kHookInterval
  Limit exceeded = Limit::none;       // the first limit reached, if any
};

constexpr int kHookInterval = 1000;  // instructions between checks

// A new state with the standard libraries restricted as above and `ashlar`
// preloaded (its metatables protected from getmetatable). The clock of
// `settings.seconds` starts now, unless `deadline` (shared by a study's
// worker states) is given. Throws ashlar::Error when a folder does not exist
// or no memory is left. Close it with close_state.
lua_State* new_state(const Settings& settings);
lua_State* new_state(const Settings& settings, Clock::time_point deadline);

// Puts the budget hook back on L after another hook (the host's Ctrl-C
// hook) replaced it; nothing for a state that is not sandboxed.
void restore_hook(lua_State* L);

// lua_close for any state; also frees a sandboxed state's bookkeeping.
void close_state(lua_State* L);

// A userdata of a sandboxed state (`size` bytes at `memory`) whose
// finalizer releases what it holds (an engine object): at the memory cap
// Lua may have no memory to call a finalizer, skips it (a warning, as for
// any error in a finalizer) and frees the userdata, and its object would
// leak. The state's allocator calls `release` on such a userdata before
// freeing it. forget_userdata once the finalizer ran. Both do nothing for
// a state that is not sandboxed.
void watch_userdata(lua_State* L, void* memory, std::size_t size, void (*release)(void* memory));
void forget_userdata(lua_State* L, const void* memory, std::size_t size);

// The sandbox of L (or of the state L is a thread of), or nullptr when L is
// not sandboxed.
const Settings* settings_of(lua_State* L);
// The deadline of a sandboxed state (Clock::time_point::max() when none).
Clock::time_point deadline_of(lua_State* L);
Usage usage_of(lua_State* L);

// Marks L's time limit as exceeded when its deadline has passed (a script
// that ends right after the engine stopped at the deadline runs too few
// instructions for the hook to see it); returns the limit's message, or ""
// when the deadline has not passed.
std::string deadline_problem(lua_State* L);

// Whether L's instruction budget or deadline is spent: every instruction it
// runs now raises the limit's error.
bool budget_exhausted(lua_State* L);

// A Lua error message, rewritten to name the limit when one was exceeded
// (Lua's own message for a refused allocation is only "not enough memory";
// it becomes "chunk:line: sandbox: memory limit ...", the line the main
// thread's Lua code was running).
std::string explain_error(lua_State* L, const std::string& message);

// The file that `path`, as a script of L gives it, names: a relative path
// is taken from the sandbox's base folder (the result is then absolute).
// `path` itself for a state that is not sandboxed.
std::string script_path(lua_State* L, const std::string& path);

enum class Access { read, write };
// Empty when L may access `path` (as a script of L gives it: see
// script_path); otherwise why not, naming the path, what it resolves to
// and the allowed folders. Always empty for a state that is not sandboxed.
std::string access_problem(lua_State* L, const std::string& path, Access access);

// The file `path` names (script_path) when L may access it; otherwise
// throws a lua::ArgError for argument `arg` naming `what` (e.g. "db").
[[nodiscard]] std::string require_access(lua_State* L, int arg, const std::string& what, const std::string& path,
                                         Access access);

// The file that a string argument names (script_path), when L may access
// it; otherwise a lua::ArgError naming the argument (`what`) and the
// problem.
std::string checked_path(lua_State* L, int arg, const char* what, Access access);

}  // namespace ashlar::sandbox
