// Stopping long C++ loops: Ctrl-C, the deadline of a sandboxed script, and
// a failed part of a parallel loop. The host's SIGINT handler sets
// interrupt_requested (an async-signal-safe atomic store); the Lua bindings
// set the calling thread's stop_deadline for the length of each call from a
// sandboxed state; ParallelLoop gives its parts the caller's deadline and a
// flag of its own (stop_flag) that it raises when one part throws, so the
// others stop early. Loops that run no Lua (solver iterations, a study's
// coordinator) poll stop_requested.
#pragma once

#include <atomic>

#include "core/clock.hpp"

namespace ashlar {

inline std::atomic<bool>& interrupt_requested() {
  static std::atomic<bool> requested{false};
  return requested;
}

inline Clock::time_point& stop_deadline() {
  thread_local Clock::time_point deadline = Clock::time_point::max();
  return deadline;
}

inline const std::atomic<bool>*& stop_flag() {
  thread_local const std::atomic<bool>* flag = nullptr;
  return flag;
}

inline bool stop_requested() {
  return interrupt_requested().load(std::memory_order_relaxed) ||
         (stop_flag() && stop_flag()->load(std::memory_order_relaxed)) ||
         (stop_deadline() != Clock::time_point::max() && Clock::now() >= stop_deadline());
}

// Sets the calling thread's deadline for its lifetime (nested calls keep the
// earlier of the two).
class DeadlineScope {
public:
  explicit DeadlineScope(Clock::time_point deadline) : saved_(stop_deadline()) {
    if (deadline < saved_) stop_deadline() = deadline;
  }
  ~DeadlineScope() { stop_deadline() = saved_; }
  DeadlineScope(const DeadlineScope&) = delete;
  DeadlineScope& operator=(const DeadlineScope&) = delete;

private:
  Clock::time_point saved_;
};

// Sets the calling thread's stop flag for its lifetime (restoring the one
// before).
class StopFlagScope {
public:
  explicit StopFlagScope(const std::atomic<bool>* flag) : saved_(stop_flag()) { stop_flag() = flag; }
  ~StopFlagScope() { stop_flag() = saved_; }
  StopFlagScope(const StopFlagScope&) = delete;
  StopFlagScope& operator=(const StopFlagScope&) = delete;

private:
  const std::atomic<bool>* saved_;
};

}  // namespace ashlar
