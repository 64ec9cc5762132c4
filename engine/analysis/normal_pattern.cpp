#include "analysis/normal_pattern.hpp"

#include <algorithm>
#include <iterator>
#include <utility>

namespace ashlar {

NormalPattern::NormalPattern(const EquilibriumProblem& problem)
    : rows_(problem.row_count), block_rows_(problem.block_rows) {
  const int d = block_rows_;
  std::vector<std::vector<int>>& upper = block_pattern_;
  upper.assign(blocks(), {});
  for (int j = 0; j < blocks(); ++j) upper[j].push_back(j);
  for (const ForceGroup& v : problem.groups) {
    if (v.row_a >= 0 && v.row_b >= 0) {
      const int a = v.row_a / d, b = v.row_b / d;
      upper[std::max(a, b)].push_back(std::min(a, b));
    }
  }
  for (std::vector<int>& rows : upper) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
}

UpperPattern NormalPattern::upper_triangle() const {
  const int d = block_rows_;
  UpperPattern out;
  out.column_starts.assign(rows_ + 1, 0);
  for (int j = 0; j < blocks(); ++j) {
    for (int cj = 0; cj < d; ++cj) {
      for (int i : block_pattern_[j]) {
        const int last = i == j ? cj : d - 1;  // diagonal block: upper part only
        for (int ri = 0; ri <= last; ++ri) out.row_indices.push_back(d * i + ri);
      }
      out.column_starts[d * j + cj + 1] = static_cast<int>(out.row_indices.size());
    }
  }
  return out;
}

bool NormalPattern::find_slots(const EquilibriumProblem& problem, std::vector<GroupSlots>& slots) const {
  const int d = block_rows_;
  // Block (i, j), i <= j: its rank among column j's block rows, -1 if absent.
  auto rank = [&](int i, int j) {
    const std::vector<int>& rows = block_pattern_[j];
    const auto at = std::lower_bound(rows.begin(), rows.end(), i);
    return at != rows.end() && *at == i ? static_cast<int>(at - rows.begin()) : -1;
  };
  slots.assign(problem.groups.size(), GroupSlots{});
  for (size_t k = 0; k < problem.groups.size(); ++k) {
    const ForceGroup& v = problem.groups[k];
    GroupSlots& slot = slots[k];
    slot.row_a = v.row_a;
    slot.row_b = v.row_b;
    if (v.row_a >= 0) slot.aa = rank(v.row_a / d, v.row_a / d);
    if (v.row_b >= 0) slot.bb = rank(v.row_b / d, v.row_b / d);
    if (v.row_a >= 0 && v.row_b >= 0) {
      const int a = v.row_a / d, b = v.row_b / d;
      slot.ab_transposed = a > b;
      slot.ab = rank(std::min(a, b), std::max(a, b));
      if (slot.ab < 0) return false;
    }
  }
  return true;
}

AssemblyParts partition_assembly(const std::vector<GroupSlots>& slots, int blocks, int block_rows, int parts) {
  const int nv = static_cast<int>(slots.size());
  parts = std::min(parts, std::max(blocks, 1));
  const int d = block_rows;
  // The blocks each group adds: C_a C_a^T in column a, C_b C_b^T in column
  // b, C_a C_b^T in column max(a, b).
  std::vector<long long> adds(blocks + 1, 0);
  for (const GroupSlots& slot : slots) {
    if (slot.row_a >= 0) ++adds[slot.row_a / d];
    if (slot.row_b >= 0) ++adds[slot.row_b / d];
    if (slot.ab >= 0) ++adds[std::max(slot.row_a, slot.row_b) / d];
  }
  long long total = 0;
  for (long long& a : adds) total += std::exchange(a, total);  // now: adds before column j
  AssemblyParts out;
  out.first_column.assign(parts + 1, blocks);
  out.first_column[0] = 0;
  for (int p = 1, j = 0; p < parts; ++p) {
    while (j < blocks && adds[j] * parts < total * p) ++j;
    out.first_column[p] = j;
  }
  out.groups.assign(parts, {});
  if (parts == 1) return out;  // the one part takes every group in order
  auto part_of = [&](int column) {
    return static_cast<int>(std::upper_bound(out.first_column.begin(), out.first_column.end(), column) -
                            out.first_column.begin()) -
           1;
  };
  for (int k = 0; k < nv; ++k) {
    const GroupSlots& slot = slots[k];
    int touched[3] = {-1, -1, -1};
    if (slot.row_a >= 0) touched[0] = part_of(slot.row_a / d);
    if (slot.row_b >= 0) touched[1] = part_of(slot.row_b / d);
    if (slot.ab >= 0) touched[2] = part_of(std::max(slot.row_a, slot.row_b) / d);
    std::sort(std::begin(touched), std::end(touched));
    for (int i = 0; i < 3; ++i) {
      if (touched[i] >= 0 && (i == 0 || touched[i] != touched[i - 1])) out.groups[touched[i]].push_back(k);
    }
  }
  return out;
}

}  // namespace ashlar
