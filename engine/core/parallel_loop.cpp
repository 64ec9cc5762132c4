#include "core/parallel_loop.hpp"

#include <algorithm>

#include "core/interrupt.hpp"

namespace ashlar {

int worker_count(int requested, int items) {
  const int available = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, std::min(requested > 0 ? requested : available, items));
}

namespace {

// The first item of part `part` of `parts` over n items.
int part_begin(int n, int parts, int part) {
  return static_cast<int>(static_cast<long long>(n) * part / parts);
}

}  // namespace

ParallelLoop::ParallelLoop(int threads, int grain) : grain_(std::max(grain, 1)) {
  // A count asked for is kept (workers sharing blocks); one per core stops
  // at kMaxThreads (the solver's passes gain nothing beyond).
  if (threads <= 0) threads = std::min(static_cast<int>(std::thread::hardware_concurrency()), kMaxThreads);
  parts_ = std::max(threads, 1);
}

ParallelLoop::~ParallelLoop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_all();
  for (std::thread& t : helpers_) t.join();
}

void ParallelLoop::run(int n, const Body& body) {
  const int parts = parts_for(n);
  if (parts == 1) {
    body(0, n, 0);
    return;
  }
  dispatch(n, parts, body);
}

void ParallelLoop::run_parts(int parts, const std::function<void(int part)>& task) {
  parts = std::clamp(parts, 1, parts_);
  if (parts == 1) {
    task(0);
    return;
  }
  // One item per part: part p gets exactly item p.
  dispatch(parts, parts, [&](int, int, int part) { task(part); });
}

void ParallelLoop::dispatch(int n, int parts, const Body& body) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    while (static_cast<int>(helpers_.size()) < parts - 1) {
      const int part = static_cast<int>(helpers_.size()) + 1;
      helpers_.emplace_back([this, part] { helper(part); });
    }
    body_ = &body;
    items_ = n;
    parts_in_use_ = parts;
    pending_ = parts - 1;
    failure_ = nullptr;
    deadline_ = stop_deadline();
    failed_ = false;
    ++generation_;
  }
  work_ready_.notify_all();
  std::exception_ptr own_failure;
  try {
    const StopFlagScope flag(&failed_);
    body(0, part_begin(n, parts, 1), 0);
  } catch (...) {
    own_failure = std::current_exception();
    failed_ = true;
  }
  std::unique_lock<std::mutex> lock(mutex_);
  work_done_.wait(lock, [this] { return pending_ == 0; });
  body_ = nullptr;
  if (own_failure) std::rethrow_exception(own_failure);
  if (failure_) std::rethrow_exception(failure_);
}

void ParallelLoop::helper(int part) {
  unsigned seen = 0;
  for (;;) {
    const Body* body;
    int n, parts;
    Clock::time_point deadline;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      work_ready_.wait(lock, [&] { return stopping_ || generation_ != seen; });
      if (stopping_) return;
      seen = generation_;
      body = body_;
      n = items_;
      parts = parts_in_use_;
      deadline = deadline_;
    }
    if (part >= parts) continue;  // this call uses fewer parts
    std::exception_ptr failure;
    try {
      const DeadlineScope scope(deadline);
      const StopFlagScope flag(&failed_);
      (*body)(part_begin(n, parts, part), part_begin(n, parts, part + 1), part);
    } catch (...) {
      failure = std::current_exception();
      failed_ = true;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (failure && !failure_) failure_ = failure;
      --pending_;
    }
    work_done_.notify_one();
  }
}

}  // namespace ashlar
