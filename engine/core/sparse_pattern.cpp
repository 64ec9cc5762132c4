#include "core/sparse_pattern.hpp"

#include <string>
#include <utility>

#include "core/error.hpp"

namespace ashlar {

ColumnPattern compress_columns(int n, const std::vector<std::array<int, 2>>& entries) {
  ColumnPattern out;
  out.column_starts.assign(n + 1, 0);
  for (const auto& entry : entries) ++out.column_starts[entry[0] + 1];
  for (int j = 0; j < n; ++j) out.column_starts[j + 1] += out.column_starts[j];
  out.row_indices.resize(entries.size());
  std::vector<int> next(out.column_starts.begin(), out.column_starts.end() - 1);
  for (const auto& [column, row] : entries) out.row_indices[next[column]++] = row;
  for (int j = 0; j < n; ++j) {
    std::sort(out.row_indices.begin() + out.column_starts[j], out.row_indices.begin() + out.column_starts[j + 1]);
  }
  return out;
}

BlockPattern::BlockPattern(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices,
                           int block_rows)
    : block_rows_(block_rows), column_starts_(column_starts) {
  const int d = block_rows;
  if (d < 1 || n % d != 0) {
    throw Error("a pattern of " + std::to_string(n) + " rows is not made of blocks of " + std::to_string(d) + " rows");
  }
  const int bodies = n / d;
  upper_starts_.assign(bodies + 1, 0);
  lower_starts_.assign(bodies + 1, 0);
  upper_bodies_.reserve(bodies + row_indices.size() / (static_cast<size_t>(d) * d));
  for (int j = 0; j < bodies; ++j) {
    // Column d j names the blocks above the diagonal: its rows are theirs,
    // d at a time, then the diagonal's first.
    const int first = column_starts[d * j], above = column_starts[d * j + 1] - 1 - first;
    const int blocks = above / d;
    bool whole_blocks = above >= 0 && above % d == 0;
    for (int k = 0; whole_blocks && k < blocks; ++k) {
      const int row = row_indices[first + d * k];
      whole_blocks = row % d == 0 && row < d * j && (k == 0 || row > row_indices[first + d * (k - 1)]);
    }
    for (int c = 0; whole_blocks && c < d; ++c) {
      const int start = column_starts[d * j + c];
      whole_blocks = column_starts[d * j + c + 1] - start == d * blocks + c + 1;
      for (int k = 0; whole_blocks && k < blocks; ++k) {
        for (int r = 0; r < d; ++r) {
          whole_blocks = whole_blocks && row_indices[start + d * k + r] == row_indices[first + d * k] + r;
        }
      }
      for (int r = 0; whole_blocks && r <= c; ++r) whole_blocks = row_indices[start + d * blocks + r] == d * j + r;
    }
    if (!whole_blocks) {
      throw Error("the pattern's columns " + std::to_string(d * j) + " to " + std::to_string(d * j + d - 1) +
                  " are not made of whole blocks of " + std::to_string(d) + " rows");
    }
    for (int k = 0; k < blocks; ++k) {
      const int body = row_indices[first + d * k] / d;
      upper_bodies_.push_back(body);
      ++lower_starts_[body + 1];
    }
    upper_bodies_.push_back(j);
    upper_starts_[j + 1] = static_cast<int>(upper_bodies_.size());
  }
  for (int j = 0; j < bodies; ++j) lower_starts_[j + 1] += lower_starts_[j];
  lower_bodies_.resize(lower_starts_[bodies]);
  std::vector<int> next(lower_starts_.begin(), lower_starts_.end() - 1);
  for (int j = 0; j < bodies; ++j) {
    for (int k = upper_starts_[j]; k < upper_starts_[j + 1] - 1; ++k) {
      lower_bodies_[next[upper_bodies_[k]]++] = {j, k - upper_starts_[j]};
    }
  }
}

FactorRows::FactorRows(int n, std::vector<int> caller_rows, int block_rows)
    : caller_row(std::move(caller_rows)),
      factor_row(n, -1),
      last_of_body(n / block_rows, -1),
      run_of_body(n / block_rows, -1) {
  const int d = block_rows;
  for (int k = 0; k < static_cast<int>(caller_row.size()); ++k) {
    factor_row[caller_row[k]] = k;
    int& last = last_of_body[caller_row[k] / d];
    last = std::max(last, k);
  }
  for (int body = 0; body < n / d; ++body) {
    const int first = factor_row[d * body];
    bool run = first >= 0;
    for (int r = 1; run && r < d; ++r) run = factor_row[d * body + r] == first + r;
    if (run) run_of_body[body] = first;
  }
}

}  // namespace ashlar
