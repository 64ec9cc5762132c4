// Runs the unfinished rows of a study: on the calling thread, on worker
// threads (each with its own worker, e.g. its own Lua state), and on remote
// workers (MPI ranks), recording every outcome in the store as it arrives.
// The calling thread is the only one that touches the store (but for the
// heartbeat thread while it runs a row itself, see claimed_rows).
//
// Other processes may run the same study on the same database: rows are
// claimed a few at a time (what the workers can take next) before they run,
// so no row runs in two processes; rows other processes hold are waited for
// (see claimed_rows), so the run ends with every row of the table finished.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "study/claimed_rows.hpp"
#include "study/study_store.hpp"

namespace ashlar::study {

// Runs rows; made, used and destroyed on one thread.
class RowWorker {
public:
  virtual ~RowWorker() = default;
  // Runs one row. A failing run is an outcome with status error, not an
  // exception; an exception means the worker itself is broken (the study
  // then stops).
  virtual Outcome run(const Task& task) = 0;
};

// Makes the worker for thread `worker_number` (1-based), on that thread.
// Throws when it cannot (the message says why).
using WorkerFactory = std::function<std::unique_ptr<RowWorker>(int worker_number)>;

// Workers in other processes, served by the calling thread between local
// outcomes (see study/mpi_workers). Every call returns without waiting long.
class RemoteWorkers {
public:
  virtual ~RemoteWorkers() = default;
  // Hands tasks taken from next_task to remotes that have room for them and
  // appends the outcomes that arrived.
  virtual void exchange(const std::function<std::optional<Task>()>& next_task, std::vector<Outcome>& arrived) = 0;
  // Tasks handed out whose outcome has not arrived.
  virtual std::size_t in_flight() const = 0;
  // Tasks the remotes can hold at once: how many rows to claim for them.
  virtual std::size_t capacity() const = 0;
};

struct StudySettings {
  // Worker threads. 0 runs every row on the calling thread with
  // calling_thread_worker (then the only worker).
  int threads = 0;
  bool progress = true;  // progress line on stderr
  double log_interval = 10.0;  // seconds between progress lines when stderr is not a terminal
  ClaimTimes claims;           // lease, heartbeat and retry of rows other processes hold
};

struct StudyRunInfo {
  std::size_t ran = 0;       // outcomes recorded in this session
  std::size_t errors = 0;    // of which ended in error
  double seconds = 0.0;      // wall time of this session
  int workers = 0;           // workers that ran rows (threads + remotes' first outcomes)
  bool interrupted = false;  // Ctrl-C: stopped handing out rows, kept what finished
  std::size_t elsewhere = 0;  // rows other processes finished meanwhile (none of them ran here)
  std::vector<std::string> worker_failures;  // workers that could not start, with why
};

// Runs every unfinished row of `table` (a table returned by
// store.open_study(name, ...)) and records the outcomes in the store.
// Outcomes whose fields break the column rules (column_name_problem, a
// parameter's name, twice the same name) are recorded as errors. Throws
// when no worker could start, with the first reason; an interruption is a
// flag in the result.
StudyRunInfo run_study(StudyStore& store, const std::string& name, const StudyTable& table,
                       const StudySettings& settings, RowWorker* calling_thread_worker,
                       const WorkerFactory& thread_workers, RemoteWorkers* remote = nullptr);

// The outcome with its fields checked against the column rules; a broken
// one becomes an error outcome that says what was wrong.
Outcome checked_outcome(Outcome outcome, const std::vector<std::string>& parameter_names);

}  // namespace ashlar::study
