// The host links the C++ build of Lua, where a Lua error unwinds C++ frames
// as an exception; but ashlar.sandbox and a study's worker states set up
// states with these functions in the C module too, whose Lua raises errors
// by longjmp. So no function here calls Lua while a C++ object with a
// destructor is alive.
#include "host_state.hpp"

#include <pthread.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <new>
#include <string>
#include <system_error>

#include "ashlar_lua.hpp"
#include "core/interrupt.hpp"
#include "luax.hpp"
#include "sandbox.hpp"

namespace ashlar::host {

namespace {

// The state running a chunk, for the signal handlers; chunks run one at a
// time, on the main thread.
std::atomic<lua_State*> g_running_state{nullptr};
volatile std::sig_atomic_t g_interrupted = 0;
std::atomic<bool> g_terminated{false};
pthread_t g_main_thread;
// A SIGTERM taken by another thread is handed to the main thread, which
// runs Lua, with this signal, whose handler nothing else installs.
constexpr int kTerminationSignal = SIGUSR1;

void stop_at_hook(lua_State* L, lua_Debug*) {
  lua_sethook(L, nullptr, 0, 0);
  sandbox::restore_hook(L);
  luaL_error(L, g_terminated ? "terminated (SIGTERM)" : "interrupted!");
}

// A signal handler may not touch the Lua state except to set a hook, so the
// error is raised from the hook at the next instruction Lua runs.
void stop_running_chunk() {
  ashlar::interrupt_requested() = true;  // for C++ loops that run no Lua, e.g. a study's coordinator
  if (lua_State* L = g_running_state.load()) {
    lua_sethook(L, stop_at_hook, LUA_MASKCALL | LUA_MASKRET | LUA_MASKLINE | LUA_MASKCOUNT, 1);
  }
}

void on_interrupt(int signal_number) {
  std::signal(signal_number, SIG_DFL);  // a second Ctrl-C kills a script stuck in C code
  g_interrupted = 1;
  stop_running_chunk();
}

// Ends the process by SIGTERM, as if nothing had caught it.
[[noreturn]] void die_by_sigterm() {
  std::signal(SIGTERM, SIG_DFL);
  std::raise(SIGTERM);
  std::_Exit(128 + SIGTERM);  // not reached
}

void on_termination(int) {
  // A chunk to stop, the first time: the main thread stops it and ends the
  // process when it is done. Else nothing is left to save.
  if (g_terminated.exchange(true) || g_running_state.load() == nullptr) die_by_sigterm();
  if (pthread_equal(pthread_self(), g_main_thread)) {
    stop_running_chunk();
  } else {
    pthread_kill(g_main_thread, kTerminationSignal);
  }
}

void on_handed_termination(int) { stop_running_chunk(); }

int add_traceback(lua_State* L) {
  const char* message = lua_tostring(L, 1);
  if (message == nullptr) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING)
      message = lua_tostring(L, -1);
    else
      message = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  luaL_traceback(L, L, message, 1);
  return 1;
}

const char* const kScriptKey = "ashlar.script";
const char* const kScriptMetatable = "ashlar.ScriptInvocation";

int release_invocation(lua_State* L) {
  if (auto* invocation = static_cast<ScriptInvocation*>(luaL_testudata(L, 1, kScriptMetatable))) {
    invocation->~ScriptInvocation();
    lua_pushnil(L);
    lua_setmetatable(L, 1);  // destroyed once, however often __gc runs
  }
  return 0;
}

}  // namespace

void create_arg_table(lua_State* L, const std::vector<std::string>& argv, int script) {
  const int argc = static_cast<int>(argv.size());
  if (script >= argc) script = 0;
  lua_createtable(L, argc - script - 1, script + 1);
  for (int i = 0; i < argc; ++i) {
    lua_pushstring(L, argv[static_cast<std::size_t>(i)].c_str());
    lua_rawseti(L, -2, i - script);
  }
  lua_setglobal(L, "arg");
}

void remember_script(lua_State* L, const ScriptInvocation& invocation) {
  void* memory = lua_newuserdatauv(L, sizeof(ScriptInvocation), 0);
  new (memory) ScriptInvocation(invocation);
  if (luaL_newmetatable(L, kScriptMetatable)) {
    lua_pushcfunction(L, release_invocation);
    lua_setfield(L, -2, "__gc");
  }
  lua_setmetatable(L, -2);
  lua_setfield(L, LUA_REGISTRYINDEX, kScriptKey);
}

const ScriptInvocation* remembered_script(lua_State* L) {
  lua::get_field(L, LUA_REGISTRYINDEX, kScriptKey);  // protected: the key may need memory
  auto* invocation = static_cast<ScriptInvocation*>(luaL_testudata(L, -1, kScriptMetatable));
  lua_pop(L, 1);
  return invocation;
}

void open_host_libraries(lua_State* L) {
  luaL_checkversion(L);
  luaL_openlibs(L);
  lua_gc(L, LUA_GCGEN, 0, 0);

  lua_getglobal(L, "package");
  lua_getfield(L, -1, "preload");
  lua_pushcfunction(L, ashlar_open_library);
  lua_setfield(L, -2, "ashlar");
  lua_pop(L, 2);
  ashlar_add_model_path(L);
}

namespace {

// The absolute folder of `script`, without a trailing '/'.
std::string script_folder(const char* script) {
  namespace fs = std::filesystem;
  fs::path folder = fs::path(script).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ignored;  // a relative folder still works while the cwd stays
  const fs::path absolute = fs::absolute(folder, ignored);
  if (!absolute.empty()) folder = absolute.lexically_normal();
  std::string directory = folder.string();
  if (directory.size() > 1 && directory.back() == '/') directory.pop_back();
  return directory;
}

}  // namespace

void prepend_script_folder_to_path(lua_State* L, const char* script) {
  if (!lua::push_message(L, script_folder(script).c_str())) lua_error(L);
  const int folder = lua_gettop(L);
  lua_getglobal(L, "package");
  lua_pushvalue(L, folder);
  lua_pushliteral(L, "/?.lua;");
  lua_pushvalue(L, folder);
  lua_pushliteral(L, "/?/init.lua;");
  lua_getfield(L, folder + 1, "path");
  if (!lua_isstring(L, -1)) {
    lua_pop(L, 1);
    lua_pushliteral(L, "");
  }
  lua_concat(L, 5);
  lua_setfield(L, folder + 1, "path");
  lua_settop(L, folder - 1);
}

int call_with_traceback(lua_State* L, int argument_count, int result_count) {
  const int handler_index = lua_gettop(L) - argument_count;
  lua_pushcfunction(L, add_traceback);
  lua_insert(L, handler_index);
  // A sandboxed script run by ashlar.sandbox nests in the host's script.
  lua_State* const outer_state = g_running_state.load();
  // A Ctrl-C stops the chunk it came in, not the ones typed after it; a
  // SIGTERM stops every chunk after it too.
  if (!outer_state && !g_terminated) ashlar::interrupt_requested() = false;
  g_running_state = L;
  const auto outer_handler = std::signal(SIGINT, on_interrupt);
  const int status = lua_pcall(L, argument_count, result_count, handler_index);
  std::signal(SIGINT, outer_handler == SIG_ERR ? SIG_DFL : outer_handler);
  g_running_state = outer_state;
  lua_remove(L, handler_index);
  return status;
}

bool interrupted() { return g_interrupted != 0 || g_terminated; }

TerminationWatch::TerminationWatch() {
  g_main_thread = pthread_self();
  struct sigaction handler {};
  sigemptyset(&handler.sa_mask);
  handler.sa_flags = SA_RESTART;
  handler.sa_handler = on_handed_termination;
  sigaction(kTerminationSignal, &handler, &saved_handed_);
  handler.sa_handler = on_termination;
  sigaction(SIGTERM, &handler, &saved_terminate_);
}

TerminationWatch::~TerminationWatch() {
  sigaction(SIGTERM, &saved_terminate_, nullptr);
  sigaction(kTerminationSignal, &saved_handed_, nullptr);
}

bool terminated() { return g_terminated.load(); }

void end_if_terminated() {
  if (terminated()) die_by_sigterm();
}

}  // namespace ashlar::host
