// One check script of `ashlar test`, run in a process of its own: the
// runner starts `ashlar test --child FOLDER/FILE`, which runs the script in
// a fresh Lua state set up as the host's and hands back what it recorded.
// A process can be stopped wherever the script is (a Lua loop, the engine,
// a C call that never returns), runs beside others without sharing a
// locale, signal state or memory, and a crash fails only its script.
#pragma once

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

#include "core/clock.hpp"
#include "regression_check.hpp"

namespace ashlar::regression {

// The argument after "test" that makes `ashlar test` the child.
constexpr const char* kChildOption = "--child";

// What running a check script gave.
struct ScriptOutcome {
  std::vector<Check> checks;          // in the order recorded
  std::optional<std::string> error;   // what the script raised, with its traceback, or why its process failed
  bool timed_out = false;             // stopped at the runner's time limit (then no checks)
  double seconds = 0.0;               // the script's run time (until stopped, when timed out)
  std::string output;                 // what it wrote to stdout
  std::string error_output;           // ... and to stderr
};

// The child's side: runs the script at `path` (`program` is arg[-1], as
// the host gives it) and writes what it recorded to file descriptor 3.
// Returns the process's exit status.
int run_child(const char* program, const std::string& path);

// The runner's side: a child process running one script, its output going
// to temporary files.
class ScriptProcess {
public:
  // Starts the child for the script at `path`; `program` is the runner's
  // argv[0]. Throws std::runtime_error when it cannot.
  ScriptProcess(const char* program, const std::string& path);
  ~ScriptProcess();  // kills a process still running
  ScriptProcess(const ScriptProcess&) = delete;
  ScriptProcess& operator=(const ScriptProcess&) = delete;

  // Whether the process has ended; never blocks.
  bool finished();
  double seconds() const { return seconds_since(started_); }
  // Ends the process at once (SIGKILL) and waits for it.
  void kill();
  // What the script gave, once finished() or after kill().
  ScriptOutcome outcome(bool timed_out);

private:
  std::string path_;
  pid_t pid_ = -1;
  int status_ = 0;  // of waitpid, once ended
  Clock::time_point started_;
  int output_ = -1, error_output_ = -1, result_ = -1;  // temporary files
};

}  // namespace ashlar::regression
