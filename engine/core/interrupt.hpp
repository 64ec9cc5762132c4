// Ctrl-C for long C++ loops: the host's SIGINT handler sets the flag (an
// async-signal-safe atomic store), loops that cannot rely on a Lua hook
// (a study's coordinator waiting for worker threads) poll it.
#pragma once

#include <atomic>

namespace ashlar {

inline std::atomic<bool>& interrupt_requested() {
  static std::atomic<bool> requested{false};
  return requested;
}

}  // namespace ashlar
