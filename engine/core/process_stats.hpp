// Wall-clock time and memory use of this process, for benchmarks.
#pragma once

namespace ashlar {

// Seconds on a monotonic clock; only differences are meaningful.
double monotonic_seconds();

struct MemoryUse {
  double resident_mb = 0.0;  // current resident set size, MiB
  double peak_mb = 0.0;      // highest resident set size so far (or since reset), MiB
};

// Reads /proc/self/status (Linux); falls back to getrusage for the peak.
MemoryUse memory_use();

// Restarts peak tracking at the current size (Linux clear_refs); returns
// false where the system does not allow it.
bool reset_peak_memory();

}  // namespace ashlar
