#include "analysis/sparse_cholesky.hpp"

#include <cholmod.h>

#include <algorithm>

#include "core/error.hpp"

namespace ashlar {

struct SparseCholesky::Impl {
  cholmod_common common;
  cholmod_sparse* matrix = nullptr;
  cholmod_factor* factor = nullptr;

  Impl() {
    cholmod_start(&common);
    common.print = 0;  // statuses are read, not printed
    common.error_handler = nullptr;
  }
  ~Impl() {
    if (factor) cholmod_free_factor(&factor, &common);
    if (matrix) cholmod_free_sparse(&matrix, &common);
    cholmod_finish(&common);
  }
};

SparseCholesky::SparseCholesky(int n, std::vector<int> column_starts,
                               std::vector<int> row_indices)
    : impl_(std::make_unique<Impl>()) {
  const size_t nonzeros = row_indices.size();
  impl_->matrix = cholmod_allocate_sparse(n, n, nonzeros, /*sorted=*/1, /*packed=*/1,
                                          /*stype=upper*/ 1, CHOLMOD_REAL, &impl_->common);
  if (!impl_->matrix) throw Error("CHOLMOD could not allocate the normal-equation matrix");
  std::copy(column_starts.begin(), column_starts.end(), static_cast<int*>(impl_->matrix->p));
  std::copy(row_indices.begin(), row_indices.end(), static_cast<int*>(impl_->matrix->i));
  std::fill_n(static_cast<double*>(impl_->matrix->x), nonzeros, 0.0);
  impl_->common.supernodal = CHOLMOD_SUPERNODAL;
  impl_->factor = cholmod_analyze(impl_->matrix, &impl_->common);
  if (!impl_->factor) throw Error("CHOLMOD could not analyse the normal-equation pattern");
}

SparseCholesky::~SparseCholesky() = default;

double* SparseCholesky::values() { return static_cast<double*>(impl_->matrix->x); }

int SparseCholesky::nonzeros() const {
  return static_cast<int*>(impl_->matrix->p)[impl_->matrix->ncol];
}

double SparseCholesky::factor_nonzeros() const { return impl_->common.lnz; }

bool SparseCholesky::factorize() {
  ++factorizations_;
  const int ok = cholmod_factorize(impl_->matrix, impl_->factor, &impl_->common);
  return ok && impl_->common.status == CHOLMOD_OK && impl_->factor->minor == impl_->factor->n;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  cholmod_dense b;
  b.nrow = static_cast<size_t>(rhs.size());
  b.ncol = 1;
  b.nzmax = b.nrow;
  b.d = b.nrow;
  b.x = const_cast<double*>(rhs.data());
  b.z = nullptr;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  cholmod_dense* x = cholmod_solve(CHOLMOD_A, impl_->factor, &b, &impl_->common);
  if (!x) throw Error("CHOLMOD solve failed");
  Eigen::VectorXd out = Eigen::Map<const Eigen::VectorXd>(static_cast<double*>(x->x), rhs.size());
  cholmod_free_dense(&x, &impl_->common);
  return out;
}

}  // namespace ashlar
