#include "core/sparse_cholesky.hpp"

#include <malloc.h>

#include <algorithm>
#include <array>
#include <thread>

#include "core/blas.hpp"
#include "core/cholmod_system.hpp"
#include "core/sparse_pattern.hpp"
#include "core/split_cholesky.hpp"

namespace ashlar {

struct SparseCholesky::Impl {
  Impl(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices, int block_rows)
      : pattern(n, column_starts, row_indices, block_rows) {}

  // The caller's values (pattern order), whole or split, and the pattern
  // by its blocks, which finds each entry's value.
  std::vector<double> values;
  const BlockPattern pattern;
  // When split: the two sides and their separator.
  std::unique_ptr<SplitCholesky> split;
  // When not split: the lower triangle in CHOLMOD's own fill-reducing
  // order (the form CholmodSystem::factorize takes), its values read from
  // the caller's.
  std::unique_ptr<CholmodSystem> whole;
  FactorRows whole_rows;     // the caller's row at each factor row, and back
  Eigen::VectorXd permuted;  // solve buffer, factor order

  void analyse_whole(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices);
};

void SparseCholesky::Impl::analyse_whole(int n, const std::vector<int>& column_starts,
                                         const std::vector<int>& row_indices) {
  CholmodSystem upper(n, column_starts.data(), row_indices.data(), CholmodSystem::Triangle::upper);
  upper.analyze();
  const int* perm = upper.permutation();
  whole_rows = FactorRows(n, std::vector<int>(perm, perm + n), pattern.block_rows());  // postordered with it
  const std::vector<int>& position = whole_rows.factor_row;
  std::vector<std::array<int, 2>> entries;  // {column, row}, lower triangle in factor order
  entries.reserve(row_indices.size());
  for (int j = 0; j < n; ++j) {
    for (int e = column_starts[j]; e < column_starts[j + 1]; ++e) {
      const int a = position[row_indices[e]], b = position[j];
      entries.push_back({std::min(a, b), std::max(a, b)});
    }
  }
  const ColumnPattern lower = compress_columns(n, entries);
  whole = std::make_unique<CholmodSystem>(n, lower.column_starts.data(), lower.row_indices.data(),
                                          CholmodSystem::Triangle::lower);
  whole->analyze_as_ordered();
}

SparseCholesky::SparseCholesky(int n, std::vector<int> column_starts, std::vector<int> row_indices,
                               const SparseCholeskyOptions& options)
    : impl_(std::make_unique<Impl>(n, column_starts, row_indices, options.block_rows)) {
  const bool two_cores = std::thread::hardware_concurrency() >= 2;
  if (n >= options.split_from_rows && (two_cores || options.split_from_rows == 0)) {
    impl_->split = SplitCholesky::analyse(n, column_starts, row_indices, options.block_rows,
                                          options.max_separator_rows);
  }
  if (!impl_->split) impl_->analyse_whole(n, column_starts, row_indices);
  impl_->values.assign(row_indices.size(), 0.0);
  // The analysis's working arrays (the halves' entries, patterns and
  // orderings: 12 bytes and more per entry, on the split's two threads)
  // are freed now, but glibc keeps freed memory inside its arenas (a
  // thread's own among them, which the solver's allocations on the main
  // thread never reuse): returned here, the 100,052-block vault's resident
  // peak 2,335-2,372 -> 2,239 MiB. Below a million entries there is
  // little to return.
  if (row_indices.size() >= 1000000) malloc_trim(0);
}

SparseCholesky::~SparseCholesky() = default;

double* SparseCholesky::values() { return impl_->values.data(); }

const std::vector<int>& SparseCholesky::column_starts() const { return impl_->pattern.column_starts(); }

int SparseCholesky::nonzeros() const { return static_cast<int>(impl_->values.size()); }

int SparseCholesky::separator_rows() const { return impl_->split ? impl_->split->separator_rows() : 0; }

double SparseCholesky::factor_nonzeros() const {
  return impl_->whole ? impl_->whole->factor_nonzeros() : impl_->split->factor_nonzeros();
}

bool SparseCholesky::factorize() {
  // The factorisations are tuned for one BLAS thread (core/blas.hpp); this
  // is where the engine sets it, and the BLAS kernels, for the whole
  // process.
  set_up_blas_in_whole_process();
  ++factorizations_;
  Impl& m = *impl_;
  if (m.split) return m.split->factorize(m.pattern, m.values.data());
  return m.whole->factorize(PatternColumns(m.pattern, m.values.data(), m.whole_rows));
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd out;
  solve(rhs, out);
  return out;
}

void SparseCholesky::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) const {
  Impl& m = *impl_;
  if (m.split) {
    m.split->solve(rhs, out);
    return;
  }
  const int n = static_cast<int>(rhs.size());
  m.permuted.resize(n);
  for (int k = 0; k < n; ++k) m.permuted[k] = rhs[m.whole_rows.caller_row[k]];
  const double* x = m.whole->solve(CholmodSystem::Solve::whole, m.permuted.data());
  out.resize(n);
  for (int k = 0; k < n; ++k) out[m.whole_rows.caller_row[k]] = x[k];
}

}  // namespace ashlar
