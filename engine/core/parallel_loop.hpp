// A loop split over a few threads, for the solver's passes over force
// groups and for analyses that share blocks among workers: the caller runs
// the first part, helper threads the others, and the helpers sleep on a
// condition variable between calls (no thread spins while another works).
// Small loops run on the caller alone. Every part answers to the caller's
// stop deadline (a sandbox's), and once a part throws, stop_requested() is
// true in the others (core/interrupt.hpp) so that they end early; the
// first error is rethrown on the caller after every part has returned.
#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "core/clock.hpp"

namespace ashlar {

// Worker threads for `items` independent pieces of work: `requested`, or
// one per hardware thread when it is 0 or less, but no more than the items
// and at least one.
int worker_count(int requested, int items);

class ParallelLoop {
public:
  // body(begin, end, part): the items [begin, end) of part `part`.
  using Body = std::function<void(int begin, int end, int part)>;

  // `threads` parts at most (0 or less: one per core, at most kMaxThreads),
  // used only for loops of at least `grain` items; helpers start on first
  // use.
  explicit ParallelLoop(int threads = 0, int grain = 20000);
  ~ParallelLoop();
  ParallelLoop(const ParallelLoop&) = delete;
  ParallelLoop& operator=(const ParallelLoop&) = delete;

  // How many parts run() may use: sizes per-part buffers.
  int parts() const { return parts_; }
  // How many parts run(n, ...) uses for n items.
  int parts_for(int n) const { return n >= grain_ ? parts_ : 1; }
  // Runs body over [0, n) in parts_for(n) contiguous parts and returns when
  // all are done; an exception in any part is rethrown here.
  void run(int n, const Body& body);
  // Runs task(part) for every part in [0, parts) (parts <= parts()), each
  // on its own thread, and returns when all are done; errors as run().
  void run_parts(int parts, const std::function<void(int part)>& task);

  static constexpr int kMaxThreads = 8;

private:
  // body over [0, n) in `parts` parts (1 < parts <= parts_).
  void dispatch(int n, int parts, const Body& body);
  void helper(int part);

  int parts_ = 1;
  int grain_ = 20000;
  std::vector<std::thread> helpers_;
  std::mutex mutex_;
  std::condition_variable work_ready_, work_done_;
  const Body* body_ = nullptr;
  int items_ = 0;
  int parts_in_use_ = 1;  // of the current call
  unsigned generation_ = 0;
  int pending_ = 0;
  bool stopping_ = false;
  std::exception_ptr failure_;
  Clock::time_point deadline_ = Clock::time_point::max();  // the caller's, for the current call
  std::atomic<bool> failed_{false};                         // a part of the current call threw
};

}  // namespace ashlar
