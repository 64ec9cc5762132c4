// A sparse Cholesky factorisation on two cores by one level of domain
// decomposition, for SparseCholesky (core/sparse_cholesky.hpp) on large
// patterns. A vertex separator S splits the unknowns into parts A and B
// with no entry between them,
//     M = [ M_AA   0     M_AS ]
//         [ 0      M_BB  M_BS ]
//         [ M_SA   M_SB  M_SS ],
// and [M_AA M_AS; M_SA M_SS] and [M_BB M_BS; M_SB M_SS] are factored at
// the same time, each with S ordered last. The trailing block L_SS of each
// factor gives that side's share of the Schur complement
//     M_SS - M_SA M_AA^-1 M_AS = L_SS L_SS^T   (and the same for B),
// so the Schur complement of M onto S is T_A + T_B - M_SS, a small dense
// matrix (separator rows squared) factored by dense Cholesky. Solves run
// the two sides' triangular solves in parallel around one dense solve on
// S. The result is the same factorisation of M as a whole (A, then B, then
// S); only its order of operations differs.
//
// Patterns and values as SparseCholesky takes them: the n x n upper
// triangle in compressed columns, values in pattern order.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/parallel_loop.hpp"

namespace ashlar {

class BlockPattern;

class SplitCholesky {
public:
  // The split of the pattern (in bodies of block_rows rows, as
  // SparseCholeskyOptions::block_rows), its two sides ordered and analysed
  // (each on its own core); null when the pattern has no usable separator (none,
  // more than max_separator_rows rows, or a side of fewer than n / 8 rows)
  // or CHOLMOD cannot order it.
  static std::unique_ptr<SplitCholesky> analyse(int n, const std::vector<int>& column_starts,
                                                const std::vector<int>& row_indices, int block_rows,
                                                int max_separator_rows);
  ~SplitCholesky();
  SplitCholesky(const SplitCholesky&) = delete;
  SplitCholesky& operator=(const SplitCholesky&) = delete;

  // Numeric factorisation of `values` (the whole pattern's, as analysed,
  // its entries found through `pattern`); false when the matrix is not
  // (numerically) positive definite.
  bool factorize(const BlockPattern& pattern, const double* values);
  // Solves with the last factorisation into `out` (n), reusing buffers
  // (one solve at a time).
  void solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& out);
  int separator_rows() const { return static_cast<int>(separator_.size()); }
  // Nonzeros of both sides' factors and the dense Schur factor.
  double factor_nonzeros() const;

private:
  struct Side;
  SplitCholesky();
  bool split(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices, int block_rows,
             int max_separator_rows);

  std::unique_ptr<Side> sides_[2];
  std::vector<int> separator_;  // the whole matrix's rows of S, ascending: the separator order
  struct SeparatorEntry {
    int value, row, column;  // value index; separator positions, row >= column
  };
  std::vector<SeparatorEntry> separator_entries_;  // M_SS's entries
  Eigen::MatrixXd schur_;  // the Schur complement on S, then its Cholesky factor (lower)
  Eigen::VectorXd separator_rhs_;
  ParallelLoop loop_{2};
};

}  // namespace ashlar
