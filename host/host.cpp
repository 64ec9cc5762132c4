// The `ashlar` host program: a Lua 5.4 stand-alone interpreter in the manner of
// Lua's own lua.c, with the ashlar library preloaded and the model library and
// the script's own folder on package.path.
//
// It links the C++ build of Lua, so a Lua error unwinds C++ frames as an
// exception: locals with destructors are safe in every function below.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <fcntl.h>

#include <unistd.h>

#include <lua.hpp>
#include <readline/history.h>
#include <readline/readline.h>

#include "core/blas.hpp"
#include "core/version.hpp"
#include "host_state.hpp"
#include "sandbox_process.hpp"
#include "study/cluster.hpp"
#include "regression_check.hpp"
#include "regression_runner.hpp"

namespace {

using ashlar::host::call_with_traceback;
using ashlar::host::open_host_libraries;
using ashlar::host::prepend_script_folder_to_path;

const char* const kProgramName = "ashlar";
const char* const kErrorPrefix = "ashlar: ";

// What the options before the script asked for. Options are checked here,
// before Lua starts, and acted on in order later (-e and -l run in sequence).
struct CommandLine {
  int argc = 0;
  char** argv = nullptr;
  int script = 0;  // index in argv of the script name; argc when there is none
  bool interactive = false;
  bool show_version = false;
  bool has_chunk = false;  // at least one -e
  bool show_help = false;
  ashlar::sandbox::ProcessOptions sandbox;
  bool sandbox_option_given = false;  // --read, --memory, ... (they need --sandbox)
  std::string error;  // set when the options are wrong
};

// glibc's malloc backs its heap and its large blocks with the kernel's
// transparent huge pages (2 MiB, where the kernel gives them on request)
// only with the tunable glibc.malloc.hugetlb=1, which it reads from
// GLIBC_TUNABLES once, as the process starts. A large analysis spends much
// of its time in page faults otherwise, each a trap out of the virtual
// machine on hosts like ours: the 10,051-block 3D wall's run 78,600 ->
// 15,000 faults, 3.38 -> 2.85 s; the 100,052-block vault's 815,000 ->
// 45,000, analysis 62.2 -> 58.5 s (docs/performance.md). So the host,
// started without the tunable, executes itself again with it added to
// GLIBC_TUNABLES: the same arguments in the same process. It does so from
// the executable's pre-initialisation array, before any library's
// initialisation (OpenBLAS starts its threads there), using only the
// arguments and the environment it is handed and system calls; the first
// start then costs about the dynamic loader's time. The user's environment
// is put back in main (restore_environment_after_huge_pages): programs a
// script runs inherit it, not the tunable (the Chromium of the viewer's
// tests draws nothing with GLIBC_TUNABLES set). A value of the user's own
// for the tunable stands; where the kernel has transparent huge pages off,
// the executable cannot be run again, or another allocator replaces
// glibc's (the sanitizers', or one preloaded, as valgrind's), the host
// goes on as it is.
const char kTunablesVariable[] = "GLIBC_TUNABLES";
// The user's GLIBC_TUNABLES, or that there was none, over the second start.
const char kTunablesWere[] = "ASHLAR_GLIBC_TUNABLES_WERE";
const char kTunablesWereUnset[] = "ASHLAR_GLIBC_TUNABLES_WERE_UNSET";

#if !defined(__SANITIZE_ADDRESS__)
bool transparent_huge_pages_offered() {
  const int file = open("/sys/kernel/mm/transparent_hugepage/enabled", O_RDONLY | O_CLOEXEC);
  if (file < 0) return false;
  char modes[128] = {};
  const ssize_t length = read(file, modes, sizeof modes - 1);
  close(file);
  return length > 0 && std::strstr(modes, "[never]") == nullptr;
}

// Whether `entry` ("NAME=value") sets the variable `name`.
bool sets(const char* entry, const char* name) {
  const size_t length = std::strlen(name);
  return std::strncmp(entry, name, length) == 0 && entry[length] == '=';
}

void start_again_with_huge_pages(int /*argc*/, char** argv, char** environment) {
  static const char kTunable[] = "glibc.malloc.hugetlb=";
  size_t count = 0;
  const char* before = nullptr;  // the user's GLIBC_TUNABLES
  for (; environment[count] != nullptr; ++count) {
    const char* entry = environment[count];
    if (sets(entry, kTunablesVariable)) before = entry + sizeof kTunablesVariable;
    // Preloaded libraries (valgrind's, another malloc) interpose their own
    // allocator, and valgrind would run the executable again outside itself.
    if (sets(entry, "LD_PRELOAD") && entry[sizeof "LD_PRELOAD"] != '\0') return;
  }
  if ((before != nullptr && std::strstr(before, kTunable) != nullptr) || !transparent_huge_pages_offered()) return;
  char tunables[4096], were[4096];
  const int written = std::snprintf(tunables, sizeof tunables, "%s=%s%s%s1", kTunablesVariable,
                                    before != nullptr ? before : "", before != nullptr && *before ? ":" : "", kTunable);
  const int kept = before != nullptr ? std::snprintf(were, sizeof were, "%s=%s", kTunablesWere, before)
                                     : std::snprintf(were, sizeof were, "%s=1", kTunablesWereUnset);
  if (written < 0 || static_cast<size_t>(written) >= sizeof tunables || kept < 0 ||
      static_cast<size_t>(kept) >= sizeof were) {
    return;
  }
  std::vector<char*> with_huge_pages;
  with_huge_pages.reserve(count + 3);
  for (size_t k = 0; k < count; ++k) {
    if (!sets(environment[k], kTunablesVariable)) with_huge_pages.push_back(environment[k]);
  }
  with_huge_pages.push_back(tunables);
  with_huge_pages.push_back(were);
  with_huge_pages.push_back(nullptr);
  execve("/proc/self/exe", argv, with_huge_pages.data());
}

// glibc calls the functions of an executable's pre-initialisation array
// with (argc, argv, envp) before any shared library's initialisation.
__attribute__((section(".preinit_array"), used)) void (*const kStartAgainWithHugePages)(int, char**, char**) =
    start_again_with_huge_pages;
#endif

// After the second start: GLIBC_TUNABLES as the user had it.
void restore_environment_after_huge_pages() {
  if (const char* were = std::getenv(kTunablesWere)) {
    const std::string value = were;
    setenv(kTunablesVariable, value.c_str(), 1);
    unsetenv(kTunablesWere);
  } else if (std::getenv(kTunablesWereUnset) != nullptr) {
    unsetenv(kTunablesVariable);
    unsetenv(kTunablesWereUnset);
  }
}

void print_usage(FILE* out) {
  std::fprintf(out,
      "usage: %s [options] [script [args]]\n"
      "       %s test [--update] [--timeout S] [-j N] [--junit FILE] [folder [name ...]]\n"
      "Available options are:\n"
      "  -e stat    execute string 'stat'\n"
      "  -i         enter interactive mode after executing 'script'\n"
      "  -l mod     require library 'mod' into global 'mod'\n"
      "  -l g=mod   require library 'mod' into global 'g'\n"
      "  -v         show version information\n"
      "  -W         turn warnings on\n"
      "  --sandbox  run the script as untrusted (see below)\n"
      "  --read DIR, --write DIR   folders a sandboxed script may read, or read and\n"
      "             write (repeatable; default: read the script's folder, write its\n"
      "             subfolder out); the script's relative paths start in its folder\n"
      "  --memory SIZE             Lua heap limit, e.g. 256M (default 1G)\n"
      "  --engine-memory SIZE      memory the whole process may add (default 4G; 0: none)\n"
      "  --instructions N          Lua instruction budget (default: none)\n"
      "  --time S                  time limit in seconds (default 600; 0: none)\n"
      "  --         stop handling options\n"
      "  -          stop handling options and execute stdin\n"
      "  --help     show this help\n"
      "  --version  show version information\n"
      "With no script and no -e, %s reads statements interactively when stdin\n"
      "is a terminal, and runs stdin as a script otherwise.\n"
      "A sandboxed script cannot run programs, load binary chunks or C modules,\n"
      "use the debug library, or touch files outside its folders.\n"
      "'%s test' runs a folder of regression checks against their golden\n"
      "values ('%s test --help' for more).\n",
      kProgramName, kProgramName, kProgramName, kProgramName, kProgramName);
}

// A sanitizer build says so: it cannot cap the process's memory (--sandbox).
#if defined(__SANITIZE_ADDRESS__)
const char* const kBuildNote = " [AddressSanitizer]";
#else
const char* const kBuildNote = "";
#endif

void print_version() {
  std::printf("%s %s (%s)%s\n", kProgramName, ashlar::version(), LUA_VERSION, kBuildNote);
  std::fflush(stdout);
}

// Options stop at the first argument that is not one, as in lua.c: the rest
// belong to the script.
CommandLine parse_command_line(int argc, char** argv) {
  CommandLine command_line;
  command_line.argc = argc;
  command_line.argv = argv;
  int i = 1;
  for (; i < argc; ++i) {
    const char* option = argv[i];
    if (option[0] != '-') break;  // the script
    if (std::strcmp(option, "-") == 0) break;  // the script is stdin
    if (std::strcmp(option, "--") == 0) {
      ++i;
      break;
    }
    if (std::strcmp(option, "--help") == 0) {
      command_line.show_help = true;
    } else if (std::strcmp(option, "--version") == 0 || std::strcmp(option, "-v") == 0) {
      command_line.show_version = true;
    } else if (std::strcmp(option, "-i") == 0) {
      command_line.interactive = true;
      command_line.show_version = true;
    } else if (std::strcmp(option, "-W") == 0) {
      // acted on in run_options
    } else if (ashlar::sandbox::parse_option(argc, argv, i, command_line.sandbox, command_line.error)) {
      if (!command_line.error.empty()) break;
      command_line.sandbox_option_given |= std::strcmp(option, "--sandbox") != 0;
    } else if (option[1] == 'e' || option[1] == 'l') {
      command_line.has_chunk |= option[1] == 'e';
      if (option[2] == '\0') {  // the argument is the next word, not "-estat"
        ++i;
        if (i == argc || argv[i][0] == '-') {
          command_line.error = std::string("'") + option + "' needs argument";
          break;
        }
      }
    } else {
      command_line.error = std::string("unrecognized option '") + option + "'";
      break;
    }
  }
  command_line.script = i;
  if (command_line.error.empty() && command_line.sandbox_option_given && !command_line.sandbox.enabled)
    command_line.error = "'--read', '--write', '--memory', '--engine-memory', '--instructions' and '--time' need --sandbox";
  return command_line;
}

// Under --engine-memory, what a failed allocation outside the Lua heap means.
std::string g_engine_memory_note;

// Prints the error object on top of the stack and pops it; returns the status.
int report(lua_State* L, int status, const char* prefix = kErrorPrefix) {
  if (status == LUA_OK) return status;
  const int error_index = lua_gettop(L);
  const char* message = lua_tostring(L, error_index);
  if (message == nullptr)  // not raised through add_traceback
    message = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, error_index));
  std::fflush(stdout);  // what the script wrote comes before its error in a shared log
  std::string shown = ashlar::sandbox::explain_error(L, message);
  if (!g_engine_memory_note.empty() && shown.find("not enough memory") != std::string::npos) shown += g_engine_memory_note;
  std::fprintf(stderr, "%s%s\n", prefix, shown.c_str());
  std::fflush(stderr);
  lua_settop(L, error_index - 1);
  return status;
}

// Runs the chunk that a load left on the stack, or reports the load's error.
int run_loaded_chunk(lua_State* L, int load_status) {
  const int status = load_status == LUA_OK ? call_with_traceback(L, 0, 0) : load_status;
  return report(L, status);
}

int run_string(lua_State* L, const char* chunk) {
  return run_loaded_chunk(L, luaL_loadbuffer(L, chunk, std::strlen(chunk), "=(command line)"));
}

// `-l mod` sets global mod = require "mod"; `-l g=mod` sets global g instead.
int require_into_global(lua_State* L, const char* specification) {
  const char* equals = std::strchr(specification, '=');
  const std::string global = equals ? std::string(specification, equals) : specification;
  const char* module = equals ? equals + 1 : specification;
  lua_getglobal(L, "require");
  lua_pushstring(L, module);
  const int status = call_with_traceback(L, 1, 1);
  if (status == LUA_OK) lua_setglobal(L, global.c_str());
  return report(L, status);
}

// Runs -e, -l and -W in the order given; false after the first failure.
bool run_options(lua_State* L, const CommandLine& command_line) {
  for (int i = 1; i < command_line.script; ++i) {
    const char* option = command_line.argv[i];
    if (std::strcmp(option, "-W") == 0) {
      lua_warning(L, "@on", 0);
      continue;
    }
    if (ashlar::sandbox::takes_value(option)) {
      ++i;  // its value, read by parse_command_line
      continue;
    }
    if (option[1] != 'e' && option[1] != 'l') continue;
    const char* value = option[2] != '\0' ? option + 2 : command_line.argv[++i];
    const int status = option[1] == 'e' ? run_string(L, value) : require_into_global(L, value);
    if (status != LUA_OK) return false;
  }
  return true;
}

bool script_is_stdin(const CommandLine& command_line) {
  const int script = command_line.script;
  // `ashlar -- -` names a file called "-".
  return std::strcmp(command_line.argv[script], "-") == 0 &&
         std::strcmp(command_line.argv[script - 1], "--") != 0;
}

int run_script(lua_State* L, const CommandLine& command_line) {
  const char* file_name = script_is_stdin(command_line) ? nullptr : command_line.argv[command_line.script];
  // A sandboxed script may not be a precompiled (binary) chunk.
  int status = luaL_loadfilex(L, file_name, command_line.sandbox.enabled ? "t" : nullptr);
  if (status == LUA_OK) {
    const int first_argument = command_line.script + 1;
    const int argument_count = command_line.argc - first_argument;
    luaL_checkstack(L, argument_count + 3, "too many arguments to script");
    for (int i = first_argument; i < command_line.argc; ++i) lua_pushstring(L, command_line.argv[i]);
    status = call_with_traceback(L, argument_count, LUA_MULTRET);
  }
  if (status == LUA_OK && command_line.sandbox.enabled) {
    const std::string late = ashlar::sandbox::deadline_problem(L);
    if (!late.empty()) {
      lua_pushstring(L, late.c_str());
      status = LUA_ERRRUN;
    }
  }
  return report(L, status);
}

// Reads one line without its newline; false at end of input. At a terminal
// through readline: line editing, and history for the session.
bool read_line(const char* prompt, std::string& line) {
  if (isatty(STDIN_FILENO)) {
    char* typed = readline(prompt);
    if (typed == nullptr) return false;
    line = typed;
    std::free(typed);
    if (!line.empty()) add_history(line.c_str());
    return true;
  }
  std::fputs(prompt, stdout);
  std::fflush(stdout);
  line.clear();
  char buffer[512];
  while (std::fgets(buffer, sizeof buffer, stdin) != nullptr) {
    line += buffer;
    if (line.back() == '\n') {
      line.pop_back();
      return true;
    }
  }
  return !line.empty();
}

// A syntax error that ends at "<eof>" means the statement goes on.
bool is_incomplete(lua_State* L, int status) {
  if (status != LUA_ERRSYNTAX) return false;
  static const char kEofMark[] = "<eof>";
  constexpr size_t kEofMarkLength = sizeof kEofMark - 1;
  size_t length = 0;
  const char* message = lua_tolstring(L, -1, &length);
  return length >= kEofMarkLength && std::strcmp(message + length - kEofMarkLength, kEofMark) == 0;
}

constexpr int kEndOfInput = -1;

// Compiles what is typed at the prompt: an expression (so its value gets
// printed) if it is one, else a statement, reading more lines while it is
// incomplete. Leaves the function or an error message on the stack.
int load_typed_chunk(lua_State* L) {
  std::string line;
  if (!read_line("> ", line)) return kEndOfInput;
  const std::string as_expression = "return " + line;
  if (luaL_loadbuffer(L, as_expression.data(), as_expression.size(), "=stdin") == LUA_OK)
    return LUA_OK;
  lua_pop(L, 1);
  std::string chunk = line;
  for (;;) {
    const int status = luaL_loadbuffer(L, chunk.data(), chunk.size(), "=stdin");
    if (!is_incomplete(L, status) || !read_line(">> ", line)) return status;
    lua_pop(L, 1);
    chunk += '\n';
    chunk += line;
  }
}

// Prints the values left above `base` with the global print.
void print_results(lua_State* L, int base) {
  const int count = lua_gettop(L) - base;
  if (count == 0) return;
  luaL_checkstack(L, LUA_MINSTACK, "too many results to print");
  lua_getglobal(L, "print");
  lua_insert(L, base + 1);
  if (lua_pcall(L, count, 0, 0) != LUA_OK) {
    lua_pushfstring(L, "error calling 'print' (%s)", lua_tostring(L, -1));
    report(L, LUA_ERRRUN);
    lua_pop(L, 1);
  }
}

// Errors typed at the prompt print without the program name, as in lua.c.
void run_interactive(lua_State* L) {
  const int base = lua_gettop(L);
  int status;
  while ((status = load_typed_chunk(L)) != kEndOfInput) {
    if (status == LUA_OK) status = call_with_traceback(L, 0, LUA_MULTRET);
    if (status == LUA_OK)
      print_results(L, base);
    else
      report(L, status, "");
    lua_settop(L, base);
    if (ashlar::host::terminated()) return;
  }
  std::fputs("\n", stdout);
  std::fflush(stdout);
}

// Everything that touches Lua runs in here, under lua_pcall, so that even a
// memory error during set-up is reported instead of aborting.
int run_host(lua_State* L) {
  const auto& command_line = *static_cast<const CommandLine*>(lua_touserdata(L, 1));
  if (!command_line.sandbox.enabled) open_host_libraries(L);  // else opened, restricted
  // A check script run on its own prints what it records; `ashlar test`
  // compares it instead.
  static ashlar::regression::CheckRecorder printed_checks(/*echo=*/true);
  ashlar::regression::preload_regression_module(L, printed_checks);
  const bool has_script = command_line.script < command_line.argc;
  ashlar::host::ScriptInvocation invocation;
  invocation.argv.assign(command_line.argv, command_line.argv + command_line.argc);
  invocation.script = command_line.script;
  if (has_script && !script_is_stdin(command_line)) {
    prepend_script_folder_to_path(L, command_line.argv[command_line.script]);
    ashlar::host::remember_script(L, invocation);  // for a study's worker states
  }
  ashlar::host::create_arg_table(L, invocation.argv, invocation.script);

  if (command_line.show_version) print_version();
  // -e chunks and the prompt have the library at hand, as scripts have it
  // after their require.
  if (!command_line.sandbox.enabled) {
    for (const auto& [global, module] : {std::pair{"ashlar", "ashlar"}, std::pair{"models", "ashlar.models"}}) {
      lua_getglobal(L, "require");
      lua_pushstring(L, module);
      if (report(L, call_with_traceback(L, 1, 1)) != LUA_OK) {
        lua_pushboolean(L, false);
        return 1;
      }
      lua_setglobal(L, global);
    }
  }
  bool succeeded = run_options(L, command_line);
  if (succeeded && has_script) succeeded = run_script(L, command_line) == LUA_OK;
  if (succeeded) {
    if (command_line.interactive) {
      run_interactive(L);
    } else if (!has_script && !command_line.has_chunk && !command_line.show_version) {
      if (isatty(STDIN_FILENO)) {
        print_version();
        run_interactive(L);
      } else {
        succeeded = run_loaded_chunk(L, luaL_loadfilex(L, nullptr, command_line.sandbox.enabled ? "t" : nullptr)) == LUA_OK;
      }
    }
  }
  lua_pushboolean(L, succeeded);
  return 1;
}

// The script's state under --sandbox, with the process limited too.
lua_State* sandboxed_state(CommandLine& command_line) {
  const bool has_script = command_line.script < command_line.argc && !script_is_stdin(command_line);
  ashlar::sandbox::complete_settings(command_line.sandbox, has_script ? command_line.argv[command_line.script] : nullptr);
  lua_State* L = ashlar::sandbox::new_state(command_line.sandbox.settings);
  ashlar::sandbox::limit_process(command_line.sandbox);
  if (command_line.sandbox.engine_memory_bytes != 0)
    g_engine_memory_note = " (the sandboxed process may use " +
                           std::to_string(command_line.sandbox.engine_memory_bytes >> 20) +
                           " MiB more than at its start: --engine-memory)";
  return L;
}

}  // namespace

int main(int argc, char** argv) {
  restore_environment_after_huge_pages();
  // Before any thread of the program's own exists: the set-up sets and
  // unsets OPENBLAS_CORETYPE, which a getenv on another thread (a study
  // worker's os.getenv, say) must not race with.
  ashlar::set_up_blas_in_whole_process();
  const ashlar::host::TerminationWatch termination_watch;  // before MPI, CHOLMOD or a study starts a thread
  const std::string cluster_warning = ashlar::cluster::join_if_launched(&argc, &argv);
  if (!cluster_warning.empty()) std::fprintf(stderr, "%s%s\n", kErrorPrefix, cluster_warning.c_str());
  // Exactly "test": `ashlar ./test` and `ashlar -- test` still run a script.
  if (argc >= 2 && std::strcmp(argv[1], "test") == 0) {
    const int status = ashlar::regression::run_regression_command(argc, argv);
    ashlar::host::end_if_terminated();
    return status;
  }
  CommandLine command_line = parse_command_line(argc, argv);
  if (!command_line.error.empty()) {
    std::fprintf(stderr, "%s%s\n", kErrorPrefix, command_line.error.c_str());
    print_usage(stderr);
    return EXIT_FAILURE;
  }
  if (command_line.show_help) {
    print_usage(stdout);
    return EXIT_SUCCESS;
  }
  lua_State* L = nullptr;
  try {
    L = command_line.sandbox.enabled ? sandboxed_state(command_line) : luaL_newstate();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s%s\n", kErrorPrefix, e.what());
    return EXIT_FAILURE;
  }
  if (L == nullptr) {
    std::fprintf(stderr, "%scannot create state: not enough memory\n", kErrorPrefix);
    return EXIT_FAILURE;
  }
  lua_pushcfunction(L, run_host);
  lua_pushlightuserdata(L, &command_line);
  const int status = lua_pcall(L, 1, 1, 0);
  const bool succeeded = status == LUA_OK && lua_toboolean(L, -1);
  report(L, status);
  ashlar::sandbox::close_state(L);
  // A terminated job ends as SIGTERM ends a process; mpirun and Slurm
  // stop the other ranks.
  ashlar::host::end_if_terminated();
  // One rank failing alone would leave the others waiting for it.
  if (!succeeded) ashlar::cluster::abort_job(EXIT_FAILURE);
  ashlar::cluster::leave();
  return succeeded ? EXIT_SUCCESS : EXIT_FAILURE;
}
