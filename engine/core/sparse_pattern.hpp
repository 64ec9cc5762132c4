// Patterns of sparse symmetric matrices as core/sparse_cholesky.hpp takes
// them (the n x n upper triangle in compressed columns: rows of column j are
// row_indices[column_starts[j] .. column_starts[j + 1]), ascending; values
// in the same order), and how the factorisations read their values:
// - compress_columns: a pattern rebuilt from its entries (permuted, or a
//   part of another), for CHOLMOD's symbolic analysis;
// - BlockPattern: the caller's pattern kept by its blocks, which finds any
//   entry's value in the caller's array by arithmetic;
// - PatternColumns: the caller's values handed to a CholmodSystem as the
//   columns of its factor order, through a BlockPattern.
// A factor's column is filled from the caller's values at every numeric
// factorisation; found per block, the entries' places cost no memory per
// entry (a map per entry, a row and a value index, was 102 MB on a
// 100,052-block vault's two split halves).
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "core/cholmod_system.hpp"

namespace ashlar {

// A pattern in compressed columns, rows ascending in each column.
struct ColumnPattern {
  std::vector<int> column_starts, row_indices;
};

// Entry {column, row} pairs of an n x n pattern into compressed columns:
// bucketed by column, then each column sorted by row.
ColumnPattern compress_columns(int n, const std::vector<std::array<int, 2>>& entries);

// An upper-triangle pattern whose rows come in consecutive runs of d (a
// body's unknowns) and whose entries are whole d x d blocks: a block (i, j)
// of bodies i < j holds all its d x d entries, a diagonal block (j, j) its
// upper triangle (every diagonal block present). d = 1 takes any pattern.
class BlockPattern {
public:
  // Throws Error, naming the column, when the pattern is not made of such
  // blocks.
  BlockPattern(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices,
               int block_rows);

  // Calls visit(body, value) for each block of column j of the whole
  // symmetric matrix (both triangles, in no particular order): the block's
  // entries are (d body + r, j) for r = 0 .. d - 1 (d = block_rows()), and
  // value(r) is the index of entry r's value in pattern order (of (i, j) or
  // of (j, i), whichever the upper triangle holds).
  template <typename Visit>
  void for_each_block_in_column(int j, Visit&& visit) const {
    const int d = block_rows_, body = j / d, c = j % d;
    const int first = upper_starts_[body], last = upper_starts_[body + 1] - 1;  // last: the diagonal block
    for (int k = first; k < last; ++k) {
      const int value = column_starts_[j] + d * (k - first);
      visit(upper_bodies_[k], [value](int r) { return value + r; });
    }
    const int* diagonal_column = column_starts_.data() + d * body;
    const int diagonal = d * (last - first);
    visit(body, [=](int r) { return diagonal_column[std::max(r, c)] + diagonal + std::min(r, c); });
    for (int k = lower_starts_[body]; k < lower_starts_[body + 1]; ++k) {
      const int* other_column = column_starts_.data() + d * lower_bodies_[k][0];
      const int offset = d * lower_bodies_[k][1] + c;
      visit(lower_bodies_[k][0], [=](int r) { return other_column[r] + offset; });
    }
  }
  int block_rows() const { return block_rows_; }
  const std::vector<int>& column_starts() const { return column_starts_; }

private:
  int block_rows_ = 1;
  std::vector<int> column_starts_;  // the caller's
  // Per body j: the bodies i < j whose block (i, j) is present, ascending
  // (its rank among them places its values in column j), then j itself.
  std::vector<int> upper_starts_, upper_bodies_;
  // Per body j: the bodies i > j whose block (j, i) is present, each with
  // j's rank in its list above.
  std::vector<int> lower_starts_;
  std::vector<std::array<int, 2>> lower_bodies_;
};

// Which of the caller's rows a factor holds, in which order.
struct FactorRows {
  FactorRows() = default;
  // The caller's row at each factor row (ascending k), of a pattern of n
  // rows in bodies of block_rows.
  FactorRows(int n, std::vector<int> caller_rows, int block_rows);
  std::vector<int> caller_row;    // the caller's row at factor row k
  std::vector<int> factor_row;    // the factor row of the caller's row i, -1 if it holds none
  // The last factor row of body b's rows, -1 if it holds none: a factor
  // column skips the blocks of the bodies whose rows all come before its
  // own.
  std::vector<int> last_of_body;
  // k when body b's rows are factor rows k, k + 1, .. in their own order
  // (as orderings that keep a body's rows together place them), else -1: its
  // blocks are then placed without looking up each row.
  std::vector<int> run_of_body;
};

// The caller's values (pattern order) as the columns of a factor holding
// `rows`: column j takes the entries at factor rows k >= j. References,
// not copies: they must outlive it.
class PatternColumns final : public CholmodSystem::Columns {
public:
  PatternColumns(const BlockPattern& pattern, const double* values, const FactorRows& rows)
      : pattern_(pattern), values_(values), rows_(rows) {}

  // Per block, not per entry: a map per entry (row and value index) was
  // 102 MB on the 100,052-block vault's split halves. The time is the
  // values' cache misses, as it was, and the blocks' bookkeeping: on the
  // 10,051-block wall in 3D about twice the map's (410 against 210 of the
  // run's 16,500 samples, perf), 1 % of the analysis.
  void fill(int j, const int* slot, double* column) const override {
    const int d = pattern_.block_rows();
    const double* values = values_;
    const int* factor_row = rows_.factor_row.data();
    const int* last_of_body = rows_.last_of_body.data();
    const int* run_of_body = rows_.run_of_body.data();
    pattern_.for_each_block_in_column(rows_.caller_row[j], [=](int body, auto value) {
      if (last_of_body[body] < j) return;
      const int run = run_of_body[body];
      if (run >= j) {
        for (int r = 0; r < d; ++r) column[slot[run + r]] = values[value(r)];
        return;
      }
      for (int r = 0; r < d; ++r) {
        const int k = factor_row[d * body + r];
        if (k >= j) column[slot[k]] = values[value(r)];
      }
    });
  }

private:
  const BlockPattern& pattern_;
  const double* values_;
  const FactorRows& rows_;
};

}  // namespace ashlar
