// Sparse Cholesky factorisation (CHOLMOD, supernodal) of symmetric positive
// definite matrices that share one sparsity pattern: the pattern is analysed
// (fill-reducing ordering, symbolic factor) once, then any number of
// numeric factorisations and solves reuse it.
//
// Large patterns are factored on two cores by one level of domain
// decomposition (core/split_cholesky.hpp); the result is the same
// factorisation, in another order of operations. CHOLMOD is reached
// through core/cholmod_system.hpp, whose .cpp alone includes cholmod.h.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace ashlar {

struct SparseCholeskyOptions {
  // Patterns of at least this many rows are split over two cores (when the
  // machine has them; 0 splits every pattern that has a separator, on any
  // machine). Measured on 2 cores: running-bond walls solved in 3D take the
  // same time split or whole at 1,590 rows (265 blocks) and 15 % less at
  // 2,976 rows; the 16 x 18 dome (1,830 rows) 15 % less; planar walls 9 %
  // less at 2,748 rows.
  int split_from_rows = 2000;
  // A separator larger than this (rows) keeps the whole factorisation: the
  // split holds five dense separator-sized matrices (8 bytes x rows^2 each:
  // 250 MB at this bound) and factors one of them densely. Walls and vaults
  // of 10,000-100,000 blocks are cut by 300-600 rows; compact 3D meshes
  // (FEA) may not be, and stay whole.
  int max_separator_rows = 2500;
  // The pattern's rows come in runs of this many (a body's unknowns) and
  // its entries are whole blocks of as many rows and columns (the diagonal
  // ones' upper triangles): the factorisations then find each value by its
  // block, with no map per entry (core/sparse_pattern.hpp). 1 takes any
  // pattern, at 12 bytes per entry off the diagonal.
  int block_rows = 1;
};

class SparseCholesky {
public:
  // The n x n pattern's upper triangle in compressed columns: rows of column
  // j are row_indices[column_starts[j] .. column_starts[j+1]), ascending.
  // Every diagonal entry must be present. Throws Error when the pattern is
  // not made of options.block_rows blocks.
  SparseCholesky(int n, std::vector<int> column_starts, std::vector<int> row_indices,
                 const SparseCholeskyOptions& options = {});
  ~SparseCholesky();
  SparseCholesky(const SparseCholesky&) = delete;
  SparseCholesky& operator=(const SparseCholesky&) = delete;

  // The values array (pattern order) to fill before factorize().
  double* values();
  int nonzeros() const;
  // The pattern's column starts as given: column j's values are
  // values()[column_starts()[j] .. column_starts()[j + 1]).
  const std::vector<int>& column_starts() const;
  // Numeric factorisation of the current values; false when the matrix is
  // not (numerically) positive definite. The first call in the process
  // sets OpenBLAS to one thread, and to its kernels for the CPU, for the
  // whole process (set_up_blas_in_whole_process, core/blas.hpp).
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
  // Rows of the separator when the factorisation is split over two cores,
  // 0 when it is factored whole.
  int separator_rows() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int factorizations_ = 0;
};

}  // namespace ashlar
