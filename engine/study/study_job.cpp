#include "study/study_job.hpp"

#include <algorithm>
#include <climits>
#include <optional>

#include "core/error.hpp"
#include "core/parallel_loop.hpp"
#include "study/cluster.hpp"
#include "study/mpi_workers.hpp"
#include "study/study_store.hpp"

namespace ashlar::study {

int study_threads(int workers, bool threads_possible, std::size_t pending) {
  if (pending == 0 || (workers == 0 && !threads_possible)) return 0;
  const int threads = worker_count(workers, static_cast<int>(std::min<std::size_t>(pending, INT_MAX)));
  return threads <= 1 ? 0 : threads;
}

StudyResult run_study_job(const StudyJob& job, RowWorker& calling_thread_worker, const WorkerFactory& thread_workers) {
  if (job.workers > 1 && !thread_workers)
    throw InvalidArgument("study '" + job.name + "': " + std::to_string(job.workers) +
                          " workers asked for, but no worker threads can be made");
  StudyResult result;
  if (cluster::size() > 1 && cluster::rank() > 0) {
    result.table = work_for_rank_zero(job.name, calling_thread_worker);
    return result;
  }
  StudyStore store(job.db);
  const StudyTable table = store.open_study(job.name, job.rows, job.rerun_errors);
  StudySettings settings;
  settings.progress = job.progress;
  settings.log_interval = job.log_interval;
  std::optional<RankWorkers> ranks;
  if (cluster::size() > 1) {
    if (!thread_workers) throw InvalidArgument("study '" + job.name + "': under MPI, rank 0 needs a worker thread");
    ranks.emplace(job.name);
    settings.threads = 1;  // one row at a time on every rank, rank 0's beside its coordinating thread
  } else {
    settings.threads = study_threads(job.workers, static_cast<bool>(thread_workers),
                                     table.rows.size() - table.finished_count());
  }
  result.info = run_study(store, job.name, table, settings, &calling_thread_worker, thread_workers,
                          ranks ? &*ranks : nullptr);
  result.table = store.open_study(job.name, job.rows);
  if (ranks) ranks->finish(result.table);
  if (result.info.interrupted)
    throw Error("interrupted! study '" + job.name + "' keeps its " + std::to_string(result.table.finished_count()) +
                " finished rows of " + std::to_string(result.table.rows.size()) + "; run the script again to go on");
  return result;
}

}  // namespace ashlar::study
