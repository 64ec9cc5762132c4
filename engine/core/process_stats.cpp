#include "core/process_stats.hpp"

#include <sys/resource.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>

namespace ashlar {

double monotonic_seconds() {
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

MemoryUse memory_use() {
  MemoryUse use;
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    std::istringstream fields(line);
    std::string key;
    double kib = 0.0;
    fields >> key >> kib;
    if (key == "VmRSS:") use.resident_mb = kib / 1024.0;
    if (key == "VmHWM:") use.peak_mb = kib / 1024.0;
  }
  if (use.peak_mb == 0.0) {
    rusage usage{};
    if (getrusage(RUSAGE_SELF, &usage) == 0) use.peak_mb = usage.ru_maxrss / 1024.0;
  }
  return use;
}

bool reset_peak_memory() {
  std::ofstream clear_refs("/proc/self/clear_refs");
  clear_refs << "5";
  clear_refs.flush();
  return static_cast<bool>(clear_refs);
}

}  // namespace ashlar
