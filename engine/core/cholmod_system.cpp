#include "core/cholmod_system.hpp"

#include <cholmod.h>

#include <dlfcn.h>
#include <pthread.h>

#include <algorithm>
#include <csignal>
#include <cstddef>
#include <mutex>

#include "core/blas.hpp"
#include "core/error.hpp"
#include "core/sparse_pattern.hpp"

namespace ashlar {

namespace {

// Every call into CHOLMOD that may reach METIS (cholmod_analyze with its
// default methods, cholmod_bisect, cholmod_metis) runs inside one
// MetisCall, one at a time in the whole process, because METIS is not
// thread-safe in two ways:
// - its random number generator (GKlib's Mersenne twister) is one process
//   global, reseeded at every call: two threads ordering at once draw from
//   each other's sequence, so the orderings, and the round-off of every
//   factorisation after them, changed from run to run (a 2-worker FEA study
//   differed in 37-50 of 150 rows between runs). One at a time, each call
//   draws its own seeded sequence: the orderings are those of a serial run;
// - it swaps the process's SIGABRT and SIGTERM handlers for its own (a
//   longjmp back into the call) with SysV signal(), saving the old ones per
//   thread: overlapping calls put back each other's, and even one call puts
//   the host's handler back as a one-shot, SysV-style handler. And a
//   SIGTERM sent to the process while METIS's handler is installed goes to
//   the main thread, or to any thread that does not block it (OpenBLAS's
//   pool, started before main, blocks nothing), which runs METIS's handler:
//   a longjmp to a jump buffer that only the thread inside METIS has, a
//   SIGSEGV elsewhere (7 of 30 SIGTERMs sent to the 10,051-block wall
//   during its orderings ended with exit 139; one was caught by METIS in
//   the ordering thread and lost).
// So in a MetisCall METIS's handler for SIGTERM is never installed (see
// __sysv_signal below): SIGTERM keeps the process's handler throughout,
// whichever thread takes it. The call's own thread blocks SIGTERM, so that
// one sent to it waits for the end of the call instead of running the
// handler inside METIS; on exit the SIGABRT and SIGTERM handlers of its
// start are put back exactly as they were (sigaction), and then SIGTERM is
// unblocked.
thread_local bool t_in_metis_call = false;

class MetisCall {
public:
  MetisCall() {
    sigset_t terminate;
    sigemptyset(&terminate);
    sigaddset(&terminate, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &terminate, &mask_);
    lock_ = std::unique_lock<std::mutex>(mutex());
    for (int k = 0; k < 2; ++k) sigaction(kSignals[k], nullptr, &saved_[k]);
    t_in_metis_call = true;
  }
  ~MetisCall() {
    t_in_metis_call = false;
    for (int k = 0; k < 2; ++k) sigaction(kSignals[k], &saved_[k], nullptr);
    lock_.unlock();
    pthread_sigmask(SIG_SETMASK, &mask_, nullptr);
  }
  MetisCall(const MetisCall&) = delete;
  MetisCall& operator=(const MetisCall&) = delete;

private:
  static std::mutex& mutex() {
    static std::mutex process_wide;
    return process_wide;
  }
  static constexpr int kSignals[2] = {SIGABRT, SIGTERM};
  sigset_t mask_;
  std::unique_lock<std::mutex> lock_;
  struct sigaction saved_[2];
};

}  // namespace

}  // namespace ashlar

// METIS sets its handlers with SysV signal(), which is glibc's
// __sysv_signal (libmetis.so.5 as Debian builds it); defined here, in the
// executable (exported, engine/core/CMakeLists.txt), it comes first for
// libmetis. Inside a MetisCall, SIGTERM's handler is left as it is: METIS's
// signal(SIGTERM, ...) calls change nothing and return the current handler,
// which METIS then "puts back" the same way. Its SIGABRT handler, its way
// out of a failed allocation, is installed as before. METIS raises SIGTERM
// itself only for errors in its input, which CHOLMOD checks first. Every
// other call goes to the next definition (glibc's). In the C module for
// stock lua5.4, loaded RTLD_LOCAL, libmetis finds glibc's first: there the
// calls are still one at a time and the handlers put back.
extern "C" __sighandler_t __sysv_signal(int signal_number, __sighandler_t handler) noexcept {
  using Signal = __sighandler_t (*)(int, __sighandler_t);
  static const Signal next = reinterpret_cast<Signal>(dlsym(RTLD_NEXT, "__sysv_signal"));
  if (signal_number == SIGTERM && ashlar::t_in_metis_call) {
    struct sigaction current {};
    sigaction(SIGTERM, nullptr, &current);
    return current.sa_handler;
  }
  return next(signal_number, handler);
}

namespace ashlar {

namespace {

// Rows from which a system's supernodes are merged as CHOLMOD's defaults
// merge them (see CholmodSystem::Impl): the sides of a 10,000-block
// model's split factorisation (about 30,000 rows) and larger.
constexpr int kDefaultMergeFromRows = 20000;
// The widest supernode of a system from kDefaultMergeFromRows rows: wider
// ones are cut into panels of at most this many columns (see
// CholmodSystem::Impl::cut_into_panels).
constexpr int kPanelColumns = 96;

}  // namespace

struct CholmodSystem::Impl {
  Impl(int n, const int* column_starts, const int* row_indices, Triangle stored, int widest_supernode)
      : rows_(n),
        widest_supernode_(widest_supernode > 0 ? widest_supernode
                          : n >= kDefaultMergeFromRows ? kPanelColumns
                                                       : n) {
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
    // bisection's last verdicts turn on rounding), so below
    // kDefaultMergeFromRows the merge stays the one its reference was
    // computed with. Above, the explicit zeros of the freer merge are memory
    // and flops for nothing: the 100,052-block vault's peak 121 MB less
    // with the default. Merging none at all (zrelax 0: only supernodes of
    // fewer than 4 columns; the default lets 5-80 % of a merged one be
    // zeros) saves 1 % more (its peak 2,315 -> 2,292 MB, factors 141.5 ->
    // 138.1 million values) but costs time in the factorisation's many
    // small BLAS calls: that vault's 24 factorisations 34.0, 33.7 s ->
    // 37.0, 37.4 s, the 10,051-block 3D wall's 11 factorisations 1.16-1.30 s
    // -> 1.33-1.54 s.
    if (n < kDefaultMergeFromRows) {
      common_.nrelax[0] = 16;
      common_.nrelax[1] = 48;
      common_.nrelax[2] = 96;
    }
    const size_t nonzeros = static_cast<size_t>(column_starts[n]);
    // The pattern alone, for the analysis: factorize() takes the values
    // from the caller's array (a large model's normal matrix is 100 MB of
    // values: one copy).
    matrix_ = cholmod_allocate_sparse(n, n, nonzeros, /*sorted=*/1, /*packed=*/1, stype(stored), CHOLMOD_PATTERN,
                                      &common_);
    if (!matrix_) {
      cholmod_finish(&common_);
      throw Error("CHOLMOD could not allocate the normal-equation matrix");
    }
    std::copy(column_starts, column_starts + n + 1, static_cast<int*>(matrix_->p));
    std::copy(row_indices, row_indices + nonzeros, static_cast<int*>(matrix_->i));
  }
  ~Impl() {
    for (cholmod_dense** dense : {&solution_, &workspace_y_, &workspace_e_}) {
      if (*dense) cholmod_free_dense(dense, &common_);
    }
    if (factor_) cholmod_free_factor(&factor_, &common_);
    if (matrix_) cholmod_free_sparse(&matrix_, &common_);
    cholmod_finish(&common_);
  }
  // CHOLMOD's default methods try METIS where AMD's ordering fills much.
  void analyze() {
    {
      const MetisCall metis;
      factor_ = cholmod_analyze(matrix_, &common_);
    }
    check_analysed();
  }
  void analyze_as_ordered() {
    common_.nmethods = 1;
    common_.method[0].ordering = CHOLMOD_NATURAL;
    common_.postorder = 0;
    factor_ = cholmod_analyze(matrix_, &common_);
    check_analysed();
    prepare_numeric();
    cholmod_free_sparse(&matrix_, &common_);
  }
  void check_analysed() const {
    if (!factor_) throw Error("CHOLMOD could not analyse the normal-equation pattern");
  }

  int rows() const { return rows_; }
  const cholmod_factor& factor() const { return *factor_; }
  size_t stored_values() const { return factor_->xsize; }
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
  bool factorize(const Columns& matrix) {
    const cholmod_factor& f = *factor_;
    const int* super = static_cast<const int*>(f.super);
    const int* pi = static_cast<const int*>(f.pi);
    const int* px = static_cast<const int*>(f.px);
    const int* row_of = static_cast<const int*>(f.s);
    double* lx = static_cast<double*>(f.x);
    const int supernodes = static_cast<int>(f.nsuper);
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
        matrix.fill(j, local_row_.data(), block + static_cast<ptrdiff_t>(j - first) * height);
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
        // C's rows among s's, ascending: where the rows from j on are
        // consecutive in s (last minus j-th equals their count less one),
        // column j is one straight run. The indexed loop alone was 6 % of
        // the 100,052-block vault's analysis (perf).
        int* relative = relative_.data();
        for (int i = 0; i < reach; ++i) relative[i] = local_row_[row_of[top + i]];
        for (int j = 0; j < in_columns; ++j) {
          double* column = block + static_cast<ptrdiff_t>(relative[j]) * height;
          const double* c = update_.data() + static_cast<ptrdiff_t>(j) * reach;
          if (relative[reach - 1] - relative[j] == reach - 1 - j) {
            double* run = column + relative[j] - j;
            for (int i = j; i < reach; ++i) run[i] -= c[i];
          } else {
            for (int i = j; i < reach; ++i) column[relative[i]] -= c[i];
          }
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

  // cholmod_solve2 keeps its solution and workspace between calls: a large
  // model's solves then allocate (and page-fault) nothing.
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

  // The symbolic factor made numeric (its values allocated, as CHOLMOD's
  // factorisation leaves it: supernodal L L^T), and what factorize() reuses:
  // each column's supernode, a row map and the update workspace (CHOLMOD's
  // bound on an update's size).
  void prepare_numeric() {
    if (matrix_->stype != stype(Triangle::lower) || !factor_->is_super) {
      throw Error("the normal-equation factorisation needs a lower triangle, analysed supernodal");
    }
    if (factor_->Perm) {
      const int* perm = static_cast<const int*>(factor_->Perm);
      for (size_t k = 0; k < factor_->n; ++k) {
        if (perm[k] != static_cast<int>(k)) throw Error("CHOLMOD reordered a system analysed as ordered");
      }
    }
    cut_into_panels(widest_supernode_);
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
    int tallest = 1;
    for (int s = 0; s < supernodes; ++s) tallest = std::max(tallest, pi[s + 1] - pi[s]);
    relative_.resize(tallest);
  }
  // CHOLMOD stores a supernode of k columns as one dense block, its
  // diagonal block whole: k (k - 1) / 2 values above the diagonal unused.
  // The halves of the 100,052-block vault have supernodes up to 1,200
  // columns wide (its dissection's separators, 100 voussoirs of 6 rows);
  // 15.1 million of their 138.1 million values were those unused ones
  // (121 MB). Cut into panels of at most `widest` columns, each a
  // supernode of its own (a panel's rows: its supernode's from the panel's
  // first column on), they leave 8.2 million with 96 columns: the peak
  // 2,534 -> 2,450 MiB (measured with zrelax 0, above), for factorisations 2-5 %
  // slower (30.6, 30.7 s -> 31.4, 32.3 s in alternating runs; narrower
  // panels cost more: see the commit). Done on the symbolic factor, before
  // its values are allocated; the factorisation (factorize) and CHOLMOD's
  // solves take any supernodal partition.
  void cut_into_panels(int widest) {
    cholmod_factor& f = *factor_;
    const int* super = static_cast<const int*>(f.super);
    const int* pi = static_cast<const int*>(f.pi);
    const int* rows_of = static_cast<const int*>(f.s);
    bool wider = false;
    for (size_t k = 0; k < f.nsuper && !wider; ++k) wider = super[k + 1] - super[k] > widest;
    if (!wider) return;
    std::vector<int> panel_super, panel_pi, panel_px, panel_rows;
    size_t values = 0, below = 0;
    for (size_t k = 0; k < f.nsuper; ++k) {
      const int columns = super[k + 1] - super[k], height = pi[k + 1] - pi[k];
      for (int offset = 0; offset < columns; offset += widest) {
        const int panel_columns = std::min(widest, columns - offset);
        panel_super.push_back(super[k] + offset);
        panel_pi.push_back(static_cast<int>(panel_rows.size()));
        panel_px.push_back(static_cast<int>(values));
        panel_rows.insert(panel_rows.end(), rows_of + pi[k] + offset, rows_of + pi[k + 1]);
        values += static_cast<size_t>(panel_columns) * (height - offset);
        below = std::max<size_t>(below, height - offset - panel_columns);
      }
    }
    panel_super.push_back(super[f.nsuper]);
    panel_pi.push_back(static_cast<int>(panel_rows.size()));
    panel_px.push_back(static_cast<int>(values));
    const auto replace = [this](void*& array, size_t count, const std::vector<int>& with) {
      void* copy = cholmod_malloc(with.size(), sizeof(int), &common_);
      if (!copy) throw Error("CHOLMOD could not allocate the normal-equation factor's panels");
      std::copy(with.begin(), with.end(), static_cast<int*>(copy));
      cholmod_free(count, sizeof(int), array, &common_);
      array = copy;
    };
    replace(f.super, f.nsuper + 1, panel_super);
    replace(f.pi, f.nsuper + 1, panel_pi);
    replace(f.px, f.nsuper + 1, panel_px);
    replace(f.s, f.ssize, panel_rows);
    f.nsuper = panel_super.size() - 1;
    f.ssize = panel_rows.size();
    f.xsize = values;
    f.maxesize = below;  // a panel's rows below its columns: the solves' workspace
    // The largest update (factorize's workspace): a panel's next panels
    // now take its updates, of at most its rows below its columns by the
    // widest panel's columns.
    f.maxcsize = std::max(f.maxcsize, below * std::min<size_t>(widest, below));
  }
  static int stype(Triangle stored) { return stored == Triangle::upper ? 1 : -1; }
  // Puts supernode d on the list of the supernode its next rows update.
  void append(int d, int target) {
    next_[d] = head_[target];
    head_[target] = d;
  }

  const int rows_;
  const int widest_supernode_;
  cholmod_common common_;
  cholmod_sparse* matrix_ = nullptr;
  cholmod_factor* factor_ = nullptr;
  std::vector<int> supernode_of_, local_row_, head_, next_, row_position_;
  std::vector<int> relative_;  // an update's rows in the supernode it updates
  std::vector<double> update_;
  cholmod_dense* solution_ = nullptr;
  cholmod_dense* workspace_y_ = nullptr;
  cholmod_dense* workspace_e_ = nullptr;
};

CholmodSystem::CholmodSystem(int n, const int* column_starts, const int* row_indices, Triangle stored,
                             int widest_supernode)
    : impl_(std::make_unique<Impl>(n, column_starts, row_indices, stored, widest_supernode)) {}

CholmodSystem::~CholmodSystem() = default;

void CholmodSystem::analyze() { impl_->analyze(); }

void CholmodSystem::analyze_as_ordered() { impl_->analyze_as_ordered(); }

const int* CholmodSystem::permutation() const { return static_cast<const int*>(impl_->factor().Perm); }

int CholmodSystem::rows() const { return impl_->rows(); }

double CholmodSystem::factor_nonzeros() const { return impl_->factor_nonzeros(); }

size_t CholmodSystem::stored_values() const { return impl_->stored_values(); }

bool CholmodSystem::factorize(const Columns& columns) { return impl_->factorize(columns); }

const double* CholmodSystem::solve(Solve system, const double* rhs) {
  const int kind = system == Solve::whole ? CHOLMOD_A : system == Solve::forward ? CHOLMOD_L : CHOLMOD_Lt;
  return impl_->solve(kind, rhs);
}

void CholmodSystem::trailing_block_reversed(int first, Eigen::MatrixXd& out) const {
  const cholmod_factor& f = impl_->factor();
  const int* super = static_cast<const int*>(f.super);
  const int* pi = static_cast<const int*>(f.pi);
  const int* px = static_cast<const int*>(f.px);
  const int* row_of = static_cast<const int*>(f.s);
  const double* x = static_cast<const double*>(f.x);
  const int s = rows() - first;
  const int last_row = rows() - 1;
  out.setZero(s, s);
  for (size_t k = 0; k < f.nsuper; ++k) {
    const int first_column = super[k], last = super[k + 1];
    if (last <= first) continue;
    const int height = pi[k + 1] - pi[k];
    for (int j = std::max(first_column, first); j < last; ++j) {
      const double* column = x + px[k] + static_cast<ptrdiff_t>(j - first_column) * height;
      for (int r = j - first_column; r < height; ++r) out(last_row - row_of[pi[k] + r], last_row - j) = column[r];
    }
  }
}

namespace {

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

// The pattern (upper triangle) with each run of `block` rows as one row:
// its graph's node J stands for rows J block .. (J + 1) block - 1.
ColumnPattern compress_blocks(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices,
                              int block) {
  const int blocks = n / block;
  ColumnPattern out;
  out.column_starts.assign(blocks + 1, 0);
  std::vector<int> seen(blocks, -1);
  for (int column = 0; column < blocks; ++column) {
    for (int j = column * block; j < (column + 1) * block; ++j) {
      for (int e = column_starts[j]; e < column_starts[j + 1]; ++e) {
        const int row = row_indices[e] / block;
        if (row <= column && seen[row] != column) {
          seen[row] = column;
          out.row_indices.push_back(row);
        }
      }
    }
    std::sort(out.row_indices.begin() + out.column_starts[column], out.row_indices.end());
    out.column_starts[column + 1] = static_cast<int>(out.row_indices.size());
  }
  return out;
}

}  // namespace

std::vector<int> bisect(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices) {
  std::vector<int> part(n);
  const bool ok = with_cholmod_pattern(n, column_starts.data(), row_indices.data(),
                                       [&](cholmod_sparse* pattern, cholmod_common* common) {
    // compress: rows of one body share their pattern and stay together.
    const MetisCall metis;
    return cholmod_bisect(pattern, nullptr, 0, /*compress=*/1, part.data(), common) >= 0;
  });
  if (!ok) part.clear();
  return part;
}

// Two candidates, and the one CHOLMOD's symbolic analysis finds the fewer
// flops for: minimum degree under that constraint (CAMD), and METIS's nested
// dissection of the leading rows with the last rows appended (the separator
// of a dissection one level up). Neither wins everywhere; flops per half,
// CAMD against METIS: 10,051-block wall 2.1e9 / 1.8e9, 10,027-block vault
// 1.3e9 / 1.4e9, 100,052-block vault 3.5e10 / 3.4e10.
std::vector<int> order_with_last_rows(int n, const std::vector<int>& column_starts,
                                      const std::vector<int>& row_indices, int first_last, int block) {
  if (block > 1 && n % block == 0 && first_last % block == 0) {
    // Ordered as the graph of the runs, each run's rows kept together in
    // their order: a 3D model's graph has a sixth of the rows and a 36th
    // of the entries to order. The sides of the 100,052-block vault's split
    // 1.56 and 2.20 s -> 0.25 and 0.40 s (the second waits for the first's
    // METIS), their factors 61.67 and 61.53 million values against 61.51
    // and 61.53; the 10,051-block walls' and vault's set-up 0.06 s less.
    const ColumnPattern blocks = compress_blocks(n, column_starts, row_indices, block);
    const std::vector<int> block_order = order_with_last_rows(n / block, blocks.column_starts, blocks.row_indices,
                                                              first_last / block, 1);
    if (block_order.empty()) return {};
    std::vector<int> order(n);
    for (size_t k = 0; k < block_order.size(); ++k) {
      for (int r = 0; r < block; ++r) order[k * block + r] = block_order[k] * block + r;
    }
    return order;
  }
  std::vector<int> constrained(n), dissected(n);
  std::vector<int> constraint(n);
  for (int i = 0; i < n; ++i) constraint[i] = i < first_last ? 0 : 1;
  double flops[2] = {-1.0, -1.0};
  auto measure = [](cholmod_sparse* pattern, cholmod_common* common, std::vector<int>& order) {
    common->nmethods = 1;
    common->method[0].ordering = CHOLMOD_GIVEN;
    common->postorder = 0;
    // The flops come from the column counts; the supernodal analysis after
    // them would be half the time for nothing (0.47 -> 0.23 s on a side of
    // the 100,052-block vault).
    common->supernodal = CHOLMOD_SIMPLICIAL;
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
      const MetisCall metis;
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

}  // namespace ashlar
