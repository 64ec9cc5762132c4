#include "analysis/sparse_cholesky.hpp"

#include <cholmod.h>
#include <dlfcn.h>

#include <algorithm>
#include <mutex>

#include "core/error.hpp"

namespace ashlar {

namespace {

// A function of a shared library this process has already loaded (CHOLMOD's
// OpenMP runtime and BLAS), or null. Looked up by handle, not in the global
// scope: in the C module for stock lua5.4 they are loaded RTLD_LOCAL.
template <typename Function>
Function* loaded_function(const char* library, const char* name) {
  void* handle = dlopen(library, RTLD_LAZY | RTLD_NOLOAD);
  if (!handle) return nullptr;
  void* symbol = dlsym(handle, name);
  dlclose(handle);  // only drops the reference RTLD_NOLOAD took
  return reinterpret_cast<Function*>(symbol);
}

// One thread for the factorisation and its BLAS, chosen by measurement on a
// 2-core machine (22 factorisations of a 10,051-block wall's 60,300-row
// normal matrix): one thread each, 3.13 s of factorisation and 0.25 s of
// system time for the whole run; CHOLMOD's OpenMP loops on 2 threads 3.39 s
// (Debian builds them with num_threads(4): on 2 cores, 10-17 s and as much
// system time as user time); OpenBLAS on 2 threads 2.85 s, but its idle
// thread yields the core in a loop between calls (6.2 s of system time).
// On a 100,052-block vault (5.4e10 flops per factorisation) two OpenBLAS
// threads cut the factorisations from 46.6 s to 37.3 s, but the idle one
// yielded for 32 s of system time (40 % of user time), so one thread there
// too. The solver's own loops are where two cores help (ParallelLoop). Set
// on every calling thread (max-active-levels is a per-thread OpenMP
// setting), so that a user never needs OMP_* or OPENBLAS_* variables for
// speed.
void use_one_thread_in_factorisations() {
  using SetInt = void(int);
  static SetInt* const set_max_active_levels =
      loaded_function<SetInt>("libgomp.so.1", "omp_set_max_active_levels");
  static std::once_flag blas_once;
  std::call_once(blas_once, [] {
    for (const char* library : {"libblas.so.3", "libopenblas.so.0"}) {
      if (SetInt* set_threads = loaded_function<SetInt>(library, "openblas_set_num_threads")) {
        set_threads(1);
      }
    }
  });
  // Max-active-levels 0: every parallel region runs on the calling thread alone.
  if (set_max_active_levels) set_max_active_levels(0);
}

}  // namespace

struct SparseCholesky::Impl {
  cholmod_common common;
  cholmod_sparse* matrix = nullptr;
  cholmod_factor* factor = nullptr;
  cholmod_dense* solution = nullptr;  // cholmod_solve2's, kept between solves
  cholmod_dense* workspace_y = nullptr;
  cholmod_dense* workspace_e = nullptr;

  Impl() {
    cholmod_start(&common);
    common.print = 0;  // statuses are read, not printed
    common.error_handler = nullptr;
  }
  ~Impl() {
    for (cholmod_dense** dense : {&solution, &workspace_y, &workspace_e}) {
      if (*dense) cholmod_free_dense(dense, &common);
    }
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
  use_one_thread_in_factorisations();
  const int ok = cholmod_factorize(impl_->matrix, impl_->factor, &impl_->common);
  return ok && impl_->common.status == CHOLMOD_OK && impl_->factor->minor == impl_->factor->n;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd out;
  solve(rhs, out);
  return out;
}

void SparseCholesky::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) const {
  cholmod_dense b;
  b.nrow = static_cast<size_t>(rhs.size());
  b.ncol = 1;
  b.nzmax = b.nrow;
  b.d = b.nrow;
  b.x = const_cast<double*>(rhs.data());
  b.z = nullptr;
  b.xtype = CHOLMOD_REAL;
  b.dtype = CHOLMOD_DOUBLE;
  // cholmod_solve2 keeps its solution and workspace between calls: a large
  // model's solves then allocate (and page-fault) nothing.
  if (!cholmod_solve2(CHOLMOD_A, impl_->factor, &b, nullptr, &impl_->solution, nullptr,
                      &impl_->workspace_y, &impl_->workspace_e, &impl_->common)) {
    throw Error("CHOLMOD solve failed");
  }
  out = Eigen::Map<const Eigen::VectorXd>(static_cast<double*>(impl_->solution->x), rhs.size());
}

}  // namespace ashlar
