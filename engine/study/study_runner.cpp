#include "study/study_runner.hpp"

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
  std::condition_variable changed;
  std::deque<Task> pending;
  std::vector<Outcome> outcomes;
  std::size_t running = 0;      // tasks taken by threads whose outcome is not queued yet
  int live_threads = 0;
  bool stop = false;            // no more tasks to anyone
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
      std::lock_guard lock(queue.mutex);
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
    for (auto& thread : threads_) thread.join();
  }

private:
  SharedQueue& queue_;
  std::vector<std::thread> threads_;
};

}  // namespace

StudyRunInfo run_study(StudyStore& store, const std::string& name, const StudyTable& table,
                       const StudySettings& settings, RowWorker* calling_thread_worker,
                       const WorkerFactory& thread_workers, RemoteWorkers* remote) {
  SharedQueue queue;
  for (const Row& row : table.rows)
    if (!row.finished) queue.pending.push_back(row.task);
  const std::size_t total = queue.pending.size();
  StudyProgress progress(name, total, settings.progress, stderr, settings.log_interval);
  StudyRunInfo info;
  std::set<int> workers_seen;
  const double start = monotonic_seconds();

  auto record = [&](std::vector<Outcome>& batch) {
    if (batch.empty()) return;
    for (Outcome& outcome : batch) {
      outcome = checked_outcome(std::move(outcome), table.parameter_names);
      info.errors += outcome.status == RunStatus::error;
      workers_seen.insert(outcome.worker);
    }
    store.record(name, batch);
    info.ran += batch.size();
    batch.clear();
    progress.update(info.ran, info.errors);
  };

  if (settings.threads == 0 && remote == nullptr) {
    if (calling_thread_worker == nullptr) throw InvalidArgument("study: no worker to run the rows");
    std::vector<Outcome> batch;
    while (!queue.pending.empty()) {
      if (stop_requested()) {
        info.interrupted = true;
        break;
      }
      batch.push_back(calling_thread_worker->run(queue.pending.front()));
      batch.back().worker = 1;
      queue.pending.pop_front();
      record(batch);
    }
  } else {
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
          }
          local_idle = queue.running == 0;
          stalled = queue.live_threads == 0 && remote == nullptr && !queue.pending.empty() && !queue.stop;
        }
        if (remote) remote->exchange(next_task, batch);
        record(batch);
        const bool remote_idle = remote == nullptr || remote->in_flight() == 0;
        bool finished;
        {
          std::lock_guard lock(queue.mutex);
          finished = (queue.pending.empty() || queue.stop) && local_idle && queue.running == 0 &&
                     queue.outcomes.empty() && remote_idle;
        }
        if (finished) break;
        if (stalled) {
          std::lock_guard lock(queue.mutex);
          const std::string why = queue.failures.empty() ? "every worker stopped" : queue.failures.front();
          throw Error("study '" + name + "': no worker left to run the " + std::to_string(queue.pending.size()) +
                      " remaining rows; " + why);
        }
      }
    }  // joined: every thread's failure is in
    info.worker_failures = queue.failures;
  }
  info.seconds = monotonic_seconds() - start;
  info.workers = static_cast<int>(workers_seen.size());
  progress.finish(info.ran, info.errors, info.interrupted ? "interrupted" : "");
  return info;
}

}  // namespace ashlar::study
