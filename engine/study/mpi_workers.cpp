#include "study/mpi_workers.hpp"

#include <numeric>
#include <stdexcept>

#include "core/error.hpp"
#include "study/cluster.hpp"

#ifdef ASHLAR_WITH_MPI
#include <mpi.h>
#endif

namespace ashlar::study {

namespace {

constexpr int kReached = 11;  // rank -> 0: the study's name
constexpr int kTask = 12;     // 0 -> rank: a row to run
constexpr int kOutcome = 13;  // rank -> 0: what it gave
constexpr int kTable = 14;    // 0 -> rank: the finished table; stop
constexpr int kRowsInFlight = 2;

#ifdef ASHLAR_WITH_MPI
void send(int destination, int tag, const std::string& bytes) {
  MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_CHAR, destination, tag, MPI_COMM_WORLD);
}

// Receives the message that `status` announced.
std::string receive_probed(const MPI_Status& status) {
  int size = 0;
  MPI_Get_count(&status, MPI_CHAR, &size);
  std::string bytes(static_cast<std::size_t>(size), '\0');
  MPI_Recv(bytes.data(), size, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return bytes;
}
#else
[[noreturn]] void no_mpi() { throw std::logic_error("this ashlar was built without MPI"); }
#endif

}  // namespace

RankWorkers::RankWorkers(std::string study_name)
    : study_name_(std::move(study_name)),
      reached_(static_cast<std::size_t>(cluster::size()), false),
      outstanding_(static_cast<std::size_t>(cluster::size()), 0) {
  reached_[0] = true;
}

std::size_t RankWorkers::in_flight() const {
  return static_cast<std::size_t>(std::accumulate(outstanding_.begin(), outstanding_.end(), 0));
}

std::size_t RankWorkers::capacity() const {
  return static_cast<std::size_t>(kRowsInFlight) * (outstanding_.size() - 1);
}

void RankWorkers::handle(int source, int tag, const std::string& bytes, std::vector<Outcome>& arrived) {
  if (tag == kReached) {
    if (bytes != study_name_)
      throw Error("MPI rank " + std::to_string(source) + " reached study '" + bytes + "' while rank 0 runs '" +
                  study_name_ + "': every rank must run the same script with the same arguments");
    reached_[static_cast<std::size_t>(source)] = true;
  } else if (tag == kOutcome) {
    arrived.push_back(decode_outcome(bytes));
    --outstanding_[static_cast<std::size_t>(source)];
  } else {
    throw Error("MPI rank " + std::to_string(source) + " sent an unexpected message (tag " + std::to_string(tag) + ")");
  }
}

void RankWorkers::fill(int rank, const std::function<std::optional<Task>()>& next_task) {
#ifdef ASHLAR_WITH_MPI
  const auto r = static_cast<std::size_t>(rank);
  while (reached_[r] && outstanding_[r] < kRowsInFlight) {
    std::optional<Task> task = next_task();
    if (!task) return;
    send(rank, kTask, encode(*task));
    ++outstanding_[r];
  }
#else
  (void)rank;
  (void)next_task;
  no_mpi();
#endif
}

void RankWorkers::exchange(const std::function<std::optional<Task>()>& next_task, std::vector<Outcome>& arrived) {
#ifdef ASHLAR_WITH_MPI
  for (;;) {
    int waiting = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &waiting, &status);
    if (!waiting) break;
    handle(status.MPI_SOURCE, status.MPI_TAG, receive_probed(status), arrived);
  }
  for (int rank = 1; rank < cluster::size(); ++rank) fill(rank, next_task);
#else
  (void)next_task;
  (void)arrived;
  no_mpi();
#endif
}

void RankWorkers::finish(const StudyTable& table) {
#ifdef ASHLAR_WITH_MPI
  std::vector<Outcome> unexpected;
  for (int rank = 1; rank < cluster::size(); ++rank) {
    while (!reached_[static_cast<std::size_t>(rank)]) {
      MPI_Status status;
      MPI_Probe(rank, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
      handle(status.MPI_SOURCE, status.MPI_TAG, receive_probed(status), unexpected);
    }
  }
  if (!unexpected.empty()) throw Error("MPI: outcomes arrived after the study '" + study_name_ + "' finished");
  const std::string bytes = encode_table(table.parameter_names, table.field_names, table.rows);
  for (int rank = 1; rank < cluster::size(); ++rank) send(rank, kTable, bytes);
#else
  (void)table;
  no_mpi();
#endif
}

StudyTable work_for_rank_zero(const std::string& study_name, RowWorker& worker) {
#ifdef ASHLAR_WITH_MPI
  send(0, kReached, study_name);
  for (;;) {
    MPI_Status status;
    MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    const std::string bytes = receive_probed(status);
    if (status.MPI_TAG == kTable) {
      StudyTable table;
      decode_table(bytes, table.parameter_names, table.field_names, table.rows);
      return table;
    }
    if (status.MPI_TAG != kTask) throw Error("MPI: unexpected message from rank 0 (tag " + std::to_string(status.MPI_TAG) + ")");
    Outcome outcome = worker.run(decode_task(bytes));
    outcome.worker = cluster::rank() * 1000 + 1;
    send(0, kOutcome, encode(outcome));
  }
#else
  (void)study_name;
  (void)worker;
  no_mpi();
#endif
}

}  // namespace ashlar::study
