#include "study/study_runner.hpp"

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <set>
#include <thread>

#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "core/process_stats.hpp"
#include "study/study_progress.hpp"

namespace ashlar::study {

Outcome checked_outcome(Outcome outcome, const std::vector<std::string>& parameter_names) {
  if (const std::string problem = fields_problem(outcome, parameter_names); !problem.empty()) {
    outcome.status = RunStatus::error;
    outcome.error = "returned field " + problem;
    outcome.fields.clear();
  }
  return outcome;
}

namespace {

// What the worker threads and the coordinating thread share.
struct SharedQueue {
  std::mutex mutex;
  std::condition_variable changed;         // to the coordinator: an outcome, a thread ended
  std::condition_variable work_available;  // to the threads: a task, or stop
  std::deque<Task> pending;                // claimed, not started
  std::vector<Outcome> outcomes;
  std::size_t running = 0;      // tasks taken by threads whose outcome is not queued yet
  int live_threads = 0;
  bool stop = false;            // no more tasks to anyone: the threads end
  std::vector<std::string> failures;

  std::optional<Task> take() {  // with the mutex held
    if (stop || pending.empty()) return std::nullopt;
    Task task = std::move(pending.front());
    pending.pop_front();
    return task;
  }
};

void work(SharedQueue& queue, const WorkerFactory& factory, int number) {
  std::unique_ptr<RowWorker> worker;
  std::string failure;
  try {
    worker = factory(number);
  } catch (const std::exception& e) {
    failure = "worker " + std::to_string(number) + " could not start: " + e.what();
  }
  while (worker) {
    std::optional<Task> task;
    {
      std::unique_lock lock(queue.mutex);
      queue.work_available.wait(lock, [&] { return queue.stop || !queue.pending.empty(); });
      task = queue.take();
      if (!task) break;
      ++queue.running;
    }
    try {
      Outcome outcome = worker->run(*task);
      outcome.worker = number;
      std::lock_guard lock(queue.mutex);
      queue.outcomes.push_back(std::move(outcome));
      --queue.running;
    } catch (const std::exception& e) {
      failure = "worker " + std::to_string(number) + " stopped: " + e.what();
      std::lock_guard lock(queue.mutex);
      queue.pending.push_front(std::move(*task));  // another worker takes it
      --queue.running;
      queue.work_available.notify_one();
      break;
    }
    queue.changed.notify_one();
  }
  worker.reset();  // on this thread, where it was made
  std::lock_guard lock(queue.mutex);
  if (!failure.empty()) queue.failures.push_back(failure);
  --queue.live_threads;
  queue.changed.notify_one();
}

// Stops and joins the worker threads however the coordinator leaves.
class WorkerThreads {
public:
  WorkerThreads(SharedQueue& queue, const WorkerFactory& factory, int count) : queue_(queue) {
    queue_.live_threads = count;
    for (int i = 1; i <= count; ++i) threads_.emplace_back(work, std::ref(queue_), std::cref(factory), i);
  }
  ~WorkerThreads() {
    {
      std::lock_guard lock(queue_.mutex);
      queue_.stop = true;
    }
    queue_.work_available.notify_all();
    for (auto& thread : threads_) thread.join();
  }

private:
  SharedQueue& queue_;
  std::vector<std::thread> threads_;
};

// How many rows a worker gets per claim: about `batch` seconds of work by
// the mean time of the rows so far (1 until one has finished), so that fast
// rows do not cost a transaction each and slow ones are shared finely.
class RowPace {
public:
  void add(const Outcome& outcome) {
    seconds_ += std::max(outcome.seconds, 0.0);
    ++rows_;
  }
  std::size_t per_worker(double batch) const {
    if (rows_ == 0) return 1;
    const double mean = std::max(seconds_ / static_cast<double>(rows_), 1e-6);
    return static_cast<std::size_t>(std::clamp(batch / mean, 1.0, 256.0));
  }

private:
  double seconds_ = 0.0;
  std::size_t rows_ = 0;
};

// Sleeps up to `seconds` in short naps, returning early on a stop request.
void nap(double seconds) {
  const double until = monotonic_seconds() + seconds;
  while (!stop_requested()) {
    const double left = until - monotonic_seconds();
    if (left <= 0) return;
    std::this_thread::sleep_for(std::chrono::duration<double>(std::min(left, 0.05)));
  }
}

}  // namespace

StudyRunInfo run_study(StudyStore& store, const std::string& name, const StudyTable& table,
                       const StudySettings& settings, RowWorker* calling_thread_worker,
                       const WorkerFactory& thread_workers, RemoteWorkers* remote) {
  std::vector<Task> unfinished;
  for (const Row& row : table.rows)
    if (!row.finished) unfinished.push_back(row.task);
  const std::size_t total = unfinished.size();
  StudyProgress progress(name, total, settings.progress, stderr, settings.log_interval);
  StudyRunInfo info;
  std::set<int> workers_seen;
  const double start = monotonic_seconds();
  if (total == 0) {  // nothing to claim: no run to register
    progress.finish(0, 0);
    return info;
  }
  ClaimedRows claims(store, name, std::move(unfinished), settings.claims);
  RowPace pace;

  auto record = [&](std::vector<Outcome>& batch) {
    if (batch.empty()) return;
    for (Outcome& outcome : batch) {
      pace.add(outcome);
      outcome = checked_outcome(std::move(outcome), table.parameter_names);
      info.errors += outcome.status == RunStatus::error;
      workers_seen.insert(outcome.worker);
    }
    store.record(name, batch);
    info.ran += batch.size();
    batch.clear();
  };

  if (settings.threads == 0 && remote == nullptr) {
    if (calling_thread_worker == nullptr) throw InvalidArgument("study: no worker to run the rows");
    // The calling thread runs the rows: another thread keeps the heartbeat
    // while a long row runs.
    const HeartbeatThread heartbeat(store.path(), name, claims.run(), settings.claims);
    std::vector<Outcome> batch;
    std::deque<Task> mine;  // claimed, not started
    while (!(mine.empty() && claims.done())) {
      if (stop_requested()) {
        info.interrupted = true;
        break;
      }
      if (!claims.beat()) {  // lost the lease: claim the unstarted rows again
        claims.give_back(std::vector<Task>(std::make_move_iterator(mine.begin()), std::make_move_iterator(mine.end())));
        mine.clear();
      }
      if (mine.empty()) {
        std::vector<Task> next = claims.take(pace.per_worker(settings.claims.batch));
        if (next.empty()) {  // the rows left run in other processes: wait for them
          progress.update(info.ran + claims.finished_elsewhere(), info.errors);
          nap(std::max(claims.retry_in(), 0.01));
          continue;
        }
        mine.assign(std::make_move_iterator(next.begin()), std::make_move_iterator(next.end()));
      }
      batch.push_back(calling_thread_worker->run(mine.front()));
      mine.pop_front();
      batch.back().worker = 1;
      record(batch);
      progress.update(info.ran + claims.finished_elsewhere(), info.errors);
    }
  } else {
    SharedQueue queue;
    // Workers to keep rows claimed ahead for: the threads and what the
    // remotes hold; each gets RowPace's rows per claim.
    const std::size_t slots = static_cast<std::size_t>(settings.threads) + (remote ? remote->capacity() : 0);
    // Keeps the heartbeat to the end (rows may run long after the last is
    // claimed) and the queue filled.
    auto refill = [&] {
      std::vector<Task> returned;
      {
        std::lock_guard lock(queue.mutex);
        if (queue.stop) return;
      }
      if (!claims.beat()) {  // lost the lease: claim the unstarted rows again
        std::lock_guard lock(queue.mutex);
        returned.assign(std::make_move_iterator(queue.pending.begin()), std::make_move_iterator(queue.pending.end()));
        queue.pending.clear();
      }
      if (!returned.empty()) claims.give_back(std::move(returned));
      std::size_t queued;
      {
        std::lock_guard lock(queue.mutex);
        queued = queue.pending.size();
      }
      // Claimed again once half of what was claimed ahead has started.
      const std::size_t ahead = slots * pace.per_worker(settings.claims.batch);
      std::vector<Task> taken = 2 * queued <= ahead ? claims.take(ahead - queued) : std::vector<Task>{};
      if (taken.empty()) return;
      std::lock_guard lock(queue.mutex);
      for (Task& task : taken) queue.pending.push_back(std::move(task));
      queue.work_available.notify_all();
    };
    refill();  // before the threads start: work for them at once
    {
      WorkerThreads threads(queue, thread_workers, settings.threads);
      std::vector<Outcome> batch;
      auto next_task = [&queue]() {
        std::lock_guard lock(queue.mutex);
        return queue.take();
      };
      for (;;) {
        bool local_idle;
        bool stalled;
        {
          std::unique_lock lock(queue.mutex);
          // Remote messages are polled, so wait briefly when there are remotes.
          queue.changed.wait_for(lock, std::chrono::milliseconds(remote ? 1 : 200),
                                 [&] { return !queue.outcomes.empty() || queue.live_threads == 0; });
          batch.swap(queue.outcomes);
          if (stop_requested() && !queue.stop) {
            queue.stop = true;
            info.interrupted = true;
            queue.work_available.notify_all();
          }
          local_idle = queue.running == 0;
          stalled = queue.live_threads == 0 && remote == nullptr && !queue.stop &&
                    !(queue.pending.empty() && claims.done());
        }
        if (remote) remote->exchange(next_task, batch);
        record(batch);
        refill();
        progress.update(info.ran + claims.finished_elsewhere(), info.errors);
        const bool remote_idle = remote == nullptr || remote->in_flight() == 0;
        bool finished;
        {
          std::lock_guard lock(queue.mutex);
          finished = ((queue.pending.empty() && claims.done()) || queue.stop) && local_idle && queue.running == 0 &&
                     queue.outcomes.empty() && remote_idle;
        }
        if (finished) break;
        if (stalled) {
          const std::size_t left = total - info.ran - claims.finished_elsewhere();
          std::lock_guard lock(queue.mutex);
          const std::string why = queue.failures.empty() ? "every worker stopped" : queue.failures.front();
          throw Error("study '" + name + "': no worker left to run the " + std::to_string(left) +
                      " remaining rows; " + why);
        }
      }
    }  // joined: every thread's failure is in
    info.worker_failures = queue.failures;
  }
  claims.end();
  info.elsewhere = claims.finished_elsewhere();
  info.seconds = monotonic_seconds() - start;
  info.workers = static_cast<int>(workers_seen.size());
  std::string note = info.interrupted ? "interrupted" : "";
  if (info.elsewhere > 0)
    note += (note.empty() ? "" : "; ") + std::to_string(info.elsewhere) + " rows run by other processes";
  progress.finish(info.ran, info.errors, note);
  return info;
}

}  // namespace ashlar::study
