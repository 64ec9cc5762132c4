// Links the C++ build of Lua, so a Lua error unwinds C++ frames as an
// exception: locals with destructors are safe in the child's functions.
#include "script_process.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <clocale>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <lua.hpp>

#include "host_state.hpp"

namespace ashlar::regression {

namespace {

constexpr int kResultDescriptor = 3;
constexpr const char* kResultHeader = "ashlar-test-result 1\n";

// ---- the result, as the child writes it and the runner reads it back:
// tagged fields, strings as length:bytes, numbers in hexadecimal (exact).

void put_text(std::string& out, const std::string& text) {
  out += std::to_string(text.size());
  out += ':';
  out += text;
}

void put_number(std::string& out, double number) {
  char text[48];
  std::snprintf(text, sizeof text, "%a;", number);
  out += text;
}

void put_value(std::string& out, const Value& value) {
  if (const double* number = std::get_if<double>(&value)) {
    out += 'n';
    put_number(out, *number);
  } else if (const bool* flag = std::get_if<bool>(&value)) {
    out += *flag ? 't' : 'f';
  } else if (const std::string* text = std::get_if<std::string>(&value)) {
    out += 's';
    put_text(out, *text);
  } else {
    const auto& list = std::get<std::vector<double>>(value);
    out += 'l';
    put_text(out, std::to_string(list.size()));
    for (const double number : list) put_number(out, number);
  }
}

void put_tolerance(std::string& out, const Tolerance& tolerance) {
  put_number(out, tolerance.relative);
  put_number(out, tolerance.absolute);
}

std::string format_result(const std::vector<Check>& checks, const std::optional<std::string>& error, double seconds) {
  std::string out = kResultHeader;
  out += 'T';
  put_number(out, seconds);
  if (error) {
    out += 'E';
    put_text(out, *error);
  }
  for (const Check& check : checks) {
    out += 'C';
    put_text(out, check.name);
    put_text(out, check.where);
    put_value(out, check.value);
    put_tolerance(out, check.tolerance);
    if (check.reference) {
      out += 'r';
      put_value(out, *check.reference);
      put_tolerance(out, check.reference_tolerance);
    } else {
      out += '-';
    }
  }
  out += 'Z';  // the end: a result cut short has none
  return out;
}

// Reads format_result's text; throws std::runtime_error when it is not whole.
class ResultReader {
public:
  explicit ResultReader(const std::string& text) : text_(text) {
    if (text_.compare(0, std::strlen(kResultHeader), kResultHeader) != 0) fail();
    at_ = std::strlen(kResultHeader);
  }

  char tag() {
    if (at_ >= text_.size()) fail();
    return text_[at_++];
  }

  std::string text() {
    const std::size_t colon = text_.find(':', at_);
    if (colon == std::string::npos) fail();
    const std::size_t length = std::strtoull(text_.c_str() + at_, nullptr, 10);
    if (length > text_.size() - colon - 1) fail();
    at_ = colon + 1 + length;
    return text_.substr(colon + 1, length);
  }

  double number() {
    const std::size_t end = text_.find(';', at_);
    if (end == std::string::npos) fail();
    char* stop = nullptr;
    const double number = std::strtod(text_.c_str() + at_, &stop);
    if (stop != text_.c_str() + end) fail();
    at_ = end + 1;
    return number;
  }

  Value value() {
    switch (tag()) {
      case 'n': return number();
      case 't': return true;
      case 'f': return false;
      case 's': return text();
      case 'l': {
        std::vector<double> list(std::stoul(text()));
        for (double& number : list) number = this->number();
        return list;
      }
      default: fail();
    }
  }

  Tolerance tolerance() {
    Tolerance tolerance;
    tolerance.relative = number();
    tolerance.absolute = number();
    return tolerance;
  }

  [[noreturn]] static void fail() { throw std::runtime_error("the result is not whole"); }

private:
  const std::string& text_;
  std::size_t at_ = 0;
};

void read_result(const std::string& text, ScriptOutcome& outcome) {
  ResultReader reader(text);
  for (;;) {
    switch (reader.tag()) {
      case 'T': outcome.seconds = reader.number(); break;
      case 'E': outcome.error = reader.text(); break;
      case 'C': {
        Check check;
        check.name = reader.text();
        check.where = reader.text();
        check.value = reader.value();
        check.tolerance = reader.tolerance();
        if (reader.tag() == 'r') {
          check.reference = reader.value();
          check.reference_tolerance = reader.tolerance();
        }
        outcome.checks.push_back(std::move(check));
        break;
      }
      case 'Z': return;
      default: ResultReader::fail();
    }
  }
}

// ---- the child

struct ChildRun {
  const char* program;
  const std::string& path;
  CheckRecorder recorder;
  std::optional<std::string> error;
};

std::string error_message(lua_State* L) {
  const char* message = lua_tostring(L, -1);
  return message ? message : std::string("(error object is a ") + luaL_typename(L, -1) + " value)";
}

// os.exit would end the child before it hands back what the script
// recorded. In a check script it is an error instead.
int refuse_exit(lua_State* L) {
  return luaL_error(L, "os.exit: a check script cannot end the run (raise an error to fail it)");
}

// Sets up a state as the host does for a script run without arguments, then
// runs the script; called under lua_pcall, so that even a memory error
// during set-up is reported.
int set_up_and_run(lua_State* L) {
  auto& run = *static_cast<ChildRun*>(lua_touserdata(L, 1));
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

bool write_all(int descriptor, const std::string& text) {
  std::size_t written = 0;
  while (written < text.size()) {
    const ssize_t count = ::write(descriptor, text.data() + written, text.size() - written);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) return false;
    written += static_cast<std::size_t>(count);
  }
  return true;
}

// ---- the runner's side

std::string read_all(int descriptor) {
  std::string text;
  if (::lseek(descriptor, 0, SEEK_SET) != 0) return text;
  char buffer[1 << 14];
  for (;;) {
    const ssize_t count = ::read(descriptor, buffer, sizeof buffer);
    if (count < 0 && errno == EINTR) continue;
    if (count <= 0) return text;
    text.append(buffer, static_cast<std::size_t>(count));
  }
}

// An unnamed temporary file, not inherited by the other children.
int temporary_file() {
  FILE* file = std::tmpfile();
  if (file == nullptr) throw std::runtime_error(std::string("cannot make a temporary file: ") + std::strerror(errno));
  const int descriptor = ::dup(::fileno(file));
  std::fclose(file);
  if (descriptor < 0 || ::fcntl(descriptor, F_SETFD, FD_CLOEXEC) != 0)
    throw std::runtime_error(std::string("cannot make a temporary file: ") + std::strerror(errno));
  return descriptor;
}

std::string how_it_ended(int status) {
  if (WIFSIGNALED(status))
    return "was killed by signal " + std::to_string(WTERMSIG(status)) + " (" + strsignal(WTERMSIG(status)) + ")";
  return "exited with status " + std::to_string(WEXITSTATUS(status));
}

}  // namespace

int run_child(const char* program, const std::string& path) {
  const Clock::time_point start = Clock::now();
  ChildRun run{program, path, CheckRecorder(), std::nullopt};
  lua_State* L = luaL_newstate();
  if (L == nullptr) {
    run.error = "cannot create a Lua state: not enough memory";
  } else {
    lua_pushcfunction(L, set_up_and_run);
    lua_pushlightuserdata(L, &run);
    if (lua_pcall(L, 1, 0, 0) != LUA_OK) run.error = error_message(L);
    lua_close(L);
  }
  std::fflush(stdout);
  std::fflush(stderr);
  if (!write_all(kResultDescriptor, format_result(run.recorder.checks(), run.error, seconds_since(start)))) {
    std::fprintf(stderr, "ashlar: test: cannot hand the result back: %s\n", std::strerror(errno));
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}

ScriptProcess::ScriptProcess(const char* program, const std::string& path) : path_(path), started_(Clock::now()) {
  output_ = temporary_file();
  error_output_ = temporary_file();
  result_ = temporary_file();
  // Everything the child needs, made before fork: after it, the child calls
  // only async-signal-safe functions until exec.
  const char* const child_argv[] = {program, "test", kChildOption, path.c_str(), nullptr};
  const pid_t parent = ::getpid();
  std::fflush(stdout);
  std::fflush(stderr);
  pid_ = ::fork();
  if (pid_ < 0) throw std::runtime_error(std::string("cannot start a process: ") + std::strerror(errno));
  if (pid_ == 0) {
    // Ends with the runner, however the runner ends.
    if (::prctl(PR_SET_PDEATHSIG, SIGKILL) != 0 || ::getppid() != parent) ::_exit(127);
    if (::dup2(output_, STDOUT_FILENO) < 0 || ::dup2(error_output_, STDERR_FILENO) < 0 ||
        ::dup2(result_, kResultDescriptor) < 0)
      ::_exit(127);
    ::execv("/proc/self/exe", const_cast<char* const*>(child_argv));
    static const char kFailed[] = "ashlar: test: cannot run /proc/self/exe\n";
    const ssize_t ignored = ::write(STDERR_FILENO, kFailed, sizeof kFailed - 1);
    (void)ignored;
    ::_exit(127);
  }
}

ScriptProcess::~ScriptProcess() {
  if (pid_ > 0) kill();
  for (const int descriptor : {output_, error_output_, result_})
    if (descriptor >= 0) ::close(descriptor);
}

bool ScriptProcess::finished() {
  if (pid_ <= 0) return true;
  int status = 0;
  const pid_t ended = ::waitpid(pid_, &status, WNOHANG);
  if (ended != pid_) return false;
  status_ = status;
  pid_ = 0;
  return true;
}

void ScriptProcess::kill() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  while (::waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
  }
  pid_ = 0;
}

ScriptOutcome ScriptProcess::outcome(bool timed_out) {
  ScriptOutcome outcome;
  outcome.output = read_all(output_);
  outcome.error_output = read_all(error_output_);
  outcome.timed_out = timed_out;
  if (timed_out) {
    outcome.seconds = seconds();
    return outcome;
  }
  const bool clean = WIFEXITED(status_) && WEXITSTATUS(status_) == EXIT_SUCCESS;
  try {
    read_result(read_all(result_), outcome);
  } catch (const std::exception&) {
    outcome = ScriptOutcome{{}, path_ + ": its process " + how_it_ended(status_) + " before it handed back a result",
                            false, seconds(), std::move(outcome.output), std::move(outcome.error_output)};
    return outcome;
  }
  // After the script: e.g. the leak check of a sanitizer build.
  if (!clean) {
    const std::string ended = path_ + ": its process " + how_it_ended(status_) + " after the script ran";
    outcome.error = outcome.error ? *outcome.error + "\n" + ended : ended;
  }
  return outcome;
}

}  // namespace ashlar::regression
