// The Lua side of a study's rows: study values to and from Lua, the worker
// that runs rows with the script's `run` function, and the worker states of
// worker threads, made one of two ways:
//   - run = a function: a worker state runs the host's script again; when it
//     reaches the ashlar.study call its thread works for, that call keeps the
//     `run` function (keep_run) and unwinds the rest of the script with a
//     sentinel error; the state then stays alive only to run rows.
//   - run = "module.function": a worker state requires the module with the
//     calling state's package.path and keeps the function; the script does
//     not run in it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <lua.hpp>

#include "host_state.hpp"
#include "study/study_runner.hpp"
#include "study/study_value.hpp"

namespace ashlar::lua {

// A scalar at idx, or an empty value and, in `problem`, why it is not one.
study::Value to_value(lua_State* L, int idx, std::string& problem);
void push_value(lua_State* L, const study::Value& value);
// A table {name = value, ...} of one row's parameters.
void push_parameters(lua_State* L, const std::vector<std::string>& names, const std::vector<study::Value>& values);

// Runs rows with the function at stack index run_index in the script's own
// state L: a Ctrl-C in a run stops the study.
std::unique_ptr<study::RowWorker> script_state_worker(lua_State* L, int run_index,
                                                     std::vector<std::string> parameter_names);

// Makes worker states like the script's state L (its sandbox, if any),
// each running the host's script `invocation` until it reaches
// ashlar.study{name = study_name}. Reads L now; the factory touches no
// state but the ones it makes, so worker threads may call it.
study::WorkerFactory worker_state_factory(lua_State* L, host::ScriptInvocation invocation, std::string study_name,
                                          std::vector<std::string> parameter_names);

// run = "module.function": the module to require and the function in it,
// split at the last dot ("a.b.c": module "a.b", function "c").
struct RunModule {
  std::string text;    // as given, for messages
  std::string module;  // for require
  std::string field;   // the function's key in the module's table
};
// Throws ArgError (argument 1, option `run`) when `text` is not of that form.
RunModule parse_run_module(const std::string& text);

// In L (the script's state): require(run.module)[run.field], which must be
// a function, replaces the string at stack index run_index. Throws ArgError
// naming the option and its value when the module cannot be required (with
// require's message) or has no such function; a sandbox's limit, Ctrl-C or
// running out of memory meanwhile is raised as it is (LuaError).
void resolve_run_module(lua_State* L, const RunModule& run, int run_index);

// Makes worker states like the script's state L (its sandbox, if any) that
// require run.module with L's package.path (and, outside a sandbox,
// package.cpath) as they are now, with L's `arg` strings, and run rows with
// the function run.field. Reads L now; the factory touches no state but the
// ones it makes, so worker threads may call it.
study::WorkerFactory module_worker_factory(lua_State* L, RunModule run, std::vector<std::string> parameter_names);

// In a worker state: whether the script reached the study its thread works
// for, named `study_name`. Only then may keep_run be called.
bool works_for(lua_State* L, const std::string& study_name);
// In a worker state that works for the study: keeps the run function at
// stack index idx and raises the sentinel that unwinds the script (as
// lua_error, `return keep_run(L, idx);`). The caller holds no C++ object
// with a destructor.
int keep_run(lua_State* L, int idx);
// Whether L is a worker state (running the script for a study).
bool is_worker_state(lua_State* L);

}  // namespace ashlar::lua
