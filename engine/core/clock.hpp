// The clock behind every `seconds` a result reports.
#pragma once

#include <chrono>

namespace ashlar {

using Clock = std::chrono::steady_clock;

// Seconds elapsed since `start`.
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace ashlar
