// Passes over a problem's force groups, split over a ParallelLoop's
// threads: the interior-point solver's per-group work (residuals,
// eliminations, back-substitutions) at every iteration.
//
// A pass that adds into the balance rows (rows long; the groups of two
// parts may share a body's rows) gives each part after the first a rows
// vector of its own, summed in, in part order, at the end: the same sums
// whatever the threads' timing.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <vector>

#include "core/parallel_loop.hpp"

namespace ashlar {

class GroupPasses {
public:
  // `groups` groups adding into `rows` balance rows; `loop` must outlive this.
  GroupPasses(ParallelLoop& loop, int groups, int rows)
      : loop_(loop), groups_(groups), rows_(rows), row_parts_(loop.parts() - 1) {}

  // per_group(k) for every group k. Generic, not std::function: the
  // per-group body is inlined into the loop (an indirect call per group was
  // 3 % of an important-weights run).
  template <typename PerGroup>
  void each(const PerGroup& per_group) {
    loop_.run(groups_, [&](int begin, int end, int) {
      for (int k = begin; k < end; ++k) per_group(k);
    });
  }

  // per_group(k, rows_of_part) for every group k, each adding its share
  // into the rows vector of its part; `rows` then holds the sum.
  template <typename PerGroup>
  void each_into(Eigen::VectorXd& rows, const PerGroup& per_group) {
    largest_into(rows, [&](int k, Eigen::VectorXd& rows_of_part) {
      per_group(k, rows_of_part);
      return 0.0;
    });
  }

  // each_into's pass with per_group(k, rows_of_part) also returning a size:
  // the largest of them (0 with no groups).
  template <typename PerGroup>
  double largest_into(Eigen::VectorXd& rows, const PerGroup& per_group) {
    const int parts = loop_.parts_for(groups_);
    std::vector<double> part_largest(parts, 0.0);
    loop_.run(groups_, [&](int begin, int end, int part) {
      Eigen::VectorXd& target = part == 0 ? rows : row_parts_[part - 1];
      if (part > 0) target.setZero(rows_);
      double most = 0.0;
      for (int k = begin; k < end; ++k) most = std::max(most, per_group(k, target));
      part_largest[part] = most;
    });
    for (int part = 1; part < parts; ++part) rows += row_parts_[part - 1];
    return *std::max_element(part_largest.begin(), part_largest.end());
  }

  // The largest of per_group(k) over every group k (0 with no groups).
  template <typename PerGroup>
  double largest(const PerGroup& per_group) {
    std::vector<double> part_largest(loop_.parts(), 0.0);
    loop_.run(groups_, [&](int begin, int end, int part) {
      double most = 0.0;
      for (int k = begin; k < end; ++k) most = std::max(most, per_group(k));
      part_largest[part] = most;
    });
    return *std::max_element(part_largest.begin(), part_largest.end());
  }

private:
  ParallelLoop& loop_;
  int groups_ = 0;
  int rows_ = 0;
  std::vector<Eigen::VectorXd> row_parts_;
};

}  // namespace ashlar
