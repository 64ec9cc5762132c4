// A study from start to finish, as ashlar.study runs it: where this process
// stands (an MPI rank above 0 serves rank 0; rank 0, or a process on its
// own, opens the store), how many worker threads run the rows, the run
// itself (study_runner) and the table read back from the store.
#pragma once

#include <string>

#include "study/parameter_rows.hpp"
#include "study/study_runner.hpp"
#include "study/study_table.hpp"

namespace ashlar::study {

struct StudyJob {
  std::string name;  // its table in the store (study_name_problem)
  std::string db;    // the SQLite file; empty: a private in-memory store
  ParameterRows rows;
  bool rerun_errors = false;  // rows that ended in error run again
  // Worker threads asked for: 0 is one per hardware thread when worker
  // threads can be made, else 1. One worker runs the rows on the calling
  // thread; never more threads than rows left to run.
  int workers = 0;
  bool progress = true;       // see StudySettings
  double log_interval = 10.0;
};

struct StudyResult {
  StudyTable table;  // every row as stored after the run
  StudyRunInfo info;
};

// Runs `job`. `calling_thread_worker` runs the rows when one worker does
// (and, on an MPI rank above 0, the rows rank 0 sends); `thread_workers`
// makes the worker of each worker thread, and may be empty when none can be
// made: then `workers` must be 0 or 1 and the process not part of an MPI
// job (rank 0 runs its rows on a worker thread beside the coordinator).
// Throws Error when the study was interrupted (Ctrl-C, a sandbox's
// deadline), saying how many rows it keeps; every finished row is in the
// store by then.
StudyResult run_study_job(const StudyJob& job, RowWorker& calling_thread_worker, const WorkerFactory& thread_workers);

// The worker threads for `pending` rows: 0 (the calling thread runs them)
// when one worker is enough, else worker_count's choice.
int study_threads(int workers, bool threads_possible, std::size_t pending);

}  // namespace ashlar::study
