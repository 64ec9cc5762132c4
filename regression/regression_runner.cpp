// Links the C++ build of Lua, so a Lua error unwinds C++ frames as an
// exception: locals with destructors are safe in every function below.
#include "regression_runner.hpp"

#include <algorithm>
#include <chrono>
#include <clocale>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include <lua.hpp>

#include "host_state.hpp"
#include "core/atomic_file.hpp"
#include "regression_check.hpp"
#include "regression_golden.hpp"

namespace ashlar::regression {

namespace {

namespace fs = std::filesystem;

const char* const kGoldenFileName = "golden.json";
const char* const kUpdateHint = "run `ashlar test --update`";

struct Arguments {
  bool update = false;
  bool help = false;
  fs::path folder = ".";
  std::vector<std::string> filters;  // parts of script file names
  std::string error;                 // set when the arguments are wrong
};

// Options may come anywhere before `--`; the first other argument is the
// folder, the rest filter the scripts.
Arguments parse_arguments(int argc, char** argv) {
  Arguments arguments;
  bool options_ended = false, has_folder = false;
  for (int i = 2; i < argc; ++i) {
    const std::string argument = argv[i];
    if (!options_ended && argument.size() > 1 && argument[0] == '-') {
      if (argument == "--") {
        options_ended = true;
      } else if (argument == "--update") {
        arguments.update = true;
      } else if (argument == "--help" || argument == "-h") {
        arguments.help = true;
      } else {
        arguments.error = "unrecognized option '" + argument + "'";
        break;
      }
    } else if (!has_folder) {
      arguments.folder = argument;
      has_folder = true;
    } else {
      arguments.filters.push_back(argument);
    }
  }
  return arguments;
}

// The check scripts of the folder: its *.lua files (not hidden ones, such as
// an editor's lock files), sorted by name, keeping those whose names contain
// one of the filters. Helpers that scripts `require` go in a subfolder.
std::vector<std::string> list_scripts(const Arguments& arguments) {
  const std::string folder = arguments.folder.string();
  std::error_code error;
  if (!fs::exists(arguments.folder, error)) throw std::runtime_error("no such folder '" + folder + "'");
  if (!fs::is_directory(arguments.folder, error)) throw std::runtime_error("'" + folder + "' is not a folder");
  std::vector<std::string> scripts;
  fs::directory_iterator entries(arguments.folder, error);
  if (error) throw std::runtime_error("cannot list '" + folder + "': " + error.message());
  for (const fs::directory_entry& entry : entries) {
    const std::string name = entry.path().filename().string();
    if (entry.path().extension() == ".lua" && name[0] != '.' && entry.is_regular_file(error)) scripts.push_back(name);
  }
  if (scripts.empty()) throw std::runtime_error("no check scripts (*.lua) in '" + folder + "'");
  std::sort(scripts.begin(), scripts.end());
  if (arguments.filters.empty()) return scripts;
  std::vector<std::string> selected;
  for (const std::string& filter : arguments.filters) {
    const auto matches = [&](const std::string& name) { return name.find(filter) != std::string::npos; };
    if (std::none_of(scripts.begin(), scripts.end(), matches))
      throw std::runtime_error("no check script in '" + folder + "' matches '" + filter + "'");
  }
  for (const std::string& name : scripts) {
    const auto in_name = [&](const std::string& filter) { return name.find(filter) != std::string::npos; };
    if (std::any_of(arguments.filters.begin(), arguments.filters.end(), in_name)) selected.push_back(name);
  }
  return selected;
}

struct ScriptRun {
  std::string file;      // the script's name in the folder: its key in the golden file
  std::string path;      // folder/file, as messages show it
  const char* program;   // the ashlar program, arg[-1] as the host gives it
  CheckRecorder recorder;
  std::optional<std::string> error;  // what the script raised, with its traceback
  double seconds = 0.0;
};

std::string error_message(lua_State* L) {
  const char* message = lua_tostring(L, -1);
  return message ? message : std::string("(error object is a ") + luaL_typename(L, -1) + " value)";
}

// os.exit would end the whole run, with the status the script chose, before
// the other scripts and the summary: a false pass. In a check script it is
// an error instead.
int refuse_exit(lua_State* L) {
  return luaL_error(L, "os.exit: a check script cannot end the run (raise an error to fail it)");
}

// Sets up a state as the host does for a script run without arguments, then
// runs the script; called under lua_pcall, so that even a memory error
// during set-up is reported.
int set_up_and_run(lua_State* L) {
  auto& run = *static_cast<ScriptRun*>(lua_touserdata(L, 1));
  host::open_host_libraries(L);
  preload_regression_module(L, run.recorder);
  host::prepend_script_folder_to_path(L, run.path.c_str());
  lua_getglobal(L, "os");
  lua_pushcfunction(L, refuse_exit);
  lua_setfield(L, -2, "exit");
  lua_pop(L, 1);
  lua_createtable(L, 0, 2);
  lua_pushstring(L, run.program);
  lua_rawseti(L, -2, -1);
  lua_pushstring(L, run.path.c_str());
  lua_rawseti(L, -2, 0);
  lua_setglobal(L, "arg");
  int status = luaL_loadfile(L, run.path.c_str());
  if (status == LUA_OK) status = host::call_with_traceback(L, 0, 0);
  if (status != LUA_OK) run.error = error_message(L);
  return 0;
}

void run_script(ScriptRun& run) {
  const auto start = std::chrono::steady_clock::now();
  lua_State* L = luaL_newstate();
  if (L == nullptr) {
    run.error = "cannot create a Lua state: not enough memory";
    return;
  }
  lua_pushcfunction(L, set_up_and_run);
  lua_pushlightuserdata(L, &run);
  if (lua_pcall(L, 1, 0, 0) != LUA_OK) run.error = error_message(L);
  lua_close(L);
  // os.setlocale in a script changes the whole process's: numbers printed
  // and written after it must still have decimal points.
  std::setlocale(LC_ALL, "C");
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Totals {
  int passed = 0;
  int failed = 0;
  int added = 0;
  int changed = 0;
  int removed = 0;

  void fail(const std::string& line) {
    ++failed;
    std::printf("  FAIL %s\n", line.c_str());
  }
};

// The error's first line, then its traceback indented below it.
void report_error(const std::string& error, Totals& totals) {
  ++totals.failed;
  std::string indented;
  for (const char c : error) indented += c == '\n' ? std::string("\n      ") : std::string(1, c);
  std::printf("  ERROR %s\n", indented.c_str());
}

std::string describe(const Check& check) { return check.where + ": " + quote(check.name) + ": "; }

bool records(const ScriptRun& run, const std::string& name) {
  const auto& checks = run.recorder.checks();
  return std::any_of(checks.begin(), checks.end(), [&](const Check& check) { return check.name == name; });
}

// Judges one script's checks against its golden values `old` and, with
// `update`, makes `next` (a copy of `old`) the values to write. A script
// that failed changes nothing: the checks it did not reach are not stale.
void judge_script(const ScriptRun& run, const std::string& golden_path, const ScriptGolden& old,
                  ScriptGolden& next, bool update, Totals& totals) {
  if (run.error) report_error(*run.error, totals);
  const auto& checks = run.recorder.checks();
  if (!run.error && checks.empty())
    totals.fail(run.path + ": records no checks (call the function that `require \"ashlar.regression\"` returns)");
  const bool writing = update && !run.error;
  for (const Check& check : checks) {
    if (const auto violation = reference_mismatch(check)) {
      totals.fail(describe(check) + *violation + (writing ? " (not written)" : ""));
      continue;
    }
    const auto golden = old.find(check.name);
    const auto difference =
        golden == old.end() ? std::nullopt : golden_mismatch(golden->second, check.value, check.tolerance);
    if (!writing) {
      if (golden == old.end())
        totals.fail(describe(check) + "no golden value (" + kUpdateHint + ")");
      else if (difference)
        totals.fail(describe(check) + *difference);
      else
        ++totals.passed;
      continue;
    }
    ++totals.passed;
    // A value within its tolerance keeps the golden one, so that updates on
    // other machines do not churn the last digits.
    if (golden == old.end()) {
      ++totals.added;
      std::printf("  added %s: %s\n", quote(check.name).c_str(), format_value(check.value).c_str());
    } else if (difference) {
      ++totals.changed;
      std::printf("  changed %s: %s -> %s\n", quote(check.name).c_str(), format_value(golden->second).c_str(),
                  format_value(check.value).c_str());
    } else {
      continue;
    }
    next[check.name] = check.value;
  }
  if (run.error || checks.empty()) return;
  for (const auto& [name, value] : old) {
    if (records(run, name)) continue;
    if (writing) {
      ++totals.removed;
      std::printf("  removed %s: %s\n", quote(name).c_str(), format_value(value).c_str());
      next.erase(name);
    } else {
      totals.fail(golden_path + ": " + quote(run.file) + " / " + quote(name) + ": stale golden value " +
                  format_value(value) + ", the script no longer records it (" + kUpdateHint + " to remove it)");
    }
  }
}

// Golden values of scripts that are no longer in the folder.
void judge_vanished_scripts(const std::vector<std::string>& scripts, const std::string& golden_path,
                            const GoldenValues& old, GoldenValues& next, bool update, Totals& totals) {
  for (const auto& [script, values] : old) {
    if (std::binary_search(scripts.begin(), scripts.end(), script) || values.empty()) continue;
    std::printf("%s: no such script\n", script.c_str());
    for (const auto& [name, value] : values) {
      if (update) {
        ++totals.removed;
        std::printf("  removed %s: %s\n", quote(name).c_str(), format_value(value).c_str());
      } else {
        totals.fail(golden_path + ": " + quote(script) + " / " + quote(name) + ": stale golden value " +
                    format_value(value) + ", there is no such script (" + kUpdateHint + " to remove it)");
      }
    }
    if (update) next.erase(script);
  }
}

int run_suite(const char* program, const Arguments& arguments) {
  const std::vector<std::string> scripts = list_scripts(arguments);
  const std::string golden_path = (arguments.folder / kGoldenFileName).string();
  const GoldenValues old = read_golden_file(golden_path);
  GoldenValues next = old;
  Totals totals;
  static const ScriptGolden kNoValues;
  for (const std::string& file : scripts) {
    ScriptRun run{file, (arguments.folder / file).string(), program, CheckRecorder(), std::nullopt, 0.0};
    run_script(run);
    std::printf("%s: %zu checks, %.2f s\n", file.c_str(), run.recorder.checks().size(), run.seconds);
    const auto found = old.find(file);
    judge_script(run, golden_path, found == old.end() ? kNoValues : found->second, next[file], arguments.update,
                 totals);
    std::fflush(stdout);
    if (host::interrupted()) {
      std::printf("interrupted%s\n", arguments.update ? ": the golden file is not written" : "");
      std::printf("%d passed, %d failed\n", totals.passed, totals.failed);
      return EXIT_FAILURE;
    }
  }
  // With a filter, the other scripts' values are simply not looked at.
  if (arguments.filters.empty()) judge_vanished_scripts(scripts, golden_path, old, next, arguments.update, totals);
  if (arguments.update) {
    if (totals.added + totals.changed + totals.removed == 0) {
      std::printf("%s: no change\n", golden_path.c_str());
    } else {
      write_file_atomically(golden_path, format_golden_file(next));
      std::printf("wrote %s: %d added, %d changed, %d removed\n", golden_path.c_str(), totals.added,
                  totals.changed, totals.removed);
    }
  }
  std::printf("%d passed, %d failed\n", totals.passed, totals.failed);
  std::fflush(stdout);
  return totals.failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

}  // namespace

void print_test_usage(FILE* out) {
  std::fprintf(out,
      "usage: ashlar test [--update] [folder [name ...]]\n"
      "Runs every *.lua file in folder (default: the current folder) as a check\n"
      "script, each in a fresh Lua state, and compares the values it records\n"
      "(`local check = require \"ashlar.regression\"`) with folder/%s.\n"
      "  --update   write the values that changed to %s (never one that\n"
      "             misses its reference); it still fails on such checks\n"
      "  name ...   run only the scripts whose file names contain a name\n"
      "  --help     show this help\n"
      "Prints a line per failure, then 'N passed, N failed'; exit status 0 only\n"
      "when nothing failed.\n",
      kGoldenFileName, kGoldenFileName);
}

int run_regression_command(int argc, char** argv) {
  const Arguments arguments = parse_arguments(argc, argv);
  if (!arguments.error.empty()) {
    std::fprintf(stderr, "ashlar: test: %s\n", arguments.error.c_str());
    print_test_usage(stderr);
    return EXIT_FAILURE;
  }
  if (arguments.help) {
    print_test_usage(stdout);
    return EXIT_SUCCESS;
  }
  try {
    return run_suite(argv[0], arguments);
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "ashlar: test: %s\n", e.what());
    return EXIT_FAILURE;
  }
}

}  // namespace ashlar::regression
