// Links the C++ build of Lua, so a Lua error unwinds C++ frames as an
// exception: locals with destructors are safe in every function below.
#include "regression_runner.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "core/atomic_file.hpp"
#include "junit_report.hpp"
#include "regression_check.hpp"
#include "regression_golden.hpp"
#include "sandbox_process.hpp"
#include "script_process.hpp"

namespace ashlar::regression {

namespace {

namespace fs = std::filesystem;

const char* const kGoldenFileName = "golden.json";
const char* const kUpdateHint = "run `ashlar test --update`";

constexpr double kDefaultTimeout = 600;  // seconds a script may run (0: no limit)
constexpr int kDefaultJobs = 1;           // scripts running at once

struct Arguments {
  bool update = false;
  bool help = false;
  double timeout = kDefaultTimeout;
  int jobs = kDefaultJobs;
  std::string junit;                 // the JUnit XML file to write, if any
  fs::path folder = ".";
  std::vector<std::string> filters;  // parts of script file names
  std::string error;                 // set when the arguments are wrong
};

// Reads the value of the option at argv[i] (advancing i past it): the rest
// of the argument after `attached` characters ("-j4"), else the next one.
const char* option_value(int argc, char** argv, int& i, std::size_t attached, std::string& error) {
  if (std::strlen(argv[i]) > attached) return argv[i] + attached;
  if (i + 1 >= argc) {
    error = std::string("'") + argv[i] + "' needs a value";
    return nullptr;
  }
  return argv[++i];
}

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
      } else if (argument == "--timeout") {
        const char* value = option_value(argc, argv, i, argument.size(), arguments.error);
        if (value && !sandbox::parse_seconds(value, arguments.timeout))
          arguments.error = "--timeout: '" + std::string(value) + "' is not a number of seconds >= 0 (0: no limit)";
      } else if (argument == "--jobs" || argument.compare(0, 2, "-j") == 0) {
        const char* value = option_value(argc, argv, i, argument == "--jobs" ? argument.size() : 2, arguments.error);
        std::uint64_t jobs = 0;
        if (value && (!sandbox::parse_count(value, jobs) || jobs < 1 || jobs > 1024))
          arguments.error = std::string(argument == "--jobs" ? "--jobs" : "-j") + ": '" + value +
                            "' is not a number of scripts to run at once from 1 to 1024";
        arguments.jobs = static_cast<int>(jobs);
      } else if (argument == "--junit") {
        const char* value = option_value(argc, argv, i, argument.size(), arguments.error);
        if (value) arguments.junit = value;
      } else {
        arguments.error = "unrecognized option '" + argument + "'";
      }
      if (!arguments.error.empty()) break;
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
  std::string file;  // the script's name in the folder: its key in the golden file
  std::string path;  // folder/file, as messages show it
  ScriptOutcome outcome;
};

struct Totals {
  int passed = 0;
  int failed = 0;
  int added = 0;
  int changed = 0;
  int removed = 0;
  std::vector<JunitCase> cases;  // a script each, its failures as printed

  void fail(const std::string& line) { record("FAIL " + line); }

  // The error's first line, then its traceback indented below it.
  void error(const std::string& error) {
    std::string indented;
    for (const char c : error) indented += c == '\n' ? std::string("\n      ") : std::string(1, c);
    record("ERROR " + indented);
  }

private:
  void record(const std::string& line) {
    ++failed;
    std::printf("  %s\n", line.c_str());
    cases.back().failures.push_back(line);
  }
};

std::string describe(const Check& check) { return check.where + ": " + quote(check.name) + ": "; }

bool records(const ScriptRun& run, const std::string& name) {
  const auto& checks = run.outcome.checks;
  return std::any_of(checks.begin(), checks.end(), [&](const Check& check) { return check.name == name; });
}

// Judges one script's checks against its golden values `old` and, with
// `update`, makes `next` (a copy of `old`) the values to write. A script
// that failed changes nothing: the checks it did not reach are not stale.
void judge_script(const ScriptRun& run, const std::string& golden_path, const ScriptGolden& old,
                  ScriptGolden& next, bool update, double timeout, Totals& totals) {
  const std::optional<std::string>& error = run.outcome.error;
  if (run.outcome.timed_out) {
    char limit[32];
    std::snprintf(limit, sizeof limit, "%g", timeout);
    totals.fail(run.path + ": stopped at the time limit of " + limit + " s (--timeout)");
    return;  // like an error: the values it did not reach are not stale
  }
  if (error) totals.error(*error);
  const auto& checks = run.outcome.checks;
  if (!error && checks.empty())
    totals.fail(run.path + ": records no checks (call the function that `require \"ashlar.regression\"` returns)");
  const bool writing = update && !error;
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
  if (error || checks.empty()) return;
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
    if (!update) totals.cases.push_back(JunitCase{script, 0.0, {}, "", ""});  // its stale values fail
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

volatile std::sig_atomic_t g_interrupted = 0;

void note_interrupt(int) { g_interrupted = 1; }

// Ctrl-C while the scripts run: the children get it too (they share the
// terminal's process group) and the runner stops instead of going on.
class InterruptWatch {
public:
  InterruptWatch() {
    struct sigaction action {};
    action.sa_handler = note_interrupt;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &saved_);
  }
  ~InterruptWatch() { sigaction(SIGINT, &saved_, nullptr); }
  InterruptWatch(const InterruptWatch&) = delete;
  InterruptWatch& operator=(const InterruptWatch&) = delete;

private:
  struct sigaction saved_ {};
};

// Prints what a script wrote, its line and its failures, and judges it.
void report_script(const ScriptRun& run, const std::string& golden_path, const GoldenValues& old,
                   GoldenValues& next, const Arguments& arguments, Totals& totals) {
  static const ScriptGolden kNoValues;
  std::fputs(run.outcome.output.c_str(), stdout);
  std::fflush(stdout);
  std::fputs(run.outcome.error_output.c_str(), stderr);
  std::fflush(stderr);
  std::printf("%s: %zu checks, %.2f s\n", run.file.c_str(), run.outcome.checks.size(), run.outcome.seconds);
  totals.cases.push_back(
      JunitCase{run.file, run.outcome.seconds, {}, run.outcome.output, run.outcome.error_output});
  const auto found = old.find(run.file);
  judge_script(run, golden_path, found == old.end() ? kNoValues : found->second, next[run.file], arguments.update,
               arguments.timeout, totals);
  std::fflush(stdout);
}

// A script's process and where its outcome goes.
struct Running {
  std::size_t index;
  std::unique_ptr<ScriptProcess> process;
};

int run_suite(const char* program, const Arguments& arguments) {
  const std::vector<std::string> scripts = list_scripts(arguments);
  const std::string golden_path = (arguments.folder / kGoldenFileName).string();
  const GoldenValues old = read_golden_file(golden_path);
  GoldenValues next = old;
  Totals totals;
  // Up to `jobs` scripts run at once; each is reported once those before
  // it are, so the report is the same whatever the number of jobs.
  std::vector<std::optional<ScriptRun>> done(scripts.size());
  std::vector<Running> running;
  std::size_t started = 0, reported = 0;
  const InterruptWatch interrupt_watch;
  g_interrupted = 0;
  while (reported < scripts.size() && !g_interrupted) {
    while (running.size() < static_cast<std::size_t>(arguments.jobs) && started < scripts.size()) {
      const std::string path = (arguments.folder / scripts[started]).string();
      running.push_back(Running{started++, std::make_unique<ScriptProcess>(program, path)});
    }
    bool progressed = false;
    for (auto r = running.begin(); r != running.end();) {
      const bool ended = r->process->finished();
      const bool over_time = !ended && arguments.timeout > 0 && r->process->seconds() > arguments.timeout;
      if (!ended && !over_time) {
        ++r;
        continue;
      }
      if (over_time) r->process->kill();
      done[r->index] = ScriptRun{scripts[r->index], (arguments.folder / scripts[r->index]).string(),
                                 r->process->outcome(over_time)};
      r = running.erase(r);
      progressed = true;
    }
    for (; reported < scripts.size() && done[reported]; ++reported)
      report_script(*done[reported], golden_path, old, next, arguments, totals);
    if (!progressed) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (g_interrupted) {
    running.clear();  // kills them
    std::printf("interrupted%s\n", arguments.update ? ": the golden file is not written" : "");
    std::printf("%d passed, %d failed\n", totals.passed, totals.failed);
    return EXIT_FAILURE;
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
  if (!arguments.junit.empty()) {
    write_file_atomically(arguments.junit, format_junit(arguments.folder.string(), totals.cases));
    std::printf("wrote %s\n", arguments.junit.c_str());
  }
  std::printf("%d passed, %d failed\n", totals.passed, totals.failed);
  std::fflush(stdout);
  return totals.failed == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}

}  // namespace

void print_test_usage(FILE* out) {
  std::fprintf(out,
      "usage: ashlar test [--update] [--timeout S] [-j N] [--junit FILE] [folder [name ...]]\n"
      "Runs every *.lua file in folder (default: the current folder) as a check\n"
      "script, each in a process of its own, and compares the values it records\n"
      "(`local check = require \"ashlar.regression\"`) with folder/%s.\n"
      "  --update       write the values that changed to %s (never one that\n"
      "                 misses its reference); it still fails on such checks\n"
      "  --timeout S    stop a script running longer than S seconds: it fails\n"
      "                 (default %g; 0: no limit)\n"
      "  -j N, --jobs N run N scripts at once (default %d); the report keeps\n"
      "                 the scripts' order\n"
      "  --junit FILE   also write the run as JUnit XML, a test case per script\n"
      "  name ...       run only the scripts whose file names contain a name\n"
      "  --help         show this help\n"
      "Prints a line per failure, then 'N passed, N failed'; exit status 0 only\n"
      "when nothing failed.\n",
      kGoldenFileName, kGoldenFileName, kDefaultTimeout, kDefaultJobs);
}

int run_regression_command(int argc, char** argv) {
  if (argc == 4 && std::strcmp(argv[2], kChildOption) == 0) return run_child(argv[0], argv[3]);
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
