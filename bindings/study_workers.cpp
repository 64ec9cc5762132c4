#include "study_workers.hpp"

#include <algorithm>
#include <new>
#include <optional>
#include <utility>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/process_stats.hpp"
#include "luax.hpp"
#include "sandbox.hpp"

namespace ashlar::lua {

namespace {

using study::Value;

// The registry key (by address) of a worker state's WorkerSlot: reading it
// allocates nothing, so it cannot raise.
const char kWorkerSlotKey = 0;

// Raised (by address) to unwind a worker's script once its run is kept.
const char kRunKept = 0;

// In a worker state, the study it works for and, once reached, its run.
struct WorkerSlot {
  std::string study;
  int run_ref = LUA_NOREF;
};

WorkerSlot* worker_slot(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kWorkerSlotKey);
  auto* slot = static_cast<WorkerSlot*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return slot;
}

// A row for call_run.
struct RunCall {
  int run_ref;
  const std::vector<std::string>* names;
  const std::vector<Value>* values;
};

// Under lua_pcall: calls the run function with the row's parameters, so
// that running out of memory while making them is the row's error too.
int call_run(lua_State* L) {
  const auto& call = *static_cast<const RunCall*>(lua_touserdata(L, 1));
  lua_rawgeti(L, LUA_REGISTRYINDEX, call.run_ref);
  push_parameters(L, *call.names, *call.values);
  lua_call(L, 1, 1);
  return 1;
}

// Runs rows with a Lua function kept in the registry of L.
class LuaRowWorker : public study::RowWorker {
public:
  // owns_state: close L when done (a worker thread's own state); otherwise
  // L is the script's state and a Ctrl-C in a run stops the study.
  LuaRowWorker(lua_State* L, int run_ref, std::vector<std::string> names, bool owns_state)
      : L_(L), run_ref_(run_ref), names_(std::move(names)), owns_state_(owns_state) {}
  ~LuaRowWorker() override {
    if (owns_state_) sandbox::close_state(L_);
    else luaL_unref(L_, LUA_REGISTRYINDEX, run_ref_);
  }
  LuaRowWorker(const LuaRowWorker&) = delete;
  LuaRowWorker& operator=(const LuaRowWorker&) = delete;

  study::Outcome run(const study::Task& task) override {
    study::Outcome outcome;
    outcome.id = task.id;
    const int top = lua_gettop(L_);
    RunCall call{run_ref_, &names_, &task.parameters};
    lua_pushcfunction(L_, call_run);
    lua_pushlightuserdata(L_, &call);
    const double start = monotonic_seconds();
    const int status = lua_pcall(L_, 1, 1, 0);
    outcome.seconds = monotonic_seconds() - start;
    if (status != LUA_OK) {
      // A stopped script stops the study instead of filling it with error rows.
      if (sandbox::budget_exhausted(L_)) {
        const std::string message = lua_type(L_, -1) == LUA_TSTRING ? lua_tostring(L_, -1) : "sandbox limit";
        lua_settop(L_, top);
        throw Error(message);
      }
      if (!owns_state_ && interrupt_requested()) {
        lua_settop(L_, top);
        throw Error("interrupted!");
      }
      fail(outcome, lua_type(L_, -1) == LUA_TSTRING ? lua_tostring(L_, -1)
                                                   : "(error object is a " + type_name(L_, -1) + " value)");
    } else if (!lua_istable(L_, -1)) {
      fail(outcome, "run returned a " + type_name(L_, -1) + ", expected a table of fields");
    } else {
      read_fields(outcome);
    }
    lua_settop(L_, top);
    return outcome;
  }

private:
  static void fail(study::Outcome& outcome, std::string message) {
    outcome.status = study::RunStatus::error;
    outcome.error = std::move(message);
    outcome.fields.clear();
  }

  // Fields of the table on top, sorted by name so columns come in one order.
  void read_fields(study::Outcome& outcome) {
    lua_pushnil(L_);
    while (lua_next(L_, -2)) {
      if (lua_type(L_, -2) != LUA_TSTRING) {
        const std::string key_type = type_name(L_, -2);
        lua_pop(L_, 2);
        return fail(outcome, "run returned a field with a " + key_type + " key");
      }
      const std::string name = lua_tostring(L_, -2);
      std::string problem;
      Value value = to_value(L_, -1, problem);
      lua_pop(L_, 1);
      if (!problem.empty()) {
        lua_pop(L_, 1);
        return fail(outcome, "field '" + name + "' " + problem);
      }
      outcome.fields.emplace_back(name, std::move(value));
    }
    std::sort(outcome.fields.begin(), outcome.fields.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
  }

  lua_State* L_;
  int run_ref_;
  std::vector<std::string> names_;
  bool owns_state_;
};

int do_nothing(lua_State*) { return 0; }

// Body of a worker state's script run, under lua_pcall: sets the state up
// like the host's and runs the script with its arguments.
int run_worker_script(lua_State* L) {
  const auto& invocation = *static_cast<const host::ScriptInvocation*>(lua_touserdata(L, 1));
  auto* slot = static_cast<WorkerSlot*>(lua_touserdata(L, 2));
  const bool sandboxed = sandbox::settings_of(L) != nullptr;
  if (!sandboxed) host::open_host_libraries(L);  // else they are open, restricted
  host::prepend_script_folder_to_path(L, invocation.path().c_str());
  host::create_arg_table(L, invocation.argv, invocation.script);
  if (!sandboxed) {
    // The globals the host gives a script outside a sandbox, so that the
    // script runs here as it did in the calling state.
    for (const auto& [global, module] : {std::pair{"ashlar", "ashlar"}, std::pair{"models", "ashlar.models"}}) {
      lua_getglobal(L, "require");
      lua_pushstring(L, module);
      lua_call(L, 1, 1);
      lua_setglobal(L, global);
    }
  }
  lua_pushcfunction(L, do_nothing);  // runs print in step; their output would garble the progress line
  lua_setglobal(L, "print");
  lua_pushlightuserdata(L, slot);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kWorkerSlotKey);
  if (luaL_loadfilex(L, invocation.path().c_str(), sandboxed ? "t" : nullptr) != LUA_OK) return lua_error(L);
  const int first = invocation.script + 1;
  for (std::size_t i = static_cast<std::size_t>(first); i < invocation.argv.size(); ++i)
    lua_pushstring(L, invocation.argv[i].c_str());
  lua_call(L, static_cast<int>(invocation.argv.size()) - first, 0);
  return 0;
}

// The script's state, sandboxed or not, decides its workers' states.
struct WorkerSandbox {
  std::optional<sandbox::Settings> settings;
  Clock::time_point deadline = Clock::time_point::max();
};

std::unique_ptr<study::RowWorker> start_script_worker(const host::ScriptInvocation& invocation,
                                                     const std::string& study_name,
                                                     const std::vector<std::string>& names,
                                                     const WorkerSandbox& worker_sandbox) {
  lua_State* W = worker_sandbox.settings ? sandbox::new_state(*worker_sandbox.settings, worker_sandbox.deadline)
                                         : luaL_newstate();
  if (W == nullptr) throw Error("not enough memory for a Lua state");
  WorkerSlot slot{study_name};
  lua_pushcfunction(W, run_worker_script);
  lua_pushlightuserdata(W, const_cast<host::ScriptInvocation*>(&invocation));
  lua_pushlightuserdata(W, &slot);
  const int status = lua_pcall(W, 2, 0, 0);
  const bool kept = status != LUA_OK && lua_touserdata(W, -1) == &kRunKept;
  std::string problem;
  if (!kept)
    problem = status == LUA_OK ? "the script " + invocation.path() + " ended without reaching ashlar.study{name = '" + study_name + "'}"
              : lua_type(W, -1) == LUA_TSTRING ? lua_tostring(W, -1)
                                               : "(error object is a " + type_name(W, -1) + " value)";
  lua_settop(W, 0);
  lua_pushnil(W);
  lua_rawsetp(W, LUA_REGISTRYINDEX, &kWorkerSlotKey);  // the slot goes out of scope
  if (!kept) {
    sandbox::close_state(W);
    throw Error(problem);
  }
  return std::make_unique<LuaRowWorker>(W, slot.run_ref, names, true);
}

// Under lua_pcall, with a RunModule as light userdata: require(module)
// and its field. Returns the function, or nil and why there is none; a
// failing require raises its own error.
int require_run_function(lua_State* L) {
  const auto& run = *static_cast<const RunModule*>(lua_touserdata(L, 1));
  lua_settop(L, 0);
  lua_getglobal(L, "require");
  lua_pushlstring(L, run.module.data(), run.module.size());
  lua_call(L, 1, 1);
  if (!lua_istable(L, 1)) {
    lua_pushnil(L);
    lua_pushfstring(L, "require \"%s\" gave a %s value, not a table holding the function '%s'", run.module.c_str(),
                    luaL_typename(L, 1), run.field.c_str());
    return 2;
  }
  if (lua_getfield(L, 1, run.field.c_str()) == LUA_TFUNCTION) return 1;
  lua_pushnil(L);
  if (lua_isnil(L, 2))
    lua_pushfstring(L, "module '%s' has no function '%s'", run.module.c_str(), run.field.c_str());
  else
    lua_pushfstring(L, "module '%s' has a %s value, not a function, at '%s'", run.module.c_str(), luaL_typename(L, 2),
                    run.field.c_str());
  return 2;
}

// What a module worker state copies from the script's state.
struct ModuleWorkerSetup {
  RunModule run;
  std::optional<std::string> path, cpath;  // package.path and package.cpath
  bool has_arg = false;
  std::vector<std::pair<lua_Integer, std::string>> arg;  // the strings of global `arg`
  WorkerSandbox sandbox;
};

struct ModuleWorkerStart {
  const ModuleWorkerSetup* setup;
  int run_ref = LUA_NOREF;
};

// Body of a module worker state's set-up, under lua_pcall: the libraries as
// in the host, the script state's package paths and `arg`, then the
// module's function, kept in the registry.
int open_module_worker(lua_State* W) {
  auto& start = *static_cast<ModuleWorkerStart*>(lua_touserdata(W, 1));
  const ModuleWorkerSetup& setup = *start.setup;
  lua_settop(W, 0);
  const bool sandboxed = sandbox::settings_of(W) != nullptr;
  if (!sandboxed) host::open_host_libraries(W);  // else they are open, restricted
  lua_getglobal(W, "package");
  if (setup.path) {
    lua_pushlstring(W, setup.path->data(), setup.path->size());
    lua_setfield(W, -2, "path");
  }
  if (setup.cpath && !sandboxed) {  // a sandbox loads no C modules
    lua_pushlstring(W, setup.cpath->data(), setup.cpath->size());
    lua_setfield(W, -2, "cpath");
  }
  lua_pop(W, 1);
  if (setup.has_arg) {
    lua_createtable(W, static_cast<int>(setup.arg.size()), 1);
    for (const auto& [index, text] : setup.arg) {
      lua_pushlstring(W, text.data(), text.size());
      lua_rawseti(W, -2, index);
    }
    lua_setglobal(W, "arg");
  }
  lua_pushcfunction(W, do_nothing);  // as in script worker states
  lua_setglobal(W, "print");
  lua_pushcfunction(W, require_run_function);
  lua_pushlightuserdata(W, const_cast<RunModule*>(&setup.run));
  lua_call(W, 1, 2);
  if (lua_isnil(W, -2)) return lua_error(W);  // why, on top
  lua_pop(W, 1);
  start.run_ref = luaL_ref(W, LUA_REGISTRYINDEX);
  return 0;
}

std::unique_ptr<study::RowWorker> start_module_worker(const ModuleWorkerSetup& setup,
                                                     const std::vector<std::string>& names) {
  lua_State* W = setup.sandbox.settings ? sandbox::new_state(*setup.sandbox.settings, setup.sandbox.deadline)
                                        : luaL_newstate();
  if (W == nullptr) throw Error("not enough memory for a Lua state");
  ModuleWorkerStart start{&setup};
  lua_pushcfunction(W, open_module_worker);
  lua_pushlightuserdata(W, &start);
  if (lua_pcall(W, 1, 0, 0) != LUA_OK) {
    const std::string problem =
        "run = \"" + setup.run.text + "\": " +
        (lua_type(W, -1) == LUA_TSTRING ? lua_tostring(W, -1) : "(error object is a " + type_name(W, -1) + " value)");
    sandbox::close_state(W);
    throw Error(problem);
  }
  return std::make_unique<LuaRowWorker>(W, start.run_ref, names, true);
}

}  // namespace

RunModule parse_run_module(const std::string& text) {
  const std::size_t dot = text.rfind('.');
  RunModule run{text, dot == std::string::npos ? "" : text.substr(0, dot),
                dot == std::string::npos ? "" : text.substr(dot + 1)};
  const bool empty_part = run.module.empty() || run.field.empty() || run.module.front() == '.' ||
                          run.module.back() == '.' || run.module.find("..") != std::string::npos;
  if (empty_part || text.find('\0') != std::string::npos)
    throw ArgError(1, "run: expected a function or a string \"module.function\" (the function of a module that "
                      "require finds), got \"" + text + "\"");
  return run;
}

void resolve_run_module(lua_State* L, const RunModule& run, int run_index) {
  if (!lua_checkstack(L, 4)) throw std::bad_alloc();
  lua_pushcfunction(L, require_run_function);
  lua_pushlightuserdata(L, const_cast<RunModule*>(&run));
  const int status = lua_pcall(L, 1, 2, 0);
  if (status != LUA_OK) {
    // Not the module's fault: raised as it is.
    if (status == LUA_ERRMEM || sandbox::budget_exhausted(L) || interrupt_requested()) throw LuaError();
    const std::string message = lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1)
                                                              : "(error object is a " + type_name(L, -1) + " value)";
    lua_pop(L, 1);
    throw ArgError(1, "run: \"" + run.text + "\": require \"" + run.module + "\" failed: " + message);
  }
  if (lua_isnil(L, -2)) {
    const std::string message = lua_tostring(L, -1);
    lua_pop(L, 2);
    throw ArgError(1, "run: \"" + run.text + "\": " + message);
  }
  lua_pop(L, 1);
  lua_replace(L, run_index);
}

study::WorkerFactory module_worker_factory(lua_State* L, RunModule run, std::vector<std::string> parameter_names) {
  ModuleWorkerSetup setup;
  setup.run = std::move(run);
  if (const sandbox::Settings* settings = sandbox::settings_of(L)) {
    setup.sandbox.settings = *settings;
    setup.sandbox.deadline = sandbox::deadline_of(L);
  }
  call_protected(L, 0, [&setup](lua_State* S) {
    lua_getfield(S, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
    if (lua_getfield(S, -1, "package") == LUA_TTABLE) {
      if (lua_getfield(S, -1, "path") == LUA_TSTRING) setup.path = std::string(lua_tostring(S, -1));
      lua_pop(S, 1);
      if (lua_getfield(S, -1, "cpath") == LUA_TSTRING) setup.cpath = std::string(lua_tostring(S, -1));
      lua_pop(S, 1);
    }
    lua_settop(S, 0);
    if (lua_getglobal(S, "arg") == LUA_TTABLE) {
      setup.has_arg = true;
      lua_pushnil(S);
      while (lua_next(S, 1)) {
        if (lua_isinteger(S, -2) && lua_type(S, -1) == LUA_TSTRING)
          setup.arg.emplace_back(lua_tointeger(S, -2), std::string(lua_tostring(S, -1)));
        lua_pop(S, 1);
      }
    }
    lua_settop(S, 0);
    return 0;
  });
  return [setup = std::move(setup), parameter_names = std::move(parameter_names)](int) {
    return start_module_worker(setup, parameter_names);
  };
}

Value to_value(lua_State* L, int idx, std::string& problem) {
  switch (lua_type(L, idx)) {
    case LUA_TBOOLEAN: return lua_toboolean(L, idx) != 0;
    case LUA_TNUMBER:
      if (lua_isinteger(L, idx)) return static_cast<std::int64_t>(lua_tointeger(L, idx));
      return static_cast<double>(lua_tonumber(L, idx));
    case LUA_TSTRING: {
      std::size_t size = 0;
      const char* text = lua_tolstring(L, idx, &size);
      return std::string(text, size);
    }
    default:
      problem = "is a " + type_name(L, idx) + ": numbers, booleans or strings are allowed";
      return std::monostate{};
  }
}

void push_value(lua_State* L, const Value& value) {
  if (const auto* b = std::get_if<bool>(&value)) lua_pushboolean(L, *b);
  else if (const auto* i = std::get_if<std::int64_t>(&value)) lua_pushinteger(L, static_cast<lua_Integer>(*i));
  else if (const auto* d = std::get_if<double>(&value)) lua_pushnumber(L, *d);
  else if (const auto* s = std::get_if<std::string>(&value)) lua_pushlstring(L, s->data(), s->size());
  else lua_pushnil(L);
}

void push_parameters(lua_State* L, const std::vector<std::string>& names, const std::vector<Value>& values) {
  lua_createtable(L, 0, static_cast<int>(names.size()));
  for (std::size_t i = 0; i < names.size(); ++i) {
    push_value(L, values[i]);
    lua_setfield(L, -2, names[i].c_str());
  }
}

std::unique_ptr<study::RowWorker> script_state_worker(lua_State* L, int run_index,
                                                     std::vector<std::string> parameter_names) {
  int run_ref = LUA_NOREF;
  lua_pushvalue(L, run_index);
  call_protected(L, 1, [&run_ref](lua_State* S) {
    run_ref = luaL_ref(S, LUA_REGISTRYINDEX);
    return 0;
  });
  return std::make_unique<LuaRowWorker>(L, run_ref, std::move(parameter_names), false);
}

study::WorkerFactory worker_state_factory(lua_State* L, host::ScriptInvocation invocation, std::string study_name,
                                          std::vector<std::string> parameter_names) {
  WorkerSandbox worker_sandbox;
  if (const sandbox::Settings* settings = sandbox::settings_of(L)) {
    worker_sandbox.settings = *settings;
    worker_sandbox.deadline = sandbox::deadline_of(L);
  }
  return [invocation = std::move(invocation), study_name = std::move(study_name),
          parameter_names = std::move(parameter_names), worker_sandbox = std::move(worker_sandbox)](int) {
    return start_script_worker(invocation, study_name, parameter_names, worker_sandbox);
  };
}

bool is_worker_state(lua_State* L) { return worker_slot(L) != nullptr; }

bool works_for(lua_State* L, const std::string& study_name) {
  const WorkerSlot* slot = worker_slot(L);
  return slot != nullptr && slot->study == study_name;
}

int keep_run(lua_State* L, int idx) {
  WorkerSlot* slot = worker_slot(L);
  lua_pushvalue(L, idx);
  slot->run_ref = luaL_ref(L, LUA_REGISTRYINDEX);
  lua_pushlightuserdata(L, const_cast<char*>(&kRunKept));
  return lua_error(L);
}

}  // namespace ashlar::lua
