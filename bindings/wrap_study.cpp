// ashlar.study and its helpers. A study with several workers runs the
// host's script again in one Lua state per worker thread: when such a state
// reaches the ashlar.study call its thread works for, the call keeps the
// `run` function and unwinds the rest of the script with a sentinel error;
// the state then stays alive only to run rows.
#include "wrap_study.hpp"

#include <algorithm>
#include <thread>

#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/process_stats.hpp"
#include "core/atomic_file.hpp"
#include "luax.hpp"
#include "sandbox.hpp"
#include "host_state.hpp"
#include "study/cluster.hpp"
#include "study/mpi_workers.hpp"
#include "study/study_runner.hpp"

namespace ashlar::lua {

namespace {

using host::ScriptInvocation;
using host::remembered_script;

using study::Value;

const char* const kStudyMetatable = "ashlar.Study";
const char* const kWorkerSlotKey = "ashlar.study_worker";

// Raised (by address) to unwind a worker's script once its run is kept.
const char kRunKept = 0;

struct StudyObject {
  std::string name;
  std::string db;  // empty: in memory
  study::StudyTable table;
  study::StudyRunInfo info;
};

// In a worker state, the study it works for and, once reached, its run.
struct WorkerSlot {
  std::string study;
  int run_ref = LUA_NOREF;
};

WorkerSlot* worker_slot(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, kWorkerSlotKey);
  auto* slot = static_cast<WorkerSlot*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return slot;
}

// A scalar at idx, or an empty string in `problem` saying why it is not one.
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

Value checked_value(lua_State* L, int idx, const std::string& what) {
  std::string problem;
  Value value = to_value(L, idx, problem);
  if (!problem.empty()) throw ArgError(1, what + " " + problem);
  // ±inf are values (friction = math.huge: no sliding); NaN is none.
  if (const auto* d = std::get_if<double>(&value); d && std::isnan(*d)) throw ArgError(1, what + " is NaN");
  return value;
}

void push_value(lua_State* L, const Value& value) {
  if (const auto* b = std::get_if<bool>(&value)) lua_pushboolean(L, *b);
  else if (const auto* i = std::get_if<std::int64_t>(&value)) lua_pushinteger(L, static_cast<lua_Integer>(*i));
  else if (const auto* d = std::get_if<double>(&value)) lua_pushnumber(L, *d);
  else if (const auto* s = std::get_if<std::string>(&value)) lua_pushlstring(L, s->data(), s->size());
  else lua_pushnil(L);
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

void push_parameters(lua_State* L, const std::vector<std::string>& names, const std::vector<Value>& values) {
  lua_createtable(L, 0, static_cast<int>(names.size()));
  for (std::size_t i = 0; i < names.size(); ++i) {
    push_value(L, values[i]);
    lua_setfield(L, -2, names[i].c_str());
  }
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
    lua_rawgeti(L_, LUA_REGISTRYINDEX, run_ref_);
    push_parameters(L_, names_, task.parameters);
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
  const auto& invocation = *static_cast<const ScriptInvocation*>(lua_touserdata(L, 1));
  auto* slot = static_cast<WorkerSlot*>(lua_touserdata(L, 2));
  const bool sandboxed = sandbox::settings_of(L) != nullptr;
  if (!sandboxed) host::open_host_libraries(L);  // else they are open, restricted
  host::prepend_script_folder_to_path(L, invocation.path().c_str());
  host::create_arg_table(L, invocation.argv, invocation.script);
  lua_pushcfunction(L, do_nothing);  // runs print in step; their output would garble the progress line
  lua_setglobal(L, "print");
  lua_pushlightuserdata(L, slot);
  lua_setfield(L, LUA_REGISTRYINDEX, kWorkerSlotKey);
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

WorkerSandbox worker_sandbox(lua_State* L) {
  WorkerSandbox worker;
  if (const sandbox::Settings* settings = sandbox::settings_of(L)) {
    worker.settings = *settings;
    worker.deadline = sandbox::deadline_of(L);
  }
  return worker;
}

std::unique_ptr<study::RowWorker> start_script_worker(const ScriptInvocation& invocation, const std::string& study_name,
                                                     const std::vector<std::string>& names,
                                                     const WorkerSandbox& worker_sandbox) {
  lua_State* W = worker_sandbox.settings ? sandbox::new_state(*worker_sandbox.settings, worker_sandbox.deadline)
                                         : luaL_newstate();
  if (W == nullptr) throw Error("not enough memory for a Lua state");
  WorkerSlot slot{study_name};
  lua_pushcfunction(W, run_worker_script);
  lua_pushlightuserdata(W, const_cast<ScriptInvocation*>(&invocation));
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
  lua_setfield(W, LUA_REGISTRYINDEX, kWorkerSlotKey);  // the slot goes out of scope
  if (!kept) {
    sandbox::close_state(W);
    throw Error(problem);
  }
  return std::make_unique<LuaRowWorker>(W, slot.run_ref, names, true);
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

// The threads to run `pending` rows with, from the workers option; `script`
// is the host's script, which worker states run again (nullptr: none).
int thread_count(const ScriptInvocation* script, lua_Integer workers, std::size_t pending) {
  if (workers > 1 && script == nullptr)
    throw ArgError(1, "workers: more than 1 needs the ashlar host running a script file (worker threads run "
                      "the script again; the C module, stdin and -e chunks cannot be)");
  lua_Integer threads = workers;
  if (workers == 0) threads = script ? std::max(1u, std::thread::hardware_concurrency()) : 1;
  threads = std::min<lua_Integer>(threads, static_cast<lua_Integer>(pending));
  return threads <= 1 ? 0 : static_cast<int>(threads);  // one worker: the script's own state
}

int w_study(lua_State* L) {
  const int result = guard(L, [&]() -> int {
    const OptionTable options(L, 1, {"name", "params", "run", "db", "workers", "progress", "rerun_errors", "log_interval"});
    const std::optional<std::string> name = options.string("name");
    if (!name) throw ArgError(1, "name: a study needs a name (its table in the database)");
    if (const std::string problem = study::study_name_problem(*name); !problem.empty()) throw ArgError(1, "name: " + problem);
    if (options.push("params") == LUA_TNIL) throw ArgError(1, "params: missing");
    const study::ParameterRows rows = read_params(L, lua_gettop(L));
    lua_pop(L, 1);
    if (options.push("run") != LUA_TFUNCTION) throw ArgError(1, "run: expected a function, got " + type_name(L, -1));
    const int run_index = lua_gettop(L);
    StudyObject study;
    study.name = *name;
    study.db = options.string("db").value_or("");
    if (!study.db.empty()) sandbox::require_access(L, 1, "db", study.db, sandbox::Access::write);
    const lua_Integer workers = options.whole("workers", 0, 4096, "0 (all cores) or a number of workers").value_or(0);
    study::StudySettings settings;
    settings.progress = options.boolean("progress").value_or(true);
    settings.log_interval = options.positive("log_interval", 10.0);
    const bool rerun_errors = options.boolean("rerun_errors").value_or(false);

    if (WorkerSlot* slot = worker_slot(L)) {
      if (slot->study == study.name) {
        lua_pushvalue(L, run_index);
        slot->run_ref = luaL_ref(L, LUA_REGISTRYINDEX);
        return -1;  // raise kRunKept, outside this guard
      }
      // Another study of the script: its results, as the coordinator stored them.
      if (!study.db.empty()) study.table = study::StudyStore(study.db, true).read_study(study.name);
      push_study(L, std::move(study));
      return 1;
    }

    lua_pushvalue(L, run_index);
    LuaRowWorker script_worker(L, luaL_ref(L, LUA_REGISTRYINDEX), rows.names, false);
    if (cluster::size() > 1 && cluster::rank() > 0) {
      study.table = study::work_for_rank_zero(study.name, script_worker);
      push_study(L, std::move(study));
      return 1;
    }
    study::StudyStore store(study.db);
    study.table = store.open_study(study.name, rows, rerun_errors);
    const std::size_t pending = study.table.rows.size() - study.table.finished_count();
    const ScriptInvocation* script = remembered_script(L);
    std::optional<study::RankWorkers> ranks;
    if (cluster::size() > 1) {
      ranks.emplace(study.name);
      settings.threads = 1;  // one row at a time on every rank, rank 0's beside its coordinating thread
      if (script == nullptr) throw ArgError(1, "under MPI, a study needs the ashlar host running a script file");
    } else {
      settings.threads = thread_count(script, workers, pending);
    }
    // Copied: the threads must not read the registry of the script's state.
    const ScriptInvocation invocation = script ? *script : ScriptInvocation{};
    const WorkerSandbox sandbox = worker_sandbox(L);
    const study::WorkerFactory start_worker = [&invocation, &study, &rows, &sandbox](int) {
      return start_script_worker(invocation, study.name, rows.names, sandbox);
    };
    study.info = study::run_study(store, study.name, study.table, settings, &script_worker, start_worker,
                                  ranks ? &*ranks : nullptr);
    study.table = store.open_study(study.name, rows);
    if (ranks) ranks->finish(study.table);
    if (study.info.interrupted)
      throw Error("interrupted! study '" + study.name + "' keeps its " + std::to_string(study.table.finished_count()) +
                  " finished rows of " + std::to_string(study.table.rows.size()) + "; run the script again to go on");
    push_study(L, std::move(study));
    return 1;
  });
  if (result >= 0) return result;
  lua_pushlightuserdata(L, const_cast<char*>(&kRunKept));
  return lua_error(L);
}

// ashlar.load_study{db = path, name = name}: a stored study's rows, read only.
int w_load_study(lua_State* L) {
  return guard(L, [&] {
    const OptionTable options(L, 1, {"db", "name"});
    StudyObject study;
    study.db = options.string("db").value_or("");
    study.name = options.string("name").value_or("");
    if (study.db.empty()) throw ArgError(1, "db: missing (the study database's path)");
    sandbox::require_access(L, 1, "db", study.db, sandbox::Access::read);
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
    lua_createtable(L, static_cast<int>(values.size()), 0);
    for (std::size_t i = 0; i < values.size(); ++i) {
      lua_pushnumber(L, values[i]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    return 1;
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
    lua_createtable(L, static_cast<int>(rows.rows.size()), 0);
    for (std::size_t r = 0; r < rows.rows.size(); ++r) {
      push_parameters(L, rows.names, rows.rows[r]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(r + 1));
    }
    return 1;
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
    lua_createtable(L, static_cast<int>(study.table.rows.size()), 0);
    for (std::size_t r = 0; r < study.table.rows.size(); ++r) {
      push_row(L, study.table, study.table.rows[r]);
      lua_rawseti(L, -2, static_cast<lua_Integer>(r + 1));
    }
    return 1;
  });
}

// st:chart{...}: ashlar.chart with the study's rows as data.
int w_study_chart(lua_State* L) {
  guard(L, [&] {
    check_study(L, 1);
    if (!lua_istable(L, 2)) throw ArgError(2, "expected a table of chart options, got " + type_name(L, 2));
    if (lua_getfield(L, 2, "data") != LUA_TNIL) throw ArgError(2, "data: not an option here, the study gives the rows");
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
    lua_pushstring(L, path.c_str());
    return 1;
  });
}

int w_study_info(lua_State* L) {
  return guard(L, [&] {
    const std::shared_ptr<StudyObject> kept = check_study(L, 1);
    const StudyObject& study = *kept;
    const std::size_t finished = study.table.finished_count(), errors = study.table.error_count();
    lua_createtable(L, 0, 12);
    set_string(L, "name", study.name.c_str());
    if (!study.db.empty()) set_string(L, "db", study.db.c_str());
    set_integer(L, "rows", study.table.rows.size());
    set_integer(L, "ok", finished - errors);
    set_integer(L, "errors", errors);
    set_integer(L, "pending", study.table.rows.size() - finished);
    set_integer(L, "ran", study.info.ran);
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
}

int w_study_name(lua_State* L) {
  return guard(L, [&] {
    lua_pushstring(L, check_study(L, 1)->name.c_str());
    return 1;
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
    lua_pushfstring(L, "Study '%s' (%d rows, %d finished, %d errors)", study.name.c_str(),
                    static_cast<int>(study.table.rows.size()), static_cast<int>(study.table.finished_count()),
                    static_cast<int>(study.table.error_count()));
    return 1;
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
