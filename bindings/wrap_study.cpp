// ashlar.study and its helpers: arguments read here, the study run by the
// engine (study/study_job), its rows by Lua functions (study_workers).
#include "wrap_study.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "host_state.hpp"
#include "luax.hpp"
#include "sandbox.hpp"
#include "study/cluster.hpp"
#include "study/study_job.hpp"
#include "study_workers.hpp"

namespace ashlar::lua {

namespace {

using study::Value;

const char* const kStudyMetatable = "ashlar.Study";

struct StudyObject {
  std::string name;
  std::string db;  // empty: in memory
  study::StudyTable table;
  study::StudyRunInfo info;
};

Value checked_value(lua_State* L, int idx, const std::string& what) {
  std::string problem;
  Value value = to_value(L, idx, problem);
  if (!problem.empty()) throw ArgError(1, what + " " + problem);
  // ±inf are values (friction = math.huge: no sliding); NaN is none.
  if (const auto* d = std::get_if<double>(&value); d && std::isnan(*d)) throw ArgError(1, what + " is NaN");
  return value;
}

std::string key_name(lua_State* L, int idx) {
  return lua_type(L, idx) == LUA_TSTRING ? lua_tostring(L, idx) : "[" + type_name(L, idx) + " key]";
}

// params: a list of rows ({ {t = 1, n = 16}, ... }) or a grid
// ({ t = {...}, n = {...} }, a scalar standing for a one-value axis).
study::ParameterRows read_params(lua_State* L, int idx) {
  if (!lua_istable(L, idx)) throw ArgError(1, "params: expected a table, got " + type_name(L, idx));
  const lua_Integer count = static_cast<lua_Integer>(lua_rawlen(L, idx));
  if (count > 0) {
    study::ParameterRows rows;
    for (lua_Integer r = 1; r <= count; ++r) {
      lua_rawgeti(L, idx, r);
      const std::string row_name = "params[" + std::to_string(r) + "]";
      if (!lua_istable(L, -1)) throw ArgError(1, row_name + ": expected a table of parameter values, got " + type_name(L, -1));
      std::vector<std::pair<std::string, Value>> values;
      lua_pushnil(L);
      while (lua_next(L, -2)) {
        if (lua_type(L, -2) != LUA_TSTRING) throw ArgError(1, row_name + ": " + key_name(L, -2) + " is not a parameter name");
        values.emplace_back(lua_tostring(L, -2), checked_value(L, -1, row_name + "." + lua_tostring(L, -2)));
        lua_pop(L, 1);
      }
      lua_pop(L, 1);
      std::sort(values.begin(), values.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      std::vector<std::string> names;
      std::vector<Value> row;
      for (auto& [name, value] : values) {
        names.push_back(name);
        row.push_back(std::move(value));
      }
      if (r == 1) rows.names = names;
      else if (names != rows.names)
        throw ArgError(1, row_name + " has other parameters than params[1]");
      rows.rows.push_back(std::move(row));
    }
    lua_pushnil(L);
    while (lua_next(L, idx)) {
      const bool in_list = lua_isinteger(L, -2) && lua_tointeger(L, -2) >= 1 && lua_tointeger(L, -2) <= count;
      if (!in_list) throw ArgError(1, "params: a list of rows cannot also have the key " + key_name(L, -2));
      lua_pop(L, 1);
    }
    return study::checked(std::move(rows));
  }
  std::vector<std::pair<std::string, std::vector<Value>>> axes;
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    if (lua_type(L, -2) != LUA_TSTRING) throw ArgError(1, "params: " + key_name(L, -2) + " is not a parameter name");
    const std::string name = lua_tostring(L, -2);
    std::vector<Value> values;
    if (lua_istable(L, -1)) {
      const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
      if (n == 0) throw ArgError(1, "params." + name + ": an empty list");
      for (lua_Integer i = 1; i <= n; ++i) {
        lua_rawgeti(L, -1, i);
        values.push_back(checked_value(L, -1, "params." + name + "[" + std::to_string(i) + "]"));
        lua_pop(L, 1);
      }
    } else {
      values.push_back(checked_value(L, -1, "params." + name));
    }
    axes.emplace_back(name, std::move(values));
    lua_pop(L, 1);
  }
  if (axes.empty()) throw ArgError(1, "params: no parameters");
  return study::grid(std::move(axes));
}

void set_integer(lua_State* L, const char* key, std::size_t value) {
  lua_pushinteger(L, static_cast<lua_Integer>(value));
  lua_setfield(L, -2, key);
}

std::shared_ptr<StudyObject> check_study(lua_State* L, int idx) {
  return check_boxed<StudyObject>(L, idx, kStudyMetatable, "Study");
}

void push_study(lua_State* L, StudyObject study) {
  push_boxed(L, std::make_shared<StudyObject>(std::move(study)), kStudyMetatable);
}

int w_study(lua_State* L) {
  int run_index = 0;  // of a worker state's study, whose run it keeps
  const int result = guard(L, [&]() -> int {
    const OptionTable options(L, 1, {"name", "params", "run", "db", "workers", "progress", "rerun_errors", "log_interval"});
    const std::optional<std::string> name = options.string("name");
    if (!name) throw ArgError(1, "name: a study needs a name (its table in the database)");
    study::StudyJob job;
    job.name = *name;
    if (const std::string problem = study::study_name_problem(job.name); !problem.empty()) throw ArgError(1, "name: " + problem);
    if (options.push("params") == LUA_TNIL) throw ArgError(1, "params: missing");
    job.rows = read_params(L, lua_gettop(L));
    lua_pop(L, 1);
    // run: a function, or "module.function" that workers require instead
    // of running the script again.
    const int run_type = options.push("run");
    if (run_type != LUA_TFUNCTION && run_type != LUA_TSTRING)
      throw ArgError(1, "run: expected a function or a string \"module.function\", got " + type_name(L, -1));
    run_index = lua_gettop(L);
    std::optional<RunModule> run_module;
    if (run_type == LUA_TSTRING) {
      std::size_t size = 0;
      const char* text = lua_tolstring(L, run_index, &size);
      run_module = parse_run_module(std::string(text, size));
    }
    job.db = options.string("db").value_or("");
    if (!job.db.empty()) job.db = sandbox::require_access(L, 1, "db", job.db, sandbox::Access::write);
    job.workers = static_cast<int>(
        options.whole("workers", 0, 4096, "0 (all cores) or a number of workers").value_or(job.workers));
    job.progress = options.boolean("progress").value_or(job.progress);
    job.log_interval = options.positive("log_interval", job.log_interval);
    job.rerun_errors = options.boolean("rerun_errors").value_or(job.rerun_errors);

    StudyObject study;
    study.name = job.name;
    study.db = job.db;
    if (is_worker_state(L)) {
      if (works_for(L, job.name)) {
        if (run_module) resolve_run_module(L, *run_module, run_index);
        return -1;  // keep the run, outside this guard
      }
      // Another study of the script: its results, as the coordinator stored them.
      if (!study.db.empty()) study.table = study::StudyStore(study.db, true).read_study(study.name);
      push_study(L, std::move(study));
      return 1;
    }

    study::WorkerFactory thread_workers;
    if (run_module) {
      // Required here first: a bad module or function is this call's error,
      // before the store opens or a worker starts.
      resolve_run_module(L, *run_module, run_index);
      thread_workers = module_worker_factory(L, *run_module, job.rows.names);
    } else {
      // Worker threads run the host's script again: none without one.
      const host::ScriptInvocation* script = host::remembered_script(L);
      if (script == nullptr && cluster::size() > 1)
        throw ArgError(1, "under MPI, a study needs the ashlar host running a script file");
      if (script == nullptr && job.workers > 1)
        throw ArgError(1, "workers: more than 1 needs the ashlar host running a script file (worker threads run "
                          "the script again; the C module, stdin and -e chunks cannot be), or run = "
                          "\"module.function\"");
      if (script) thread_workers = worker_state_factory(L, *script, job.name, job.rows.names);
    }
    const std::unique_ptr<study::RowWorker> script_worker = script_state_worker(L, run_index, job.rows.names);
    study::StudyResult result = study::run_study_job(job, *script_worker, thread_workers);
    study.table = std::move(result.table);
    study.info = std::move(result.info);
    push_study(L, std::move(study));
    return 1;
  });
  if (result >= 0) return result;
  return keep_run(L, run_index);
}

// ashlar.load_study{db = path, name = name}: a stored study's rows, read only.
int w_load_study(lua_State* L) {
  return guard(L, [&] {
    const OptionTable options(L, 1, {"db", "name"});
    StudyObject study;
    study.db = options.string("db").value_or("");
    study.name = options.string("name").value_or("");
    if (study.db.empty()) throw ArgError(1, "db: missing (the study database's path)");
    study.db = sandbox::require_access(L, 1, "db", study.db, sandbox::Access::read);
    if (study.name.empty()) throw ArgError(1, "name: missing (the study's name)");
    study.table = study::StudyStore(study.db, true).read_study(study.name);
    push_study(L, std::move(study));
    return 1;
  });
}

// ashlar.rank(): this process's MPI rank and the job's size (0, 1 outside MPI).
int w_rank(lua_State* L) {
  lua_pushinteger(L, cluster::rank());
  lua_pushinteger(L, cluster::size());
  return 2;
}

int w_range(lua_State* L) {
  return guard(L, [&] {
    const double first = check_number(L, 1, "first");
    const double last = check_number(L, 2, "last");
    const lua_Integer count = check_integer(L, 3, "count");
    if (count < 1 || count > 10'000'000) throw ArgError(3, "count must be in [1, 10^7], got " + std::to_string(count));
    const std::vector<double> values = study::linear_range(first, last, static_cast<int>(count));
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, static_cast<int>(values.size()), 0);
      for (std::size_t i = 0; i < values.size(); ++i) {
        lua_pushnumber(L, values[i]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
      }
      return 1;
    });
  });
}

// ashlar.latin_hypercube(axes, {samples, seed}): axes name = {min = a, max = b}
// (an interval) or a list of levels.
int w_latin_hypercube(lua_State* L) {
  return guard(L, [&] {
    if (!lua_istable(L, 1)) throw ArgError(1, "expected a table of parameters, got " + type_name(L, 1));
    const OptionTable options(L, 2, {"samples", "seed"});
    const lua_Integer samples = options.whole("samples", 1, 10'000'000, "a whole number of samples in [1, 10^7]").value_or(0);
    if (samples == 0) throw ArgError(2, "samples: missing");
    const lua_Integer seed = options.whole("seed", LUA_MININTEGER, LUA_MAXINTEGER, "an integer").value_or(1);
    std::vector<study::SampledAxis> axes;
    lua_pushnil(L);
    while (lua_next(L, 1)) {
      if (lua_type(L, -2) != LUA_TSTRING) throw ArgError(1, key_name(L, -2) + " is not a parameter name");
      study::SampledAxis axis;
      axis.name = lua_tostring(L, -2);
      if (!lua_istable(L, -1)) throw ArgError(1, axis.name + ": expected {min = a, max = b} or a list of levels, got " + type_name(L, -1));
      const int axis_index = lua_gettop(L);
      if (lua_rawlen(L, axis_index) > 0) {
        for (lua_Integer i = 1; i <= static_cast<lua_Integer>(lua_rawlen(L, axis_index)); ++i) {
          lua_rawgeti(L, axis_index, i);
          axis.levels.push_back(checked_value(L, -1, axis.name + "[" + std::to_string(i) + "]"));
          lua_pop(L, 1);
        }
      } else {
        const OptionTable interval(L, axis_index, 1, axis.name + ".", {"min", "max"});
        const std::optional<double> min = interval.number("min"), max = interval.number("max");
        if (!min || !max || *min > *max) throw ArgError(1, axis.name + ": expected {min = a, max = b} with a <= b");
        axis.min = *min;
        axis.max = *max;
      }
      axes.push_back(std::move(axis));
      lua_pop(L, 1);
    }
    const study::ParameterRows rows = study::latin_hypercube(std::move(axes), static_cast<int>(samples),
                                                              static_cast<std::uint64_t>(seed));
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, static_cast<int>(rows.rows.size()), 0);
      for (std::size_t r = 0; r < rows.rows.size(); ++r) {
        push_parameters(L, rows.names, rows.rows[r]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(r + 1));
      }
      return 1;
    });
  });
}

void push_row(lua_State* L, const study::StudyTable& table, const study::Row& row) {
  push_parameters(L, table.parameter_names, row.task.parameters);
  if (!row.finished) {
    set_string(L, "run_status", "pending");
    return;
  }
  for (const auto& [name, value] : row.outcome.fields) {
    push_value(L, value);
    lua_setfield(L, -2, name.c_str());
  }
  set_string(L, "run_status", study::status_name(row.outcome.status));
  if (!row.outcome.error.empty()) set_string(L, "run_error", row.outcome.error.c_str());
  set_field(L, "run_seconds", row.outcome.seconds);
  lua_pushinteger(L, row.outcome.worker);
  lua_setfield(L, -2, "run_worker");
}

int w_study_rows(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<StudyObject> kept = check_study(L, 1);
    const StudyObject& study = *kept;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, static_cast<int>(study.table.rows.size()), 0);
      for (std::size_t r = 0; r < study.table.rows.size(); ++r) {
        push_row(L, study.table, study.table.rows[r]);
        lua_rawseti(L, -2, static_cast<lua_Integer>(r + 1));
      }
      return 1;
    });
  });
}

// st:chart{...}: ashlar.chart with the study's rows as data.
int w_study_chart(lua_State* L) {
  guard(L, [&] {
    check_study(L, 1);
    if (!lua_istable(L, 2)) throw ArgError(2, "expected a table of chart options, got " + type_name(L, 2));
    if (get_field(L, 2, "data") != LUA_TNIL) throw ArgError(2, "data: not an option here, the study gives the rows");
    lua_pop(L, 1);
    return 0;
  });
  lua_getfield(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);
  if (lua_getfield(L, -1, "ashlar") != LUA_TTABLE) return luaL_error(L, "chart: the ashlar library is not loaded");
  lua_getfield(L, -1, "chart");
  lua_newtable(L);  // the options, with data added
  lua_pushnil(L);
  while (lua_next(L, 2)) {
    lua_pushvalue(L, -2);
    lua_insert(L, -2);
    lua_settable(L, -4);
  }
  lua_pushcfunction(L, w_study_rows);
  lua_pushvalue(L, 1);
  lua_call(L, 1, 1);
  lua_setfield(L, -2, "data");
  if (lua_pcall(L, 1, 1, 0) != LUA_OK) {
    // ashlar.chart called from here cannot see the script's line: add it.
    luaL_where(L, 1);
    lua_insert(L, -2);
    lua_concat(L, 2);
    return lua_error(L);
  }
  return 1;
}

int w_study_csv(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<StudyObject> kept = check_study(L, 1);
    const StudyObject& study = *kept;
    const std::string path = sandbox::checked_path(L, 2, "path", sandbox::Access::write);
    if (cluster::rank() == 0) write_file_atomically(path, study::csv_text(study.table));  // one writer per MPI job
    return push_string(L, path);
  });
}

int w_study_info(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<StudyObject> kept = check_study(L, 1);
    const StudyObject& study = *kept;
    const std::size_t finished = study.table.finished_count(), errors = study.table.error_count();
    return call_protected(L, 0, [&](lua_State* L) {
      lua_createtable(L, 0, 13);
      set_string(L, "name", study.name.c_str());
      if (!study.db.empty()) set_string(L, "db", study.db.c_str());
      set_integer(L, "rows", study.table.rows.size());
      set_integer(L, "ok", finished - errors);
      set_integer(L, "errors", errors);
      set_integer(L, "pending", study.table.rows.size() - finished);
      set_integer(L, "ran", study.info.ran);
      set_integer(L, "elsewhere", study.info.elsewhere);
      set_field(L, "seconds", study.info.seconds);
      set_field(L, "runs_per_second", study.info.seconds > 0 ? static_cast<double>(study.info.ran) / study.info.seconds : 0.0);
      set_integer(L, "workers", static_cast<std::size_t>(study.info.workers));
      lua_createtable(L, static_cast<int>(study.info.worker_failures.size()), 0);
      for (std::size_t i = 0; i < study.info.worker_failures.size(); ++i) {
        lua_pushstring(L, study.info.worker_failures[i].c_str());
        lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
      }
      lua_setfield(L, -2, "worker_failures");
      return 1;
    });
  });
}

int w_study_name(lua_State* L) {
  return guard(L, [&] {
    return push_string(L, check_study(L, 1)->name);
  });
}

int w_study_len(lua_State* L) {
  return guard(L, [&] {
    lua_pushinteger(L, static_cast<lua_Integer>(check_study(L, 1)->table.rows.size()));
    return 1;
  });
}

int w_study_tostring(lua_State* L) {
  if (push_if_closed<StudyObject>(L, kStudyMetatable, "Study")) return 1;
  return guard(L, [&] {
    const std::shared_ptr<StudyObject> kept = check_study(L, 1);
    const StudyObject& study = *kept;
    return call_protected(L, 0, [&](lua_State* L) {
      lua_pushfstring(L, "Study '%s' (%d rows, %d finished, %d errors)", study.name.c_str(),
                      static_cast<int>(study.table.rows.size()), static_cast<int>(study.table.finished_count()),
                      static_cast<int>(study.table.error_count()));
      return 1;
    });
  });
}

int w_study_gc(lua_State* L) { return release_boxed<StudyObject>(L, kStudyMetatable); }

}  // namespace

void register_Study(lua_State* L) {
  static const luaL_Reg methods[] = {{"rows", w_study_rows}, {"csv", w_study_csv}, {"chart", w_study_chart}, {"info", w_study_info},
                                     {"name", w_study_name}, {nullptr, nullptr}};
  static const luaL_Reg metamethods[] = {{"__len", w_study_len},
                                         {"__tostring", w_study_tostring},
                                         {"__gc", w_study_gc},
                                         {"__close", w_study_gc},
                                         {nullptr, nullptr}};
  register_type(L, kStudyMetatable, methods, metamethods);
}

void set_study_functions(lua_State* L) {
  static const luaL_Reg functions[] = {{"study", w_study}, {"range", w_range},
                                       {"latin_hypercube", w_latin_hypercube}, {"load_study", w_load_study},
                                       {"rank", w_rank},       {nullptr, nullptr}};
  luaL_setfuncs(L, functions, 0);
}

}  // namespace ashlar::lua
