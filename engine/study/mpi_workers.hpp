// A study across the ranks of an MPI job. Every rank runs the same script;
// at ashlar.study rank 0 opens the database and hands rows out, the other
// ranks run them and send the outcomes back, and when all rows are done
// every rank gets the finished table, so the script goes on alike on all.
//
// Messages (tags): a rank says it reached the study (its name), rank 0
// sends it rows, keeping two in flight per rank so a rank never waits for
// its next row, the rank returns outcomes; at the end rank 0 sends the
// table, which tells the rank to stop.
//
// Only meaningful when cluster::size() > 1; in a build without MPI the
// calls throw std::logic_error.
#pragma once

#include <string>
#include <vector>

#include "study/study_runner.hpp"

namespace ashlar::study {

// Rank 0's view of the other ranks.
class RankWorkers : public RemoteWorkers {
public:
  explicit RankWorkers(std::string study_name);

  void exchange(const std::function<std::optional<Task>()>& next_task, std::vector<Outcome>& arrived) override;
  std::size_t in_flight() const override;
  std::size_t capacity() const override;

  // Waits until every rank has reached the study, then sends each the
  // finished table.
  void finish(const StudyTable& table);

private:
  void handle(int source, int tag, const std::string& bytes, std::vector<Outcome>& arrived);
  void fill(int rank, const std::function<std::optional<Task>()>& next_task);

  std::string study_name_;
  std::vector<bool> reached_;       // by rank
  std::vector<int> outstanding_;    // rows sent and not returned, by rank
};

// A rank above 0: runs the rows rank 0 sends with `worker` until the study
// is done, then returns the finished table. Outcomes carry worker number
// rank × 1000 + 1.
StudyTable work_for_rank_zero(const std::string& study_name, RowWorker& worker);

}  // namespace ashlar::study
