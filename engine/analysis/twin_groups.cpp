#include "analysis/twin_groups.hpp"

#include <algorithm>
#include <utility>

namespace ashlar {

namespace {

// Whether contact vertices p and q are twins: the same rules, bodies and
// bound, and the same effect on the d balance rows to rounding (on b's,
// and the same lever for a's). Effects are scaled, O(1) per unit force.
bool are_twins(const ForceGroup& p, const ForceGroup& q, int d) {
  constexpr double kSameEffect = 1e-13;
  auto same = [&](const Eigen::Matrix<double, 6, 4>& e, const Eigen::Matrix<double, 6, 4>& f) {
    return (e.topRows(d) - f.topRows(d)).lpNorm<Eigen::Infinity>() <=
           kSameEffect * (1.0 + e.topRows(d).lpNorm<Eigen::Infinity>());
  };
  return p.kind == GroupKind::contact_vertex && q.kind == GroupKind::contact_vertex &&
         p.row_a == q.row_a && p.row_b == q.row_b && p.bound == q.bound &&
         same(p.on_b, q.on_b) &&
         (p.row_a < 0 || (p.lever - q.lever).lpNorm<Eigen::Infinity>() <= kSameEffect * (1.0 + p.lever.lpNorm<Eigen::Infinity>()));
}

}  // namespace

bool TwinGroups::find(const EquilibriumProblem& problem, int block_rows, bool merge) {
  // Twins come from one interface (its vertices are consecutive groups); a
  // vertex is compared with the classes begun among the kTwinWindow groups
  // before it, so that a polygon of many vertices costs O(vertices).
  constexpr int kTwinWindow = 16;
  const int n = merge ? static_cast<int>(problem.groups.size()) : 0;
  TwinGroups twins;
  twins.merged_of_.resize(n);
  int run_start = 0;
  for (int k = 0; k < n; ++k) {
    const ForceGroup& group = problem.groups[k];
    if (k == 0 || group.source != problem.groups[k - 1].source ||
        group.kind != problem.groups[k - 1].kind) {
      run_start = k;
    }
    int twin = -1;
    for (int j = std::max(run_start, k - kTwinWindow); j < k && twin < 0; ++j) {
      const int merged = twins.merged_of_[j];
      if (twins.first_member_[merged] == j && are_twins(problem.groups[j], group, block_rows)) twin = merged;
    }
    if (twin >= 0) {
      twins.merged_of_[k] = twin;
      twins.count_[twin] += 1.0;
    } else {
      twins.merged_of_[k] = static_cast<int>(twins.first_member_.size());
      twins.first_member_.push_back(k);
      twins.count_.push_back(1.0);
    }
  }
  if (static_cast<int>(twins.first_member_.size()) == n) twins = TwinGroups{};
  if (twins.merged_of_ == merged_of_) return false;
  *this = std::move(twins);
  return true;
}

EquilibriumProblem TwinGroups::merge(const EquilibriumProblem& problem) const {
  // The classes' groups alone are made: copying the problem's groups and
  // compacting them was a seventh of the 10,051-block planar wall's
  // analysis (0.13 s: 45 MB of fresh memory, written once each).
  EquilibriumProblem merged;
  static_cast<ProblemFrame&>(merged) = problem;
  const int n = classes();
  merged.groups.reserve(n);
  for (int j = 0; j < n; ++j) {
    merged.groups.push_back(problem.groups[first_member_[j]]);
    ForceGroup& group = merged.groups.back();
    group.on_b *= count_[j];  // and so on_a()
    if (group.kind == GroupKind::contact_vertex) ++merged.contact_vertex_count;
  }
  return merged;
}

std::vector<int> TwinGroups::merged_first_rows(const std::vector<int>& full_first_row) const {
  std::vector<int> starts(first_member_.size() + 1, 0);
  for (size_t j = 0; j < first_member_.size(); ++j) {
    const int k = first_member_[j];
    starts[j + 1] = starts[j] + full_first_row[k + 1] - full_first_row[k];
  }
  return starts;
}

void TwinGroups::merge_solution(const InteriorPointIterate& full, const std::vector<int>& full_first_row,
                                InteriorPointIterate& merged) const {
  const int n = classes();
  merged.x.resize(4 * n);
  merged.y = full.y;
  const std::vector<int> starts = merged_first_rows(full_first_row);
  merged.w.resize(starts.back());
  merged.z.resize(starts.back());
  for (int j = 0; j < n; ++j) {
    const int k = first_member_[j];
    const int rows = starts[j + 1] - starts[j];
    merged.x.segment<4>(4 * j) = full.x.segment<4>(4 * k);
    merged.w.segment(starts[j], rows) = full.w.segment(full_first_row[k], rows);
    merged.z.segment(starts[j], rows) = count_[j] * full.z.segment(full_first_row[k], rows);
  }
}

void TwinGroups::split_solution(const InteriorPointIterate& merged, const std::vector<int>& full_first_row,
                                InteriorPointIterate& full) const {
  const int n = static_cast<int>(merged_of_.size());
  if (merged.x.size() != 4 * classes()) {  // no iterate (the solve stopped before its first)
    full = InteriorPointIterate{};
    return;
  }
  const std::vector<int> merged_first_row = merged_first_rows(full_first_row);
  full.x.resize(4 * n);
  full.y = merged.y;
  full.w.resize(full_first_row[n]);
  full.z.resize(full_first_row[n]);
  for (int k = 0; k < n; ++k) {
    const int j = merged_of_[k];
    const int rows = full_first_row[k + 1] - full_first_row[k];
    full.x.segment<4>(4 * k) = merged.x.segment<4>(4 * j);
    full.w.segment(full_first_row[k], rows) = merged.w.segment(merged_first_row[j], rows);
    full.z.segment(full_first_row[k], rows) = merged.z.segment(merged_first_row[j], rows) / count_[j];
  }
}

}  // namespace ashlar
