// Sparse Cholesky factorisation (CHOLMOD, supernodal) of symmetric positive
// definite matrices that share one sparsity pattern: the pattern is analysed
// (fill-reducing ordering, symbolic factor) once, then any number of
// numeric factorisations and solves reuse it. CHOLMOD stays in the .cpp.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace ashlar {

class SparseCholesky {
public:
  // The n x n pattern's upper triangle in compressed columns: rows of column
  // j are row_indices[column_starts[j] .. column_starts[j+1]), ascending.
  SparseCholesky(int n, std::vector<int> column_starts, std::vector<int> row_indices);
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // The values array (pattern order) to fill before factorize().
  double* values();
  int nonzeros() const;
  // Numeric factorisation of the current values; false when the matrix is
  // not (numerically) positive definite.
  bool factorize();
  // Solves with the last factorisation.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;
  // The same into `out`, reusing its storage and CHOLMOD's workspace (not
  // thread-safe: one solve at a time per object).
  void solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) const;
  int factorizations() const { return factorizations_; }
  // Nonzeros of the Cholesky factor, from the symbolic analysis (memory is
  // about 8 bytes each, plus the supernodes' row indices).
  double factor_nonzeros() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int factorizations_ = 0;
};

}  // namespace ashlar
