// SparseCholesky: the factorisation split over two cores around a
// separator solves the same systems as a dense Cholesky factorisation (the
// independent reference), on block patterns like the solver's; patterns
// that cannot be split are factored whole; a matrix that is not positive
// definite is reported, split or not. BlockPattern finds every entry of a
// block pattern's columns. CholmodSystem: supernodes cut into narrower
// panels solve as Eigen's sparse Cholesky factorisation does, and store
// fewer values.
#include <gtest/gtest.h>

#include <pthread.h>

#include <unistd.h>

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "core/cholmod_system.hpp"
#include "core/error.hpp"
#include "core/sparse_cholesky.hpp"
#include "core/sparse_pattern.hpp"

using ashlar::SparseCholesky;
using ashlar::SparseCholeskyOptions;

namespace {

// A symmetric positive definite matrix with the pattern of bodies on a
// rows x columns grid, each coupled to its 8 neighbours by dense d x d
// blocks (as a running-bond wall's normal matrix), plus its dense copy.
struct GridMatrix {
  int n = 0;
  std::vector<int> column_starts, row_indices;
  std::vector<double> values;
  Eigen::MatrixXd dense;
};

// The couplings of bodies on a rows x columns grid, each to its 8
// neighbours, by dense d x d blocks: per coupling a random term C C^T
// (positive semidefinite, entries of mixed signs) over the two bodies'
// rows, each entry given to add(row, column, value).
template <typename Add>
void add_grid_couplings(int rows, int columns, int d, unsigned seed, Add&& add) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < columns; ++c) {
      const int a = r * columns + c;
      for (int dr = 0; dr <= 1; ++dr) {
        for (int dc = -1; dc <= 1; ++dc) {
          if ((dr == 0 && dc <= 0) || r + dr >= rows || c + dc < 0 || c + dc >= columns) continue;
          const int b = (r + dr) * columns + c + dc;
          Eigen::MatrixXd coupling(2 * d, 3);
          for (int i = 0; i < coupling.size(); ++i) coupling.data()[i] = uniform(random);
          const Eigen::MatrixXd term = coupling * coupling.transpose();
          for (int i = 0; i < 2 * d; ++i) {
            for (int j = 0; j < 2 * d; ++j) add((i < d ? a : b) * d + i % d, (j < d ? a : b) * d + j % d, term(i, j));
          }
        }
      }
    }
  }
}

// The couplings plus a diagonal: positive definite.
GridMatrix grid_matrix(int rows, int columns, int d, unsigned seed) {
  GridMatrix m;
  m.n = rows * columns * d;
  m.dense = Eigen::MatrixXd::Zero(m.n, m.n);
  add_grid_couplings(rows, columns, d, seed, [&](int i, int j, double value) { m.dense(i, j) += value; });
  m.dense.diagonal().array() += 0.1;
  m.column_starts.push_back(0);
  for (int j = 0; j < m.n; ++j) {
    for (int i = 0; i <= j; ++i) {
      // The pattern holds every coupled block, zero or not.
      const int a = i / d, b = j / d;
      const int ra = a / columns, ca = a % columns, rb = b / columns, cb = b % columns;
      if (std::abs(ra - rb) <= 1 && std::abs(ca - cb) <= 1) {
        m.row_indices.push_back(i);
        m.values.push_back(m.dense(i, j));
      }
    }
    m.column_starts.push_back(static_cast<int>(m.row_indices.size()));
  }
  return m;
}

Eigen::VectorXd random_vector(int n, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = uniform(random);
  return v;
}

// The lower triangle of a grid matrix's pattern with its values (sparse,
// for sizes whose dense copy would not fit), rows in the grid's order: a
// banded factor, whose supernodes are as wide as the band.
struct LowerGrid {
  int n = 0;
  std::vector<int> column_starts, row_indices;
  std::vector<double> values;
  Eigen::SparseMatrix<double> matrix;  // the whole symmetric matrix
};

LowerGrid lower_grid(int rows, int columns, int d, unsigned seed) {
  LowerGrid m;
  m.n = rows * columns * d;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < m.n; ++i) entries.emplace_back(i, i, 0.1);
  add_grid_couplings(rows, columns, d, seed, [&](int i, int j, double value) { entries.emplace_back(i, j, value); });
  m.matrix.resize(m.n, m.n);
  m.matrix.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> lower = m.matrix.triangularView<Eigen::Lower>();
  m.column_starts.assign(lower.outerIndexPtr(), lower.outerIndexPtr() + m.n + 1);
  m.row_indices.assign(lower.innerIndexPtr(), lower.innerIndexPtr() + lower.nonZeros());
  m.values.assign(lower.valuePtr(), lower.valuePtr() + lower.nonZeros());
  return m;
}

// A lower grid's columns as CholmodSystem::factorize takes them.
class LowerColumns final : public ashlar::CholmodSystem::Columns {
public:
  explicit LowerColumns(const LowerGrid& m) : m_(m) {}
  void fill(int j, const int* slot, double* column) const override {
    for (int e = m_.column_starts[j]; e < m_.column_starts[j + 1]; ++e) column[slot[m_.row_indices[e]]] = m_.values[e];
  }

private:
  const LowerGrid& m_;
};

// A lower-triangle system analysed in its own order, `widest` as
// CholmodSystem takes it.
std::unique_ptr<ashlar::CholmodSystem> analysed(const LowerGrid& m, int widest) {
  auto system = std::make_unique<ashlar::CholmodSystem>(m.n, m.column_starts.data(), m.row_indices.data(),
                                                        ashlar::CholmodSystem::Triangle::lower, widest);
  system->analyze_as_ordered();
  return system;
}

SparseCholeskyOptions always_split(int block_rows = 1) {
  SparseCholeskyOptions options;
  options.split_from_rows = 0;
  options.block_rows = block_rows;
  return options;
}

}  // namespace

class SplitFactorisation : public testing::TestWithParam<int> {};

// The pattern read entry by entry (1) and by its 6 x 6 blocks.
INSTANTIATE_TEST_SUITE_P(BlockRows, SplitFactorisation, testing::Values(1, 6));

TEST_P(SplitFactorisation, SolvesLikeDenseCholesky) {
  const GridMatrix m = grid_matrix(12, 20, 6, 1);
  SparseCholesky split(m.n, m.column_starts, m.row_indices, always_split(GetParam()));
  // A 12 x 20 grid is cut across its shorter side: 12 bodies (72 rows)
  // separate it, give or take METIS's choice.
  EXPECT_GT(split.separator_rows(), 0);
  EXPECT_LE(split.separator_rows(), 3 * 12 * 6);
  std::copy(m.values.begin(), m.values.end(), split.values());
  ASSERT_TRUE(split.factorize());
  const Eigen::LLT<Eigen::MatrixXd> reference(m.dense);
  for (unsigned seed : {2u, 3u}) {
    const Eigen::VectorXd rhs = random_vector(m.n, seed);
    const Eigen::VectorXd expected = reference.solve(rhs);
    const Eigen::VectorXd x = split.solve(rhs);
    EXPECT_LE((x - expected).norm(), 1e-10 * expected.norm());
    EXPECT_LE((m.dense * x - rhs).norm(), 1e-12 * m.dense.norm() * x.norm());
  }
  // New values on the same pattern refactor with the same analysis.
  std::vector<double> doubled = m.values;
  for (double& v : doubled) v *= 2;
  std::copy(doubled.begin(), doubled.end(), split.values());
  ASSERT_TRUE(split.factorize());
  const Eigen::VectorXd rhs = random_vector(m.n, 4);
  EXPECT_LE((split.solve(rhs) - 0.5 * reference.solve(rhs)).norm(), 1e-10 * reference.solve(rhs).norm());
  EXPECT_EQ(split.factorizations(), 2);
}

TEST(SparseCholesky, SplitAndWholeFactorsHoldAboutAsManyNonzeros) {
  const GridMatrix m = grid_matrix(30, 30, 3, 5);
  SparseCholesky split(m.n, m.column_starts, m.row_indices, always_split(3));
  SparseCholeskyOptions never = always_split(3);
  never.split_from_rows = m.n + 1;
  SparseCholesky whole(m.n, m.column_starts, m.row_indices, never);
  ASSERT_GT(split.separator_rows(), 0);
  EXPECT_EQ(whole.separator_rows(), 0);
  // Both are nested-dissection-quality orderings of a planar grid.
  EXPECT_LT(split.factor_nonzeros(), 1.5 * whole.factor_nonzeros());
  EXPECT_GT(split.factor_nonzeros(), 0.5 * whole.factor_nonzeros());
  std::copy(m.values.begin(), m.values.end(), split.values());
  std::copy(m.values.begin(), m.values.end(), whole.values());
  ASSERT_TRUE(split.factorize());
  ASSERT_TRUE(whole.factorize());
  const Eigen::VectorXd rhs = random_vector(m.n, 6);
  const Eigen::VectorXd expected = Eigen::LLT<Eigen::MatrixXd>(m.dense).solve(rhs);
  EXPECT_LE((whole.solve(rhs) - expected).norm(), 1e-10 * expected.norm());
  EXPECT_LE((split.solve(rhs) - expected).norm(), 1e-10 * expected.norm());
}

TEST(BlockPattern, VisitsEveryEntryOfEachColumnOnceWithItsValue) {
  // 4 x 5 bodies of 6 rows, read by blocks of 6, of 3 (a body's halves:
  // its blocks are whole blocks of 3 too) and entry by entry.
  const GridMatrix m = grid_matrix(4, 5, 6, 12);
  for (int d : {6, 3, 1}) {
    const ashlar::BlockPattern pattern(m.n, m.column_starts, m.row_indices, d);
    Eigen::MatrixXd found = Eigen::MatrixXd::Zero(m.n, m.n);
    Eigen::MatrixXi visits = Eigen::MatrixXi::Zero(m.n, m.n);
    for (int j = 0; j < m.n; ++j) {
      pattern.for_each_block_in_column(j, [&](int body, auto value) {
        for (int r = 0; r < d; ++r) {
          found(d * body + r, j) = m.values[value(r)];
          ++visits(d * body + r, j);
        }
      });
    }
    EXPECT_EQ((found - m.dense).cwiseAbs().maxCoeff(), 0.0) << "blocks of " << d;
    EXPECT_EQ(visits.maxCoeff(), 1) << "blocks of " << d;
    // Every entry of the pattern, both triangles: 20 bodies' diagonal
    // blocks, and 2 x 6 x 6 entries per coupled pair (4 x 4 along the
    // rows, 3 x 5 across them, 2 x 3 x 4 diagonally).
    EXPECT_EQ(visits.sum(), 20 * 36 + (16 + 15 + 24) * 72) << "blocks of " << d;
  }
}

TEST(BlockPattern, APatternNotMadeOfWholeBlocksIsRefused) {
  const GridMatrix m = grid_matrix(4, 5, 6, 13);
  // Blocks of 4 rows straddle the bodies' 6.
  EXPECT_THROW(ashlar::BlockPattern(m.n, m.column_starts, m.row_indices, 4), ashlar::Error);
  // 7 does not divide 120 rows.
  EXPECT_THROW(ashlar::BlockPattern(m.n, m.column_starts, m.row_indices, 7), ashlar::Error);
  // One entry above the diagonal missing in the last column.
  std::vector<int> starts = m.column_starts, rows = m.row_indices;
  rows.erase(rows.begin() + starts[m.n - 1]);
  --starts[m.n];
  try {
    ashlar::BlockPattern(m.n, starts, rows, 6);
    ADD_FAILURE() << "accepted";
  } catch (const ashlar::Error& error) {
    EXPECT_STREQ(error.what(), "the pattern's columns 114 to 119 are not made of whole blocks of 6 rows");
  }
  EXPECT_NO_THROW(ashlar::BlockPattern(m.n, starts, rows, 1));
}

TEST(SparseCholesky, APatternWithoutASeparatorIsFactoredWhole) {
  // One dense 12 x 12 block: nothing separates it.
  const GridMatrix m = grid_matrix(1, 2, 6, 7);
  SparseCholesky cholesky(m.n, m.column_starts, m.row_indices, always_split());
  EXPECT_EQ(cholesky.separator_rows(), 0);
  std::copy(m.values.begin(), m.values.end(), cholesky.values());
  ASSERT_TRUE(cholesky.factorize());
  const Eigen::VectorXd rhs = random_vector(m.n, 8);
  EXPECT_LE((m.dense * cholesky.solve(rhs) - rhs).norm(), 1e-12 * m.dense.norm() * rhs.norm());
}

TEST(SparseCholesky, AMatrixThatIsNotPositiveDefiniteIsReportedWhenSplit) {
  GridMatrix m = grid_matrix(12, 20, 6, 9);
  SparseCholesky split(m.n, m.column_starts, m.row_indices, always_split());
  ASSERT_GT(split.separator_rows(), 0);
  // A negative diagonal entry in the first, middle or last row (which part
  // or the separator holds each is METIS's choice).
  for (int row : {0, m.n - 1, m.n / 2}) {
    std::vector<double> values = m.values;
    values[m.column_starts[row + 1] - 1] = -1.0;  // the column's last entry is its diagonal
    std::copy(values.begin(), values.end(), split.values());
    EXPECT_FALSE(split.factorize()) << "row " << row;
  }
}

TEST(SparseCholesky, SplitOrderingLeavesTheProcessSignalHandlersAsTheyWere) {
  // METIS swaps SIGABRT's and SIGTERM's handlers while it orders; two sides
  // ordered at once used to leave its own (a longjmp to a stale buffer)
  // behind for the whole process. The handlers of the test's start, here
  // the defaults, must be the ones after.
  for (int signal_number : {SIGABRT, SIGTERM}) {
    struct sigaction before {};
    sigaction(signal_number, nullptr, &before);
    ASSERT_EQ(before.sa_handler, SIG_DFL);
  }
  for (unsigned seed = 1; seed <= 4; ++seed) {
    const GridMatrix m = grid_matrix(12, 20, 6, seed);
    SparseCholesky split(m.n, m.column_starts, m.row_indices, always_split());
    EXPECT_GT(split.separator_rows(), 0);
  }
  for (int signal_number : {SIGABRT, SIGTERM}) {
    struct sigaction after {};
    sigaction(signal_number, nullptr, &after);
    EXPECT_EQ(after.sa_handler, SIG_DFL) << "signal " << signal_number;
  }
}

namespace {

TEST(CholmodSystem, SupernodesCutIntoPanelsSolveAsEigensSparseCholesky) {
  // 20 x 30 bodies of 6 rows in the grid's order: a band of about 190
  // rows, so supernodes about as wide, cut into panels of 16 columns.
  const LowerGrid m = lower_grid(20, 30, 6, 7);
  const auto panels = analysed(m, 16);
  const auto whole = analysed(m, m.n);
  EXPECT_EQ(panels->factor_nonzeros(), whole->factor_nonzeros());
  // The diagonal blocks' unused upper triangles: at most 16 x 15 / 2 per
  // panel, against about 190 x 189 / 2 per supernode.
  EXPECT_LT(panels->stored_values(), 0.97 * whole->stored_values());
  ASSERT_TRUE(panels->factorize(LowerColumns(m)));
  ASSERT_TRUE(whole->factorize(LowerColumns(m)));
  // The reference: Eigen's simplicial factorisation in the same order (L
  // of a positive definite matrix is unique).
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower, Eigen::NaturalOrdering<int>> reference(
      m.matrix);
  ASSERT_EQ(reference.info(), Eigen::Success);
  using Solve = ashlar::CholmodSystem::Solve;
  for (unsigned seed : {8u, 9u}) {
    const Eigen::VectorXd rhs = random_vector(m.n, seed);
    const Eigen::VectorXd expected = reference.solve(rhs);
    const Eigen::VectorXd forward = reference.matrixL().solve(rhs);
    const Eigen::VectorXd backward = reference.matrixU().solve(rhs);
    for (ashlar::CholmodSystem* system : {panels.get(), whole.get()}) {
      const Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(system->solve(Solve::whole, rhs.data()), m.n);
      EXPECT_LE((x - expected).norm(), 1e-10 * expected.norm());
      EXPECT_LE((m.matrix * x - rhs).norm(), 1e-12 * m.matrix.norm() * x.norm());
      const Eigen::VectorXd l = Eigen::Map<const Eigen::VectorXd>(system->solve(Solve::forward, rhs.data()), m.n);
      EXPECT_LE((l - forward).norm(), 1e-10 * forward.norm());
      const Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(system->solve(Solve::backward, rhs.data()), m.n);
      EXPECT_LE((u - backward).norm(), 1e-10 * backward.norm());
    }
  }
}

TEST(CholmodSystem, SystemsFromTwentyThousandRowsAreCutIntoPanelsOf96Columns) {
  // 60 x 60 bodies of 6 rows (21,600): supernodes up to about 370 columns wide.
  const LowerGrid large = lower_grid(60, 60, 6, 10);
  const auto by_default = analysed(large, 0);
  EXPECT_EQ(by_default->stored_values(), analysed(large, 96)->stored_values());
  EXPECT_LT(by_default->stored_values(), analysed(large, large.n)->stored_values());
  // Below 20,000 rows none is cut: 55 x 60 bodies, 19,800 rows.
  const LowerGrid smaller = lower_grid(55, 60, 6, 11);
  EXPECT_EQ(analysed(smaller, 0)->stored_values(), analysed(smaller, smaller.n)->stored_values());
}

// The METIS orderings of a 30 x 30 grid: its bisection and the order that
// puts the last 90 rows last.
struct Orderings {
  std::vector<int> part, order;
  bool operator==(const Orderings& other) const { return part == other.part && order == other.order; }
};

Orderings metis_orderings(const GridMatrix& m) {
  return {ashlar::bisect(m.n, m.column_starts, m.row_indices),
          ashlar::order_with_last_rows(m.n, m.column_starts, m.row_indices, m.n - 90, 1)};
}

// The nonzeros of m's factor with its rows in `order` (order[k]: the row
// placed k-th), by CHOLMOD's symbolic analysis.
double factor_nonzeros_in(const GridMatrix& m, const std::vector<int>& order) {
  const Eigen::Map<const Eigen::SparseMatrix<double>> upper(m.n, m.n, static_cast<int>(m.values.size()),
                                                            m.column_starts.data(), m.row_indices.data(),
                                                            m.values.data());
  Eigen::PermutationMatrix<Eigen::Dynamic> placed(m.n);
  for (int k = 0; k < m.n; ++k) placed.indices()[order[k]] = k;
  Eigen::SparseMatrix<double> permuted;
  permuted = upper.selfadjointView<Eigen::Upper>().twistedBy(placed);
  const Eigen::SparseMatrix<double> lower = permuted.triangularView<Eigen::Lower>();
  ashlar::CholmodSystem system(m.n, lower.outerIndexPtr(), lower.innerIndexPtr(),
                               ashlar::CholmodSystem::Triangle::lower);
  system.analyze_as_ordered();
  return system.factor_nonzeros();
}

void on_test_signal(int) {}

std::atomic<int> g_sigterms_taken{0};
void count_sigterm(int) { ++g_sigterms_taken; }

}  // namespace

TEST(MetisOrderings, RowsInRunsOfABodyAreOrderedAsOneAndKeptTogether) {
  const GridMatrix m = grid_matrix(30, 30, 3, 11);  // 900 bodies of 3 rows
  const int first_last = m.n - 90;
  const std::vector<int> by_bodies = ashlar::order_with_last_rows(m.n, m.column_starts, m.row_indices, first_last, 3);
  const std::vector<int> by_rows = ashlar::order_with_last_rows(m.n, m.column_starts, m.row_indices, first_last, 1);
  ASSERT_EQ(static_cast<int>(by_bodies.size()), m.n);
  std::vector<int> placed(m.n, 0);
  for (int k = 0; k < m.n; ++k) {
    ++placed[by_bodies[k]];
    EXPECT_EQ(k >= first_last, by_bodies[k] >= first_last) << "row " << by_bodies[k] << " placed " << k;
    if (k % 3 == 0) EXPECT_EQ(by_bodies[k] % 3, 0);
    else EXPECT_EQ(by_bodies[k], by_bodies[k - 1] + 1);
  }
  EXPECT_EQ(std::count(placed.begin(), placed.end(), 1), m.n);
  // As good an ordering as the rows' own (measured: the same 163,296 nonzeros).
  const double bodies_fill = factor_nonzeros_in(m, by_bodies), rows_fill = factor_nonzeros_in(m, by_rows);
  EXPECT_LE(bodies_fill, 1.03 * rows_fill);
  EXPECT_GT(bodies_fill, 0.0);
  // Rows that are not runs of 7 (2,700 = 385 x 7 + 5) are ordered one by one.
  EXPECT_EQ(ashlar::order_with_last_rows(m.n, m.column_starts, m.row_indices, first_last, 7), by_rows);
}

TEST(MetisOrderings, FromTwoThreadsAtOnceAreThoseOfASerialRun) {
  // METIS's random number generator is one for the process, reseeded at
  // every call: calls at once drew from each other's sequence. They run
  // one at a time, so each thread gets the serial orderings.
  const GridMatrix m = grid_matrix(30, 30, 3, 11);
  const Orderings serial = metis_orderings(m);
  ASSERT_EQ(static_cast<int>(serial.part.size()), m.n);
  ASSERT_EQ(static_cast<int>(serial.order.size()), m.n);
  int differing = 0;
  for (int round = 0; round < 8; ++round) {
    Orderings other;
    std::thread second([&] { other = metis_orderings(m); });
    const Orderings own = metis_orderings(m);
    second.join();
    differing += (own == serial ? 0 : 1) + (other == serial ? 0 : 1);
  }
  EXPECT_EQ(differing, 0);
}

TEST(MetisOrderings, LeaveTheSigtermHandlerOfTheirStartExactlyAsItWas) {
  // METIS installs its own SIGABRT and SIGTERM handlers with SysV signal()
  // and, at its end, puts the old ones back the same way: as one-shot
  // handlers (SA_RESETHAND) with no mask. The host's handler, its flags and
  // its mask must come through orderings on this thread and on two at once,
  // and SIGTERM must not stay blocked in the ordering threads.
  struct sigaction host {};
  host.sa_handler = on_test_signal;
  sigemptyset(&host.sa_mask);
  sigaddset(&host.sa_mask, SIGUSR2);
  host.sa_flags = SA_RESTART;
  struct sigaction saved {};
  ASSERT_EQ(sigaction(SIGTERM, &host, &saved), 0);
  const GridMatrix m = grid_matrix(30, 30, 3, 12);
  auto sigterm_blocked = [] {
    sigset_t mask;
    pthread_sigmask(SIG_SETMASK, nullptr, &mask);
    return sigismember(&mask, SIGTERM) == 1;
  };
  bool blocked_after[2] = {true, true};
  metis_orderings(m);
  std::thread second([&] {
    metis_orderings(m);
    blocked_after[1] = sigterm_blocked();
  });
  metis_orderings(m);
  blocked_after[0] = sigterm_blocked();
  second.join();
  struct sigaction after {};
  sigaction(SIGTERM, nullptr, &after);
  sigaction(SIGTERM, &saved, nullptr);
  EXPECT_EQ(after.sa_handler, on_test_signal);
  EXPECT_EQ(after.sa_flags & (SA_RESTART | SA_RESETHAND | SA_NODEFER), SA_RESTART);
  EXPECT_EQ(sigismember(&after.sa_mask, SIGUSR2), 1);
  EXPECT_FALSE(blocked_after[0]);
  EXPECT_FALSE(blocked_after[1]);
  struct sigaction abort_after {};
  sigaction(SIGABRT, nullptr, &abort_after);
  EXPECT_EQ(abort_after.sa_handler, SIG_DFL);
}

TEST(MetisOrderings, ASigtermSentToTheProcessDuringThemReachesTheProcessHandler) {
  // SIGTERMs sent to the process while another thread orders: this thread
  // takes them (it blocks nothing), with the handler of the process, never
  // METIS's (a longjmp to a jump buffer only the ordering thread has: a
  // SIGSEGV here).
  struct sigaction counting {};
  counting.sa_handler = count_sigterm;
  sigemptyset(&counting.sa_mask);
  counting.sa_flags = SA_RESTART;
  struct sigaction saved {};
  ASSERT_EQ(sigaction(SIGTERM, &counting, &saved), 0);
  g_sigterms_taken = 0;
  const GridMatrix m = grid_matrix(30, 30, 3, 13);
  std::atomic<bool> ordering{true};
  std::thread orderer([&] {
    for (int k = 0; k < 10; ++k) metis_orderings(m);
    ordering = false;
  });
  int sent = 0;
  while (ordering) {
    kill(getpid(), SIGTERM);
    ++sent;
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  orderer.join();
  sigaction(SIGTERM, &saved, nullptr);
  EXPECT_GT(sent, 0);
  EXPECT_GT(g_sigterms_taken.load(), 0);
}
