#include "core/sparse_cholesky.hpp"

#include <cholmod.h>
#include <dlfcn.h>

#include <algorithm>
#include <array>
#include <mutex>
#include <thread>
#include <utility>

#include "core/error.hpp"
#include "core/parallel_loop.hpp"

namespace ashlar {

// BLAS and LAPACK (OpenBLAS's): the dense kernels of the supernodal
// factorisation, and the split's Schur complement: the product of a
// triangular matrix with its transpose, dense Cholesky factorisation and
// solve, all in place.
extern "C" {
void dsyrk_(const char* uplo, const char* trans, const int* n, const int* k, const double* alpha, const double* a,
            const int* lda, const double* beta, double* c, const int* ldc, size_t uplo_length, size_t trans_length);
void dgemm_(const char* transa, const char* transb, const int* m, const int* n, const int* k, const double* alpha,
            const double* a, const int* lda, const double* b, const int* ldb, const double* beta, double* c,
            const int* ldc, size_t transa_length, size_t transb_length);
void dtrsm_(const char* side, const char* uplo, const char* transa, const char* diag, const int* m, const int* n,
            const double* alpha, const double* a, const int* lda, double* b, const int* ldb, size_t side_length,
            size_t uplo_length, size_t transa_length, size_t diag_length);
void dlauum_(const char* uplo, const int* n, double* a, const int* lda, int* info, size_t uplo_length);
void dpotrf_(const char* uplo, const int* n, double* a, const int* lda, int* info, size_t uplo_length);
void dpotrs_(const char* uplo, const int* n, const int* nrhs, const double* a, const int* lda, double* b,
             const int* ldb, int* info, size_t uplo_length);
}

namespace {

// A function of a shared library this process has already loaded (its
// BLAS), or null. Looked up by handle, not in the global scope: in the C
// module for stock lua5.4 it is loaded RTLD_LOCAL.
template <typename Function>
Function* loaded_function(const char* library, const char* name) {
  void* handle = dlopen(library, RTLD_LAZY | RTLD_NOLOAD);
  if (!handle) return nullptr;
  void* symbol = dlsym(handle, name);
  dlclose(handle);  // only drops the reference RTLD_NOLOAD took
  return reinterpret_cast<Function*>(symbol);
}

// One BLAS thread for each factorisation, chosen by measurement on a 2-core
// machine (22 factorisations of a 10,051-block wall's 60,300-row normal
// matrix): one thread, 3.13 s of factorisation and 0.25 s of system time
// for the whole run; OpenBLAS on 2 threads 2.85 s, but its idle thread
// yields the core in a loop between calls (6.2 s of system time). On a
// 100,052-block vault (5.4e10 flops per factorisation) two OpenBLAS threads
// cut the factorisations from 46.6 s to 37.3 s, but the idle one yielded
// for 32 s of system time (40 % of user time), so one thread there too. Two
// cores help where the work itself is split: the solver's loops
// (ParallelLoop) and a large pattern's two halves, factored side by side
// (SparseCholesky's split, 1.7x on that wall's factorisations). Set here so
// that a user never needs OPENBLAS_* variables for speed.
void use_one_blas_thread() {
  using SetInt = void(int);
  static std::once_flag blas_once;
  std::call_once(blas_once, [] {
    for (const char* library : {"libblas.so.3", "libopenblas.so.0"}) {
      if (SetInt* set_threads = loaded_function<SetInt>(library, "openblas_set_num_threads")) {
        set_threads(1);
      }
    }
  });
}

// One CHOLMOD matrix (the upper or the lower triangle) with its analysis
// and factor.
class CholmodSystem {
public:
  enum class Triangle { upper = 1, lower = -1 };  // CHOLMOD's stype

  CholmodSystem(int n, const int* column_starts, const int* row_indices, Triangle stored) {
    cholmod_start(&common_);
    common_.print = 0;  // statuses are read, not printed
    common_.error_handler = nullptr;
    common_.supernodal = CHOLMOD_SUPERNODAL;
    // Supernodes merged more freely than CHOLMOD's default (4, 16, 48
    // columns), chosen when CHOLMOD's own numeric factorisation paid an
    // OpenMP region per supernode: the 16 x 18 dome's 1,734 rows, 174
    // supernodes -> 79, its load capacity 25.6 s -> 23.3 s and important
    // weights 16.9 s -> 15.0 s on one core. With factorize() below the
    // default is 3 % faster there (5 % on the 10,027-block vault, 17 MB
    // less), but it moves the 512-voussoir arch's minimum thickness in
    // tests/regression/arch_minimum_thickness.lua by 0.3 % (that
    // bisection's last verdicts turn on rounding), so the merge stays the
    // one its reference was computed with.
    common_.nrelax[0] = 16;
    common_.nrelax[1] = 48;
    common_.nrelax[2] = 96;
    const size_t nonzeros = static_cast<size_t>(column_starts[n]);
    matrix_ = cholmod_allocate_sparse(n, n, nonzeros, /*sorted=*/1, /*packed=*/1, static_cast<int>(stored),
                                      CHOLMOD_REAL, &common_);
    if (!matrix_) {
      cholmod_finish(&common_);
      throw Error("CHOLMOD could not allocate the normal-equation matrix");
    }
    std::copy(column_starts, column_starts + n + 1, static_cast<int*>(matrix_->p));
    std::copy(row_indices, row_indices + nonzeros, static_cast<int*>(matrix_->i));
    std::fill_n(values(), nonzeros, 0.0);
  }
  ~CholmodSystem() {
    for (cholmod_dense** dense : {&solution_, &workspace_y_, &workspace_e_}) {
      if (*dense) cholmod_free_dense(dense, &common_);
    }
    if (factor_) cholmod_free_factor(&factor_, &common_);
    cholmod_free_sparse(&matrix_, &common_);
    cholmod_finish(&common_);
  }
  CholmodSystem(const CholmodSystem&) = delete;
  CholmodSystem& operator=(const CholmodSystem&) = delete;

  // Fill-reducing ordering of CHOLMOD's choice.
  void analyze() {
    factor_ = cholmod_analyze(matrix_, &common_);
    if (!factor_) throw Error("CHOLMOD could not analyse the normal-equation pattern");
  }
  // The rows' own order (the caller has permuted them), kept as given: no
  // postordering. Only a system analysed so, a lower triangle, can be
  // factorised (factorize()): its columns then go straight into the
  // factor's.
  void analyze_as_ordered() {
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_NATURAL;
    common_.postorder = 0;
    analyze();
    prepare_numeric();
  }

  int rows() const { return static_cast<int>(matrix_->nrow); }
  double* values() { return static_cast<double*>(matrix_->x); }
  const cholmod_factor& factor() const { return *factor_; }
  double factor_nonzeros() const { return common_.lnz; }

  // Numeric factorisation of the lower triangle in factor order (the
  // system analysed with analyze_as_ordered) into CHOLMOD's supernodal
  // factor, which its solves then use; false when the matrix is not
  // positive definite. CHOLMOD's own numeric factorisation
  // (cholmod_super_numeric) does the same left-looking supernodal
  // elimination with the same BLAS calls, but on the small normal matrices
  // of 3D margins (the 16 x 18 dome's 1,734 rows: 0.9 ms and 9.1 Mflop a
  // factorisation) about a third of its time was overhead: an OpenMP region
  // per supernode (a team and a futex system call each, even on one
  // thread), a timer read around every BLAS call, and workspace allocated
  // and freed at every call. Here the workspace is set up once: important
  // weights on that dome 7.2 s -> 6.0 s on 2 cores; the 10,051-block wall's
  // factorisations unchanged (1.33 s against 1.37 s).
  bool factorize() {
    use_one_blas_thread();
    const cholmod_factor& f = *factor_;
    const int* super = static_cast<const int*>(f.super);
    const int* pi = static_cast<const int*>(f.pi);
    const int* px = static_cast<const int*>(f.px);
    const int* row_of = static_cast<const int*>(f.s);
    double* lx = static_cast<double*>(f.x);
    const int supernodes = static_cast<int>(f.nsuper);
    const int* column_starts = static_cast<const int*>(matrix_->p);
    const int* row_indices = static_cast<const int*>(matrix_->i);
    const double* ax = values();
    // Left-looking: supernode s takes its columns of the matrix, then the
    // updates of the supernodes below it whose rows reach its columns (the
    // list head_[s], each descendant's next row at row_position_), then
    // factors itself.
    std::fill(head_.begin(), head_.end(), -1);
    const double one = 1.0, zero = 0.0;
    for (int s = 0; s < supernodes; ++s) {
      const int first = super[s], last = super[s + 1], columns = last - first;
      const int height = pi[s + 1] - pi[s];
      double* block = lx + px[s];
      for (int r = 0; r < height; ++r) local_row_[row_of[pi[s] + r]] = r;
      std::fill(block, lx + px[s + 1], 0.0);
      for (int j = first; j < last; ++j) {
        double* column = block + static_cast<ptrdiff_t>(j - first) * height;
        for (int e = column_starts[j]; e < column_starts[j + 1]; ++e) column[local_row_[row_indices[e]]] = ax[e];
      }
      for (int d = head_[s]; d != -1;) {
        const int next_d = next_[d];
        const int d_height = pi[d + 1] - pi[d], d_columns = super[d + 1] - super[d];
        const int top = pi[d] + row_position_[d];  // d's first row in s's columns
        int below = top;
        while (below < pi[d + 1] && row_of[below] < last) ++below;
        const int in_columns = below - top, reach = pi[d + 1] - top;
        const double* d_top = lx + px[d] + (top - pi[d]);
        // C (reach x in_columns) = L_d(rows top .. end) L_d(rows top ..
        // below)^T: its lower triangle where both are s's columns, all of
        // it below.
        dsyrk_("L", "N", &in_columns, &d_columns, &one, d_top, &d_height, &zero, update_.data(), &reach, 1, 1);
        if (reach > in_columns) {
          const int rest = reach - in_columns;
          dgemm_("N", "T", &rest, &in_columns, &d_columns, &one, d_top + in_columns, &d_height, d_top,
                 &d_height, &zero, update_.data() + in_columns, &reach, 1, 1);
        }
        for (int j = 0; j < in_columns; ++j) {
          double* column = block + static_cast<ptrdiff_t>(local_row_[row_of[top + j]]) * height;
          const double* c = update_.data() + static_cast<ptrdiff_t>(j) * reach;
          for (int i = j; i < reach; ++i) column[local_row_[row_of[top + i]]] -= c[i];
        }
        row_position_[d] = below - pi[d];
        if (below < pi[d + 1]) append(d, supernode_of_[row_of[below]]);
        d = next_d;
      }
      int info = 0;
      dpotrf_("L", &columns, block, &height, &info, 1);
      if (info != 0) {
        factor_->minor = static_cast<size_t>(first + info - 1);
        return false;
      }
      if (height > columns) {
        const int rest = height - columns;
        dtrsm_("R", "L", "T", "N", &rest, &columns, &one, block, &height, block + columns, &height, 1, 1, 1, 1);
        row_position_[s] = columns;
        append(s, supernode_of_[row_of[pi[s] + columns]]);
      }
    }
    factor_->minor = factor_->n;
    return true;
  }

  // Solves `system` (CHOLMOD_A, CHOLMOD_L, CHOLMOD_Lt, ...) for the
  // right-hand side rhs[0 .. rows()); the solution stays valid until the
  // next solve. cholmod_solve2 keeps its solution and workspace between
  // calls: a large model's solves then allocate (and page-fault) nothing.
  const double* solve(int system, const double* rhs) {
    cholmod_dense b;
    b.nrow = static_cast<size_t>(rows());
    b.ncol = 1;
    b.nzmax = b.nrow;
    b.d = b.nrow;
    b.x = const_cast<double*>(rhs);
    b.z = nullptr;
    b.xtype = CHOLMOD_REAL;
    b.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(system, factor_, &b, nullptr, &solution_, nullptr, &workspace_y_, &workspace_e_,
                        &common_)) {
      throw Error("CHOLMOD solve failed");
    }
    return static_cast<const double*>(solution_->x);
  }

private:
  // The symbolic factor made numeric (its values allocated, as CHOLMOD's
  // factorisation leaves it: supernodal L L^T), and what factorize() reuses:
  // each column's supernode, a row map and the update workspace (CHOLMOD's
  // bound on an update's size).
  void prepare_numeric() {
    if (matrix_->stype != static_cast<int>(Triangle::lower) || !factor_->is_super) {
      throw Error("the normal-equation factorisation needs a lower triangle, analysed supernodal");
    }
    if (factor_->Perm) {
      const int* perm = static_cast<const int*>(factor_->Perm);
      for (size_t k = 0; k < factor_->n; ++k) {
        if (perm[k] != static_cast<int>(k)) throw Error("CHOLMOD reordered a system analysed as ordered");
      }
    }
    if (!cholmod_change_factor(CHOLMOD_REAL, /*to_ll=*/1, /*to_super=*/1, /*to_packed=*/1, /*to_monotonic=*/1,
                               factor_, &common_) ||
        !factor_->x) {
      throw Error("CHOLMOD could not allocate the normal-equation factor");
    }
    const cholmod_factor& f = *factor_;
    const int n = static_cast<int>(f.n);
    const int supernodes = static_cast<int>(f.nsuper);
    const int* super = static_cast<const int*>(f.super);
    const int* pi = static_cast<const int*>(f.pi);
    const int* row_of = static_cast<const int*>(f.s);
    supernode_of_.resize(n);
    for (int s = 0; s < supernodes; ++s) {
      std::fill(supernode_of_.begin() + super[s], supernode_of_.begin() + super[s + 1], s);
    }
    // Every entry of the matrix's lower triangle lies in its supernode's rows.
    local_row_.assign(n, -1);
    const int* column_starts = static_cast<const int*>(matrix_->p);
    const int* row_indices = static_cast<const int*>(matrix_->i);
    for (int s = 0; s < supernodes; ++s) {
      const int height = pi[s + 1] - pi[s];
      for (int r = 0; r < height; ++r) local_row_[row_of[pi[s] + r]] = r;
      for (int j = super[s]; j < super[s + 1]; ++j) {
        for (int e = column_starts[j]; e < column_starts[j + 1]; ++e) {
          if (row_indices[e] < j || local_row_[row_indices[e]] < 0) {
            throw Error("CHOLMOD's factor pattern misses a matrix entry");
          }
        }
      }
      for (int r = 0; r < height; ++r) local_row_[row_of[pi[s] + r]] = -1;
    }
    head_.assign(supernodes, -1);
    next_.assign(supernodes, -1);
    row_position_.assign(supernodes, 0);
    update_.resize(std::max<size_t>(f.maxcsize, 1));
  }
  // Puts supernode d on the list of the supernode its next rows update.
  void append(int d, int target) {
    next_[d] = head_[target];
    head_[target] = d;
  }

  cholmod_common common_;
  cholmod_sparse* matrix_ = nullptr;
  cholmod_factor* factor_ = nullptr;
  std::vector<int> supernode_of_, local_row_, head_, next_, row_position_;
  std::vector<double> update_;
  cholmod_dense* solution_ = nullptr;
  cholmod_dense* workspace_y_ = nullptr;
  cholmod_dense* workspace_e_ = nullptr;
};

// Runs use(pattern, common) on the upper-triangle pattern as a CHOLMOD
// pattern-only matrix; returns false if CHOLMOD cannot allocate it or use
// returns false.
template <typename Use>
bool with_cholmod_pattern(int n, const int* column_starts, const int* row_indices, Use&& use) {
  cholmod_common common;
  cholmod_start(&common);
  common.print = 0;
  common.error_handler = nullptr;
  bool ok = false;
  cholmod_sparse* pattern = cholmod_allocate_sparse(n, n, column_starts[n], /*sorted=*/1, /*packed=*/1,
                                                    /*stype=upper*/ 1, CHOLMOD_PATTERN, &common);
  if (pattern) {
    std::copy(column_starts, column_starts + n + 1, static_cast<int*>(pattern->p));
    std::copy(row_indices, row_indices + column_starts[n], static_cast<int*>(pattern->i));
    ok = use(pattern, &common);
    cholmod_free_sparse(&pattern, &common);
  }
  cholmod_finish(&common);
  return ok;
}

// The rows of the pattern's graph that separate it into two parts (METIS
// through CHOLMOD): part[i] is 0 or 1, or 2 for the separator. Empty when
// CHOLMOD cannot bisect.
std::vector<int> bisect(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices) {
  std::vector<int> part(n);
  const bool ok = with_cholmod_pattern(n, column_starts.data(), row_indices.data(),
                                       [&](cholmod_sparse* pattern, cholmod_common* common) {
    // compress: rows of one body share their pattern and stay together.
    return cholmod_bisect(pattern, nullptr, 0, /*compress=*/1, part.data(), common) >= 0;
  });
  if (!ok) part.clear();
  return part;
}

// A fill-reducing order of the pattern's rows (order[k]: the row placed
// k-th) that places the rows from `first_last` on after all others. Two
// candidates, and the one CHOLMOD's symbolic analysis finds the fewer flops
// for: minimum degree under that constraint (CAMD), and METIS's nested
// dissection of the leading rows with the last rows appended (the separator
// of a dissection one level up). Neither wins everywhere; flops per half,
// CAMD against METIS: 10,051-block wall 2.1e9 / 1.8e9, 10,027-block vault
// 1.3e9 / 1.4e9, 100,052-block vault 3.5e10 / 3.4e10. Empty if CHOLMOD
// fails.
std::vector<int> order_with_last_rows(int n, const std::vector<int>& column_starts,
                                      const std::vector<int>& row_indices, int first_last) {
  std::vector<int> constrained(n), dissected(n);
  std::vector<int> constraint(n);
  for (int i = 0; i < n; ++i) constraint[i] = i < first_last ? 0 : 1;
  double flops[2] = {-1.0, -1.0};
  auto measure = [](cholmod_sparse* pattern, cholmod_common* common, std::vector<int>& order) {
    common->nmethods = 1;
    common->method[0].ordering = CHOLMOD_GIVEN;
    common->postorder = 0;
    cholmod_factor* symbolic = cholmod_analyze_p(pattern, order.data(), nullptr, 0, common);
    if (!symbolic) return -1.0;
    cholmod_free_factor(&symbolic, common);
    return common->fl;
  };
  with_cholmod_pattern(n, column_starts.data(), row_indices.data(),
                       [&](cholmod_sparse* pattern, cholmod_common* common) {
    if (cholmod_camd(pattern, nullptr, 0, constraint.data(), constrained.data(), common)) {
      flops[0] = measure(pattern, common, constrained);
    }
    const bool leading = with_cholmod_pattern(first_last, column_starts.data(), row_indices.data(),
                                              [&](cholmod_sparse* lead, cholmod_common* lead_common) {
      return cholmod_metis(lead, nullptr, 0, /*postorder=*/1, dissected.data(), lead_common) != 0;
    });
    if (leading) {
      for (int k = first_last; k < n; ++k) dissected[k] = k;
      flops[1] = measure(pattern, common, dissected);
    }
    return true;
  });
  if (flops[0] < 0 && flops[1] < 0) return {};
  std::vector<int>& order = flops[1] >= 0 && (flops[0] < 0 || flops[1] < flops[0]) ? dissected : constrained;
  for (int k = first_last; k < n; ++k) {
    if (order[k] < first_last) return {};
  }
  return order;
}

// A pattern in compressed columns (rows ascending in each column) with,
// for each entry, the index of the value it takes in another pattern.
struct SourcedPattern {
  std::vector<int> column_starts, row_indices, sources;
};

// Entry {column, row, source} triples into compressed columns: bucketed by
// column, then each column sorted by row.
SourcedPattern compress_columns(int n, const std::vector<std::array<int, 3>>& entries) {
  SourcedPattern out;
  out.column_starts.assign(n + 1, 0);
  for (const auto& entry : entries) ++out.column_starts[entry[0] + 1];
  for (int j = 0; j < n; ++j) out.column_starts[j + 1] += out.column_starts[j];
  std::vector<std::pair<int, int>> placed(entries.size());  // (row, source)
  std::vector<int> next(out.column_starts.begin(), out.column_starts.end() - 1);
  for (const auto& [column, row, source] : entries) placed[next[column]++] = {row, source};
  out.row_indices.resize(entries.size());
  out.sources.resize(entries.size());
  for (int j = 0; j < n; ++j) {
    std::sort(placed.begin() + out.column_starts[j], placed.begin() + out.column_starts[j + 1]);
  }
  for (size_t k = 0; k < placed.size(); ++k) {
    out.row_indices[k] = placed[k].first;
    out.sources[k] = placed[k].second;
  }
  return out;
}

}  // namespace

// One side of the split: the rows of part A (or B) followed by the
// separator's, factored with the separator last.
struct SplitSide {
  std::unique_ptr<CholmodSystem> system;
  int own = 0;                      // rows of this part; separator rows follow
  std::vector<int> own_rows;        // the whole matrix's row of each own row
  std::vector<int> sources;         // the whole matrix's value behind each of system's values
  std::vector<int> order;           // local row (own rows, then separator) at factor row k
  std::vector<int> separator_slot;  // separator position of the factor's trailing row own + k
  // L_SS reversed, U = J L_SS J (J: the reversal), which is upper
  // triangular: LAPACK forms U U^T (a third of a general product's flops)
  // and L_SS L_SS^T = J U U^T J.
  Eigen::MatrixXd reversed_trailing;
  Eigen::MatrixXd product;               // U U^T (upper triangle)
  // Solve buffers, kept between solves at their sizes: rows of this side
  // (factor order), and separator rows.
  Eigen::VectorXd permuted, back, separator_work;
  Eigen::VectorXd separator_part;        // this side's M_SA M_AA^-1 b_A, separator order

  int separator_rows() const { return static_cast<int>(separator_slot.size()); }

  // Copies this side's values, factors, and forms its Schur share T.
  bool factorize(const double* whole_values) {
    double* values = system->values();
    for (size_t k = 0; k < sources.size(); ++k) values[k] = whole_values[sources[k]];
    if (!system->factorize()) return false;
    extract_trailing_block();
    product = reversed_trailing;
    const int s = separator_rows();
    int info = 0;
    if (s > 0) dlauum_("U", &s, product.data(), &s, &info, 1);
    return info == 0;
  }

  // Adds this side's T = L_SS L_SS^T to the lower triangle of `schur`
  // (separator order).
  void add_schur_share(Eigen::MatrixXd& schur) const {
    const int s = separator_rows();
    for (int b = 0; b < s; ++b) {
      const int column_slot = separator_slot[s - 1 - b];
      for (int a = 0; a <= b; ++a) {
        const int row_slot = separator_slot[s - 1 - a];
        schur(std::max(row_slot, column_slot), std::min(row_slot, column_slot)) += product(a, b);
      }
    }
  }

  // L_SS from the supernodal factor, stored reversed.
  void extract_trailing_block() {
    const cholmod_factor& f = system->factor();
    const int* super = static_cast<const int*>(f.super);
    const int* pi = static_cast<const int*>(f.pi);
    const int* px = static_cast<const int*>(f.px);
    const int* row_of = static_cast<const int*>(f.s);
    const double* x = static_cast<const double*>(f.x);
    const int s = separator_rows();
    const int last_row = own + s - 1;
    reversed_trailing.setZero(s, s);
    for (size_t k = 0; k < f.nsuper; ++k) {
      const int first = super[k], last = super[k + 1];
      if (last <= own) continue;
      const int height = pi[k + 1] - pi[k];
      for (int j = std::max(first, own); j < last; ++j) {
        const double* column = x + px[k] + static_cast<ptrdiff_t>(j - first) * height;
        for (int r = j - first; r < height; ++r) {
          reversed_trailing(last_row - row_of[pi[k] + r], last_row - j) = column[r];
        }
      }
    }
  }

  // Forward solve of this side with b_S = 0: y = L^-1 P b; its separator
  // rows give M_SA M_AA^-1 b_A = L_SA y_A = -L_SS y_S.
  void forward(const Eigen::VectorXd& rhs) {
    const int n = system->rows(), s = separator_rows();
    permuted.resize(n);
    for (int k = 0; k < n; ++k) permuted[k] = order[k] < own ? rhs[own_rows[order[k]]] : 0.0;
    const double* y = system->solve(CHOLMOD_L, permuted.data());
    std::copy(y, y + n, permuted.data());
    // L_SS y_S = J U J y_S.
    separator_work.noalias() = reversed_trailing.triangularView<Eigen::Upper>() * permuted.tail(s).reverse();
    separator_part.resize(s);
    for (int k = 0; k < s; ++k) separator_part[separator_slot[k]] = -separator_work[s - 1 - k];
  }

  // Back solve given the separator's solution: L^T u = [y_A; L_SS^T x_S]
  // gives u_A = x_A, written into the whole solution.
  void backward(const Eigen::VectorXd& separator_solution, Eigen::VectorXd& out) {
    const int n = system->rows(), s = separator_rows();
    back.resize(n);
    back.head(own) = permuted.head(own);
    // L_SS^T x_S = J U^T J x_S, with x_S taken into factor order.
    separator_work.resize(s);
    for (int k = 0; k < s; ++k) separator_work[s - 1 - k] = separator_solution[separator_slot[k]];
    back.tail(s).reverse() = reversed_trailing.triangularView<Eigen::Upper>().transpose() * separator_work;
    const double* u = system->solve(CHOLMOD_Lt, back.data());
    for (int k = 0; k < own; ++k) out[own_rows[order[k]]] = u[k];
  }
};

struct SparseCholesky::Impl {
  // When not split: the lower triangle in CHOLMOD's own fill-reducing
  // order (the form factorize() takes), its values copied from the
  // caller's through whole_sources.
  std::unique_ptr<CholmodSystem> whole;
  std::vector<int> whole_sources;  // the caller's value behind each of whole's values
  std::vector<int> whole_order;    // the caller's row at factor row k
  Eigen::VectorXd permuted;        // solve buffer, factor order
  // The caller's values (pattern order), whole or split. When split: the
  // two sides, the separator's rows (ascending: the separator order) and
  // its own entries.
  std::vector<double> values;
  SplitSide sides[2];
  std::vector<int> separator;
  struct SeparatorEntry {
    int value, row, column;  // value index; separator positions, row >= column
  };
  std::vector<SeparatorEntry> separator_entries;
  Eigen::MatrixXd schur;  // the Schur complement on S, then its Cholesky factor (lower)
  Eigen::VectorXd separator_rhs;
  ParallelLoop loop{2};
  int nonzeros = 0;

  bool split(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices,
             const SparseCholeskyOptions& options);
  void analyse_whole(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices);
};

void SparseCholesky::Impl::analyse_whole(int n, const std::vector<int>& column_starts,
                                         const std::vector<int>& row_indices) {
  CholmodSystem upper(n, column_starts.data(), row_indices.data(), CholmodSystem::Triangle::upper);
  upper.analyze();
  const int* perm = static_cast<const int*>(upper.factor().Perm);
  whole_order.assign(perm, perm + n);  // postordered with it
  std::vector<int> position(n);
  for (int k = 0; k < n; ++k) position[whole_order[k]] = k;
  std::vector<std::array<int, 3>> entries;  // {column, row, value index}, lower triangle in factor order
  entries.reserve(row_indices.size());
  for (int j = 0; j < n; ++j) {
    for (int e = column_starts[j]; e < column_starts[j + 1]; ++e) {
      const int a = position[row_indices[e]], b = position[j];
      entries.push_back({std::min(a, b), std::max(a, b), e});
    }
  }
  const SourcedPattern lower = compress_columns(n, entries);
  whole_sources = lower.sources;
  whole = std::make_unique<CholmodSystem>(n, lower.column_starts.data(), lower.row_indices.data(),
                                          CholmodSystem::Triangle::lower);
  whole->analyze_as_ordered();
  values.assign(row_indices.size(), 0.0);
}

bool SparseCholesky::Impl::split(int n, const std::vector<int>& column_starts,
                                 const std::vector<int>& row_indices, const SparseCholeskyOptions& options) {
  const std::vector<int> part = bisect(n, column_starts, row_indices);
  if (part.empty()) return false;
  // Local numbering per side: own rows first, then the separator's.
  std::vector<int> local(n);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) local[i] = counts[part[i]]++;
  const int s = counts[2];
  if (s == 0 || s > options.max_separator_rows || std::min(counts[0], counts[1]) < n / 8) return false;
  separator.reserve(s);
  for (int i = 0; i < n; ++i) {
    if (part[i] == 2) separator.push_back(i);
  }
  // Each side's entries in its local numbering, upper triangle:
  // {column, row, value index in the whole pattern}.
  std::vector<std::array<int, 3>> entries[2];
  for (int p = 0; p < 2; ++p) {
    SplitSide& side = sides[p];
    side.own = counts[p];
    side.own_rows.reserve(side.own);
    for (int i = 0; i < n; ++i) {
      if (part[i] == p) side.own_rows.push_back(i);
    }
  }
  auto local_index = [&](int i, int p) { return part[i] == 2 ? sides[p].own + local[i] : local[i]; };
  for (int j = 0; j < n; ++j) {
    for (int e = column_starts[j]; e < column_starts[j + 1]; ++e) {
      const int i = row_indices[e];
      if (part[i] != 2 && part[j] != 2 && part[i] != part[j]) return false;  // not a separator
      for (int p = 0; p < 2; ++p) {
        if ((part[i] == 2 || part[i] == p) && (part[j] == 2 || part[j] == p)) {
          const int a = local_index(i, p), b = local_index(j, p);
          entries[p].push_back({std::max(a, b), std::min(a, b), e});
        }
      }
      if (part[i] == 2 && part[j] == 2) {
        separator_entries.push_back({e, std::max(local[i], local[j]), std::min(local[i], local[j])});
      }
    }
  }
  // The two sides' orderings and analyses, each on its own core.
  bool ordered[2] = {false, false};
  loop.run_parts(2, [&](int p) {
    SplitSide& side = sides[p];
    const int rows = side.own + s;
    const SourcedPattern upper = compress_columns(rows, entries[p]);
    side.order = order_with_last_rows(rows, upper.column_starts, upper.row_indices, side.own);
    if (side.order.empty()) return;
    std::vector<int> position(rows);
    for (int k = 0; k < rows; ++k) position[side.order[k]] = k;
    // The side's lower triangle in factor order, which CHOLMOD factors in
    // place.
    for (auto& [column, row, source] : entries[p]) {
      const int a = position[row], b = position[column];
      column = std::min(a, b);
      row = std::max(a, b);
    }
    const SourcedPattern lower = compress_columns(rows, entries[p]);
    std::vector<std::array<int, 3>>().swap(entries[p]);
    side.sources = lower.sources;
    side.system = std::make_unique<CholmodSystem>(rows, lower.column_starts.data(), lower.row_indices.data(),
                                                  CholmodSystem::Triangle::lower);
    side.system->analyze_as_ordered();
    side.separator_slot.resize(s);
    for (int k = 0; k < s; ++k) side.separator_slot[k] = side.order[side.own + k] - side.own;
    ordered[p] = true;
  });
  if (!ordered[0] || !ordered[1]) return false;
  values.assign(row_indices.size(), 0.0);
  return true;
}

SparseCholesky::SparseCholesky(int n, std::vector<int> column_starts, std::vector<int> row_indices,
                               const SparseCholeskyOptions& options)
    : impl_(std::make_unique<Impl>()) {
  impl_->nonzeros = static_cast<int>(row_indices.size());
  const bool two_cores = std::thread::hardware_concurrency() >= 2;
  const bool split = n >= options.split_from_rows && (two_cores || options.split_from_rows == 0) &&
                     impl_->split(n, column_starts, row_indices, options);
  if (!split) {
    impl_->separator.clear();
    impl_->analyse_whole(n, column_starts, row_indices);
  }
}

SparseCholesky::~SparseCholesky() = default;

double* SparseCholesky::values() { return impl_->values.data(); }

int SparseCholesky::nonzeros() const { return impl_->nonzeros; }

int SparseCholesky::separator_rows() const { return static_cast<int>(impl_->separator.size()); }

double SparseCholesky::factor_nonzeros() const {
  if (impl_->whole) return impl_->whole->factor_nonzeros();
  const double s = static_cast<double>(impl_->separator.size());
  // The two sides' factors hold their separator block too; the dense
  // Schur factor replaces them.
  return impl_->sides[0].system->factor_nonzeros() + impl_->sides[1].system->factor_nonzeros() -
         s * (s + 1) / 2;
}

bool SparseCholesky::factorize() {
  ++factorizations_;
  Impl& m = *impl_;
  if (m.whole) {
    double* values = m.whole->values();
    for (size_t k = 0; k < m.whole_sources.size(); ++k) values[k] = m.values[m.whole_sources[k]];
    return m.whole->factorize();
  }
  bool factored[2] = {false, false};
  m.loop.run_parts(2, [&](int p) { factored[p] = m.sides[p].factorize(m.values.data()); });
  if (!factored[0] || !factored[1]) return false;
  // Schur complement of M onto S: T_A + T_B - M_SS (lower triangle).
  const int s = static_cast<int>(m.separator.size());
  m.schur.setZero(s, s);
  for (const SplitSide& side : m.sides) side.add_schur_share(m.schur);
  for (const Impl::SeparatorEntry& entry : m.separator_entries) {
    m.schur(entry.row, entry.column) -= m.values[entry.value];
  }
  int info = 0;
  dpotrf_("L", &s, m.schur.data(), &s, &info, 1);
  return info == 0 && m.schur.diagonal().allFinite();
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  Eigen::VectorXd out;
  solve(rhs, out);
  return out;
}

void SparseCholesky::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) const {
  Impl& m = *impl_;
  if (m.whole) {
    const int n = static_cast<int>(rhs.size());
    m.permuted.resize(n);
    for (int k = 0; k < n; ++k) m.permuted[k] = rhs[m.whole_order[k]];
    const double* x = m.whole->solve(CHOLMOD_A, m.permuted.data());
    out.resize(n);
    for (int k = 0; k < n; ++k) out[m.whole_order[k]] = x[k];
    return;
  }
  out.resize(rhs.size());
  m.loop.run_parts(2, [&](int p) { m.sides[p].forward(rhs); });
  const int s = static_cast<int>(m.separator.size());
  m.separator_rhs.resize(s);
  for (int k = 0; k < s; ++k) m.separator_rhs[k] = rhs[m.separator[k]];
  m.separator_rhs -= m.sides[0].separator_part + m.sides[1].separator_part;
  const int one = 1;
  int info = 0;
  dpotrs_("L", &s, &one, m.schur.data(), &s, m.separator_rhs.data(), &s, &info, 1);
  m.loop.run_parts(2, [&](int p) { m.sides[p].backward(m.separator_rhs, out); });
  for (int k = 0; k < s; ++k) out[m.separator[k]] = m.separator_rhs[k];
}

}  // namespace ashlar
