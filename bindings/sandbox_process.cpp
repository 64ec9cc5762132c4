#include "sandbox_process.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <thread>

#include "core/error.hpp"

namespace ashlar::sandbox {

namespace {

// "64M", "2G", "512K" or a number of bytes.
bool parse_size(const char* text, std::size_t& bytes) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text, &end);
  if (end == text || errno != 0 || !(value >= 0)) return false;
  double scale = 1;
  switch (*end) {
    case '\0': break;
    case 'K': case 'k': scale = 1024.0; ++end; break;
    case 'M': case 'm': scale = 1024.0 * 1024.0; ++end; break;
    case 'G': case 'g': scale = 1024.0 * 1024.0 * 1024.0; ++end; break;
    default: return false;
  }
  if (*end == 'B' || *end == 'b') ++end;  // "64MB"
  const double scaled = std::floor(value * scale);
  if (*end != '\0' || scaled > 1e18) return false;
  bytes = static_cast<std::size_t>(scaled);
  return true;
}

// Bytes of the data segment now (VmData of /proc/self/status); 0 if unknown.
// Unused under AddressSanitizer, where limit_process sets no RLIMIT_DATA.
[[maybe_unused]] std::size_t data_segment_bytes() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmData:") {
      std::size_t kilobytes = 0;
      status >> kilobytes;
      return kilobytes * 1024;
    }
    status.ignore(1 << 20, '\n');
  }
  return 0;
}

void write_error(const char* message) {
  const ssize_t ignored = ::write(STDERR_FILENO, message, std::strlen(message));
  (void)ignored;
}

}  // namespace

bool parse_count(const char* text, std::uint64_t& count) {
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text, &end);  // "1e9" is allowed
  if (end == text || *end != '\0' || errno != 0 || !(value >= 0) || value > 1e18 || value != std::floor(value))
    return false;
  count = static_cast<std::uint64_t>(value);
  return true;
}

bool parse_seconds(const char* text, double& seconds) {
  char* end = nullptr;
  errno = 0;
  seconds = std::strtod(text, &end);
  return end != text && *end == '\0' && errno == 0 && seconds >= 0 && std::isfinite(seconds);
}

bool takes_value(const char* option) {
  static const char* const kWithValue[] = {"--read", "--write", "--memory", "--engine-memory", "--instructions",
                                           "--time"};
  for (const char* name : kWithValue)
    if (std::strcmp(option, name) == 0) return true;
  return false;
}

bool parse_option(int argc, char** argv, int& i, ProcessOptions& options, std::string& error) {
  const char* option = argv[i];
  if (std::strcmp(option, "--sandbox") == 0) {
    options.enabled = true;
    return true;
  }
  if (!takes_value(option)) return false;
  if (i + 1 >= argc) {
    error = std::string("'") + option + "' needs argument";
    return true;
  }
  const char* value = argv[++i];
  bool valid = true;
  if (std::strcmp(option, "--read") == 0) {
    options.settings.read_folders.emplace_back(value);
    options.folders_given = true;
  } else if (std::strcmp(option, "--write") == 0) {
    options.settings.write_folders.emplace_back(value);
    options.folders_given = true;
  } else if (std::strcmp(option, "--memory") == 0) {
    valid = parse_size(value, options.settings.memory_bytes);
  } else if (std::strcmp(option, "--engine-memory") == 0) {
    valid = parse_size(value, options.engine_memory_bytes);
  } else if (std::strcmp(option, "--instructions") == 0) {
    valid = parse_count(value, options.settings.instructions);
  } else {
    valid = parse_seconds(value, options.settings.seconds);
  }
  if (!valid)
    error = std::string("'") + option + "': '" + value + "' is not " +
            (std::strcmp(option, "--time") == 0            ? "a number of seconds >= 0"
             : std::strcmp(option, "--instructions") == 0  ? "a whole number >= 0"
             : std::strncmp(option, "--read", 6) == 0 || std::strncmp(option, "--write", 7) == 0 ? "a folder"
                                                          : "a size such as 512M or 2G");
  return true;
}

void complete_settings(ProcessOptions& options, const char* script) {
  namespace fs = std::filesystem;
  const fs::path folder = script ? fs::path(script).parent_path() : fs::path();
  options.settings.base_folder = folder.string();
  if (options.folders_given) return;
  options.settings.read_folders.push_back(folder.empty() ? "." : folder.string());
  const fs::path output = folder / kDefaultOutputFolder;
  std::error_code error;
  fs::create_directories(output, error);
  if (error)
    throw Error("sandbox: cannot create the output folder '" + output.string() + "': " + error.message());
  options.settings.write_folders.push_back(output.string());
}

void limit_process(const ProcessOptions& options) {
#if !defined(__SANITIZE_ADDRESS__)  // AddressSanitizer maps its shadow memory as it goes
  if (options.engine_memory_bytes != 0) {
    const rlim_t limit = static_cast<rlim_t>(data_segment_bytes() + options.engine_memory_bytes);
    rlimit data{};
    getrlimit(RLIMIT_DATA, &data);
    if (data.rlim_max == RLIM_INFINITY || limit <= data.rlim_max) data.rlim_cur = limit;
    if (setrlimit(RLIMIT_DATA, &data) != 0)
      throw Error(std::string("sandbox: cannot limit the process's memory: ") + std::strerror(errno));
  }
#endif
  const double seconds = options.settings.seconds;
  if (seconds <= 0) return;
  // Past the deadline the hook stops Lua code and the engine's loops stop
  // themselves; this is for C code that never returns to either.
  const double grace = std::max(2.0, 0.1 * seconds);
  static char message[160];
  std::snprintf(message, sizeof message,
                "ashlar: sandbox: time limit of %g s exceeded, and the script did not stop within %g s "
                "(stuck in C code); process ended\n",
                seconds, grace);
  std::thread([delay = seconds + grace] {
    std::this_thread::sleep_for(std::chrono::duration<double>(delay));
    write_error(message);
    std::_Exit(EXIT_FAILURE);
  }).detach();
}

}  // namespace ashlar::sandbox
