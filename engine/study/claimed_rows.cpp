#include "study/claimed_rows.hpp"

#include <algorithm>
#include <chrono>
#include <set>

#include "core/process_stats.hpp"

namespace ashlar::study {

ClaimedRows::ClaimedRows(StudyStore& store, std::string name, std::vector<Task> unfinished, ClaimTimes times)
    : store_(store),
      name_(std::move(name)),
      times_(times),
      candidates_(std::make_move_iterator(unfinished.begin()), std::make_move_iterator(unfinished.end())) {
  run_ = store_.begin_run(name_, times_.lease);
  last_beat_ = monotonic_seconds();
}

ClaimedRows::~ClaimedRows() {
  try {
    end();
  } catch (...) {
  }
}

void ClaimedRows::end() {
  if (ended_) return;
  ended_ = true;
  store_.end_run(run_);
}

double ClaimedRows::retry_in() const { return std::max(0.0, next_retry_ - monotonic_seconds()); }

std::vector<Task> ClaimedRows::take(std::size_t count) {
  std::vector<Task> taken;
  if (count == 0) return taken;
  if (candidates_.empty() && !elsewhere_.empty()) {
    if (monotonic_seconds() < next_retry_) return taken;
    candidates_.swap(elsewhere_);
    next_retry_ = monotonic_seconds() + times_.retry;
  }
  while (taken.size() < count && !candidates_.empty()) {
    // A slice of the candidates at a time: the store looks at them in order
    // and stops once it claimed enough.
    const std::size_t slice = std::min(candidates_.size(), std::max<std::size_t>(2 * count, 32));
    std::vector<std::int64_t> ids;
    ids.reserve(slice);
    for (std::size_t i = 0; i < slice; ++i) ids.push_back(candidates_[i].id);
    const StudyStore::ClaimResult result = store_.claim(name_, run_, ids, count - taken.size(), times_.lease);
    last_beat_ = monotonic_seconds();
    if (!result.lease_kept) lease_lost_ = true;
    const std::set<std::int64_t> claimed(result.claimed.begin(), result.claimed.end());
    const std::set<std::int64_t> elsewhere(result.elsewhere.begin(), result.elsewhere.end());
    for (std::size_t i = 0; i < result.examined; ++i) {
      Task task = std::move(candidates_.front());
      candidates_.pop_front();
      if (claimed.count(task.id)) {
        taken.push_back(std::move(task));
      } else if (elsewhere.count(task.id)) {
        elsewhere_.push_back(std::move(task));
        next_retry_ = monotonic_seconds() + times_.retry;
      } else {
        ++finished_elsewhere_;
      }
    }
  }
  return taken;
}

bool ClaimedRows::beat() {
  if (monotonic_seconds() - last_beat_ >= times_.heartbeat) {
    if (!store_.heartbeat(name_, run_, times_.lease)) lease_lost_ = true;
    last_beat_ = monotonic_seconds();
  }
  const bool kept = !lease_lost_;
  lease_lost_ = false;
  return kept;
}

void ClaimedRows::give_back(std::vector<Task> tasks) {
  for (auto task = tasks.rbegin(); task != tasks.rend(); ++task) candidates_.push_front(std::move(*task));
}

HeartbeatThread::HeartbeatThread(const std::string& db, const std::string& name, std::int64_t run, ClaimTimes times) {
  if (db.empty()) return;
  thread_ = std::thread([this, db, name, run, times] {
    std::unique_ptr<StudyStore> store;
    try {
      store = std::make_unique<StudyStore>(db);
    } catch (...) {
      return;  // the coordinator's own claims and records still beat
    }
    const auto interval = std::chrono::duration<double>(times.heartbeat);
    std::unique_lock lock(mutex_);
    while (!stop_changed_.wait_for(lock, interval, [this] { return stop_; })) {
      lock.unlock();
      try {
        store->heartbeat(name, run, times.lease);
      } catch (...) {
        // busy beyond the timeout: the next beat tries again
      }
      lock.lock();
    }
  });
}

HeartbeatThread::~HeartbeatThread() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  stop_changed_.notify_all();
  thread_.join();
}

}  // namespace ashlar::study
