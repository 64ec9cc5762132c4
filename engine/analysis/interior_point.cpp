#include "analysis/interior_point.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/sparse_cholesky.hpp"
#include "core/clock.hpp"
#include "core/interrupt.hpp"
#include "core/parallel_loop.hpp"

namespace ashlar {

namespace {

using PhiFactor = EquilibriumSolver::PhiFactor;
using Vector4 = Eigen::Vector4d;
using RowsMatrix = Eigen::Matrix<double, Eigen::Dynamic, 4>;
// Inequality rows of one group at most: compression, tension and a
// friction pyramid of up to 1024 sides.
constexpr int kMaxGroupRows = 2 + 1024;
// One value per inequality row of a group, on the stack: the per-group
// passes run millions of times and must not allocate.
using GroupRowsVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxGroupRows, 1>;

// Iterations without a more accurate iterate, once one is within the
// inaccurate tolerance, after which the solve stops; and at any accuracy,
// after which more iterations are not going to help.
constexpr int kStallIterations = 8;
constexpr int kHopelessIterations = 20;
// The least slack or multiplier of the starting point, in scaled units (a
// mean block weight). Measured: N & W's 1 takes 25 iterations on a
// 10,027-block vault, 0.1 takes 22 (the robustness sweep 2 % fewer); 3
// takes 36.
constexpr double kStartFloor = 0.1;

// Largest step in (0, 1] keeping v + step * dv >= 0; NaN if dv is not
// finite (a direction that must not be taken).
double step_to_boundary(const Eigen::VectorXd& v, const Eigen::VectorXd& dv) {
  double step = 1.0;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (dv(i) < 0.0) step = std::min(step, -v(i) / dv(i));
    else if (!(dv(i) >= 0.0)) return std::numeric_limits<double>::quiet_NaN();
  }
  return step;
}

// Phi = diag(hessian) + G^T diag(scaling) G, a group's 4 x 4 block of the
// Newton system after eliminating its slacks, as R^T R with R upper
// triangular. Forming Phi itself would not do: near the optimum scaling
// spreads from 1e-13 to 1e13, and adding 1e13 g g^T rounds away the
// regularisation (1e-6) in the directions that stay free, which are the
// very directions Phi^-1 is about. Instead each row scaling_i g_i g_i^T is
// added to Phi = L D L^T (L unit lower triangular, D = diag(hessian) at
// first) as a positive rank-one update (Gill, Golub, Murray & Saunders
// 1974, method C1): what a large row adds is absorbed into its pivot and
// L's column, and only what remains, of the free directions' size, reaches
// the later pivots, as with Givens rotations of R, which this replaced:
// one division per nonzero instead of a square root and a division (the
// group factorisations were 13 % of an important-weights run). Then
// R = D^(1/2) L^T, its diagonal stored inverted: the solves below multiply
// by it.
PhiFactor factor_phi(const Vector4& hessian, const RowsMatrix& rows,
                     const Eigen::Ref<const Eigen::VectorXd>& scaling) {
  Vector4 d = hessian;
  double lower[4][4] = {};  // L below the diagonal, lower[l][j] for l > j
  for (Eigen::Index i = 0; i < rows.rows(); ++i) {
    Vector4 v = rows.row(i).transpose();
    // alpha: the weight of what is left of the row. It is spent (0) once a
    // pivot with no Hessian takes it all; a NaN scaling goes on into the
    // factor, where the solver's checks stop the solve.
    double alpha = scaling(i);
    for (int j = 0; j < 4 && alpha != 0.0; ++j) {
      const double p = v(j);
      if (p == 0.0) continue;
      const double pivot = d(j) + alpha * p * p;
      const double inverse = 1.0 / pivot;  // one division, not two
      const double beta = alpha * p * inverse;
      alpha *= d(j) * inverse;
      d(j) = pivot;
      for (int l = j + 1; l < 4; ++l) {
        v(l) -= p * lower[l][j];
        lower[l][j] += beta * v(l);
      }
    }
  }
  PhiFactor r{};
  for (int j = 0; j < 4; ++j) {
    const double root = std::sqrt(d(j));
    r(j, j) = 1.0 / root;
    for (int l = j + 1; l < 4; ++l) r(j, l) = root * lower[l][j];
  }
  return r;
}

// Phi^-1 v for Phi = R^T R (R from factor_phi): two triangular solves,
// never Phi^-1 itself (whose product with v would round the stiff
// directions' tiny components to the size of the free ones). Inlined into
// the per-group passes, where a chain of dependent steps of one group
// overlaps the next group's work: important weights on one core 10.75 s
// -> 10.2 s.
[[gnu::always_inline]] inline Vector4 solve_phi(const PhiFactor& r, Vector4 v) {
  v(0) *= r(0, 0);  // R^T t = v
  v(1) = (v(1) - r(0, 1) * v(0)) * r(1, 1);
  v(2) = (v(2) - r(0, 2) * v(0) - r(1, 2) * v(1)) * r(2, 2);
  v(3) = (v(3) - r(0, 3) * v(0) - r(1, 3) * v(1) - r(2, 3) * v(2)) * r(3, 3);
  v(3) *= r(3, 3);  // R u = t
  v(2) = (v(2) - r(2, 3) * v(3)) * r(2, 2);
  v(1) = (v(1) - r(1, 2) * v(2) - r(1, 3) * v(3)) * r(1, 1);
  v(0) = (v(0) - r(0, 1) * v(1) - r(0, 2) * v(2) - r(0, 3) * v(3)) * r(0, 0);
  return v;
}

// Four vectors shaped like the unknowns: x (4 per group), y (one per balance
// row), w and z (one per inequality row). As a direction: (dx, dy, dw, dz).
// As the right-hand side or the residual of the Newton system, in the same
// shape:
//   H dx - A^T dy - G^T dz = -x,   A dx = -y,   G dx - dw = -w,   Z dw + W dz = -z
// (x: the dual residual, y: the balance rows', w: the slacks', z: the
// complementarity). One shape for both lets a solve overwrite its
// right-hand side with its direction.
struct NewtonVectors {
  Eigen::VectorXd x, y, w, z;
};

// A R^-1 for a D x 4 matrix A: A Phi^-1 A^T = (A R^-1)(A R^-1)^T.
template <int D>
Eigen::Matrix<double, D, 4> divide_by_factor(const Eigen::Matrix<double, D, 4>& a, const PhiFactor& r) {
  Eigen::Matrix<double, D, 4> out = a;
  for (int j = 0; j < 4; ++j) {
    for (int l = 0; l < j; ++l) out.col(j) -= r(l, j) * out.col(l);
    out.col(j) *= r(j, j);
  }
  return out;
}

}  // namespace

const char* status_name(SolverStatus status) {
  return kSolverStatusNames.name(status);
}

EquilibriumSolver::EquilibriumSolver(const EquilibriumProblem& problem, SolverCores cores)
    : loop_(cores == SolverCores::one ? 1 : 0), size_(problem.row_count), block_rows_(problem.block_rows) {
  const int d = block_rows_;
  const int blocks = problem.row_count / d;
  // Upper-triangle block pattern: for block column J, the block rows I <= J.
  std::vector<std::vector<int>>& upper = block_pattern_;
  upper.assign(blocks, {});
  for (int j = 0; j < blocks; ++j) upper[j].push_back(j);
  for (const ForceGroup& v : problem.groups) {
    if (v.row_a >= 0 && v.row_b >= 0) {
      const int a = v.row_a / d, b = v.row_b / d;
      upper[std::max(a, b)].push_back(std::min(a, b));
    }
  }
  for (std::vector<int>& rows : upper) {
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
  column_starts_.assign(problem.row_count + 1, 0);
  std::vector<int> row_indices;
  for (int j = 0; j < blocks; ++j) {
    for (int cj = 0; cj < d; ++cj) {
      for (int i : upper[j]) {
        const int last = i == j ? cj : d - 1;  // diagonal block: upper part only
        for (int ri = 0; ri <= last; ++ri) row_indices.push_back(d * i + ri);
      }
      column_starts_[d * j + cj + 1] = static_cast<int>(row_indices.size());
    }
  }
  find_slots(problem, pattern_slots_);
  if (problem.row_count > 0) {
    SparseCholeskyOptions factorisation;
    if (cores == SolverCores::one) factorisation.split_from_rows = std::numeric_limits<int>::max();
    cholesky_ = std::make_unique<SparseCholesky>(problem.row_count, column_starts_, row_indices, factorisation);
  }
  partition_columns(blocks);
}

namespace {

// Whether contact vertices p and q are twins (interior_point.hpp): the same
// rules, bodies and bound, and the same effect on the D balance rows to
// rounding. Effects are scaled, O(1) per unit force.
bool are_twins(const ForceGroup& p, const ForceGroup& q, int d) {
  constexpr double kSameEffect = 1e-13;
  auto same = [&](const Eigen::Matrix<double, 6, 4>& e, const Eigen::Matrix<double, 6, 4>& f) {
    return (e.topRows(d) - f.topRows(d)).lpNorm<Eigen::Infinity>() <=
           kSameEffect * (1.0 + e.topRows(d).lpNorm<Eigen::Infinity>());
  };
  return p.kind == GroupKind::contact_vertex && q.kind == GroupKind::contact_vertex &&
         p.row_a == q.row_a && p.row_b == q.row_b && p.bound == q.bound &&
         (p.row_a < 0 || same(p.on_a, q.on_a)) && (p.row_b < 0 || same(p.on_b, q.on_b));
}

}  // namespace

void EquilibriumSolver::find_twins(const EquilibriumProblem& problem, bool merge) {
  // Twins come from one interface (its vertices are consecutive groups); a
  // vertex is compared with the classes begun among the kTwinWindow groups
  // before it, so that a polygon of many vertices costs O(vertices).
  constexpr int kTwinWindow = 16;
  const int n = merge ? static_cast<int>(problem.groups.size()) : 0;
  Twins twins;
  twins.merged_of.resize(n);
  int run_start = 0;
  for (int k = 0; k < n; ++k) {
    const ForceGroup& group = problem.groups[k];
    if (k == 0 || group.source != problem.groups[k - 1].source ||
        group.kind != problem.groups[k - 1].kind) {
      run_start = k;
    }
    int twin = -1;
    for (int j = std::max(run_start, k - kTwinWindow); j < k && twin < 0; ++j) {
      const int merged = twins.merged_of[j];
      if (twins.first_member[merged] == j && are_twins(problem.groups[j], group, block_rows_)) twin = merged;
    }
    if (twin >= 0) {
      twins.merged_of[k] = twin;
      twins.count[twin] += 1.0;
    } else {
      twins.merged_of[k] = static_cast<int>(twins.first_member.size());
      twins.first_member.push_back(k);
      twins.count.push_back(1.0);
    }
  }
  if (static_cast<int>(twins.first_member.size()) == n) twins = Twins{};
  if (twins.merged_of == twins_.merged_of) return;
  twins_ = std::move(twins);
  merged_slots_.clear();
  if (!twins_.merged_of.empty()) {
    merged_slots_.resize(twins_.first_member.size());
    for (size_t j = 0; j < merged_slots_.size(); ++j) merged_slots_[j] = pattern_slots_[twins_.first_member[j]];
  }
  merged_slots_.shrink_to_fit();
  partition_columns(size_ / block_rows_);
}

EquilibriumProblem EquilibriumSolver::merge_twins(const EquilibriumProblem& problem) const {
  EquilibriumProblem merged = problem;
  // In place: a class's first member is never before its own index.
  const int classes = static_cast<int>(twins_.first_member.size());
  merged.contact_vertex_count = 0;
  for (int j = 0; j < classes; ++j) {
    ForceGroup& group = merged.groups[j];
    group = merged.groups[twins_.first_member[j]];
    group.on_a *= twins_.count[j];
    group.on_b *= twins_.count[j];
    if (group.kind == GroupKind::contact_vertex) ++merged.contact_vertex_count;
  }
  merged.groups.resize(classes);
  merged.groups.shrink_to_fit();
  return merged;
}

std::vector<int> EquilibriumSolver::merged_first_rows(const std::vector<int>& full_first_row) const {
  std::vector<int> starts(twins_.first_member.size() + 1, 0);
  for (size_t j = 0; j < twins_.first_member.size(); ++j) {
    const int k = twins_.first_member[j];
    starts[j + 1] = starts[j] + full_first_row[k + 1] - full_first_row[k];
  }
  return starts;
}

void EquilibriumSolver::merge_solution(const InteriorPointSolution& full, const std::vector<int>& full_first_row,
                                       InteriorPointSolution& merged) const {
  const int classes = static_cast<int>(twins_.first_member.size());
  merged.x.resize(4 * classes);
  merged.y = full.y;
  const std::vector<int> starts = merged_first_rows(full_first_row);
  merged.w.resize(starts.back());
  merged.z.resize(starts.back());
  for (int j = 0; j < classes; ++j) {
    const int k = twins_.first_member[j];
    const int rows = starts[j + 1] - starts[j];
    merged.x.segment<4>(4 * j) = full.x.segment<4>(4 * k);
    merged.w.segment(starts[j], rows) = full.w.segment(full_first_row[k], rows);
    merged.z.segment(starts[j], rows) = twins_.count[j] * full.z.segment(full_first_row[k], rows);
  }
}

void EquilibriumSolver::split_solution(const InteriorPointSolution& merged, const std::vector<int>& full_first_row,
                                       InteriorPointSolution& full) const {
  const int n = static_cast<int>(twins_.merged_of.size());
  const int classes = static_cast<int>(twins_.first_member.size());
  if (merged.x.size() != 4 * classes) {  // no iterate (the solve stopped before its first)
    full = InteriorPointSolution{};
    return;
  }
  const std::vector<int> merged_first_row = merged_first_rows(full_first_row);
  full.x.resize(4 * n);
  full.y = merged.y;
  full.w.resize(full_first_row[n]);
  full.z.resize(full_first_row[n]);
  for (int k = 0; k < n; ++k) {
    const int j = twins_.merged_of[k];
    const int rows = full_first_row[k + 1] - full_first_row[k];
    full.x.segment<4>(4 * k) = merged.x.segment<4>(4 * j);
    full.w.segment(full_first_row[k], rows) = merged.w.segment(merged_first_row[j], rows);
    full.z.segment(full_first_row[k], rows) = merged.z.segment(merged_first_row[j], rows) / twins_.count[j];
  }
}

void EquilibriumSolver::partition_columns(int blocks) {
  const std::vector<VertexSlots>& slots = worked_slots();
  const int nv = static_cast<int>(slots.size());
  const int parts = std::min(loop_.parts_for(nv), std::max(blocks, 1));
  const int d = block_rows_;
  // The blocks each group adds: C_a C_a^T in column a, C_b C_b^T in column
  // b, C_a C_b^T in column max(a, b).
  std::vector<long long> adds(blocks + 1, 0);
  for (const VertexSlots& slot : slots) {
    if (slot.row_a >= 0) ++adds[slot.row_a / d];
    if (slot.row_b >= 0) ++adds[slot.row_b / d];
    if (slot.ab >= 0) ++adds[std::max(slot.row_a, slot.row_b) / d];
  }
  long long total = 0;
  for (long long& a : adds) total += std::exchange(a, total);  // now: adds before column j
  part_first_column_.assign(parts + 1, blocks);
  part_first_column_[0] = 0;
  for (int p = 1, j = 0; p < parts; ++p) {
    while (j < blocks && adds[j] * parts < total * p) ++j;
    part_first_column_[p] = j;
  }
  part_groups_.assign(parts, {});
  if (parts == 1) return;  // the one part takes every group in order
  auto part_of = [&](int column) {
    return static_cast<int>(std::upper_bound(part_first_column_.begin(), part_first_column_.end(),
                                             column) -
                            part_first_column_.begin()) -
           1;
  };
  for (int k = 0; k < nv; ++k) {
    const VertexSlots& slot = slots[k];
    int touched[3] = {-1, -1, -1};
    if (slot.row_a >= 0) touched[0] = part_of(slot.row_a / d);
    if (slot.row_b >= 0) touched[1] = part_of(slot.row_b / d);
    if (slot.ab >= 0) touched[2] = part_of(std::max(slot.row_a, slot.row_b) / d);
    std::sort(std::begin(touched), std::end(touched));
    for (int i = 0; i < 3; ++i) {
      if (touched[i] >= 0 && (i == 0 || touched[i] != touched[i - 1])) part_groups_[touched[i]].push_back(k);
    }
  }
}

EquilibriumSolver::~EquilibriumSolver() = default;

bool EquilibriumSolver::find_slots(const EquilibriumProblem& problem, std::vector<VertexSlots>& slots) const {
  const int d = block_rows_;
  // Block (i, j), i <= j: its rank among column j's block rows, -1 if absent.
  auto rank = [&](int i, int j) {
    const std::vector<int>& rows = block_pattern_[j];
    const auto at = std::lower_bound(rows.begin(), rows.end(), i);
    return at != rows.end() && *at == i ? static_cast<int>(at - rows.begin()) : -1;
  };
  slots.assign(problem.groups.size(), VertexSlots{});
  for (size_t k = 0; k < problem.groups.size(); ++k) {
    const ForceGroup& v = problem.groups[k];
    VertexSlots& slot = slots[k];
    slot.row_a = v.row_a;
    slot.row_b = v.row_b;
    if (v.row_a >= 0) slot.aa = rank(v.row_a / d, v.row_a / d);
    if (v.row_b >= 0) slot.bb = rank(v.row_b / d, v.row_b / d);
    if (v.row_a >= 0 && v.row_b >= 0) {
      const int a = v.row_a / d, b = v.row_b / d;
      slot.ab_transposed = a > b;
      slot.ab = rank(std::min(a, b), std::max(a, b));
      if (slot.ab < 0) return false;
    }
  }
  return true;
}

bool EquilibriumSolver::refit(const EquilibriumProblem& problem) {
  if (fits(problem)) return true;
  if (problem.row_count != size_ || problem.block_rows != block_rows_) return false;
  std::vector<VertexSlots> slots;
  if (!find_slots(problem, slots)) return false;
  pattern_slots_ = std::move(slots);
  // The twin classes and the assembly's parts are of the old groups.
  twins_ = Twins{};
  merged_slots_.clear();
  response_ready_ = false;
  partition_columns(size_ / block_rows_);
  return true;
}

bool EquilibriumSolver::fits(const EquilibriumProblem& problem) const {
  if (problem.row_count != size_ || problem.block_rows != block_rows_ ||
      problem.groups.size() != pattern_slots_.size()) {
    return false;
  }
  for (size_t k = 0; k < pattern_slots_.size(); ++k) {
    if (problem.groups[k].row_a != pattern_slots_[k].row_a || problem.groups[k].row_b != pattern_slots_[k].row_b) {
      return false;
    }
  }
  return true;
}

template <int D>
void EquilibriumSolver::assemble_normal_matrix(const EquilibriumProblem& problem,
                                               const std::vector<int>& first_row,
                                               const Eigen::VectorXd& w, const Eigen::VectorXd& z,
                                               std::vector<PhiFactor>& phi_factors) {
  using BlockByVertexD = Eigen::Matrix<double, D, 4>;
  const int nv = static_cast<int>(problem.groups.size());
  phi_factors.resize(nv);
  // Slacks of active rows may be (near) zero; keep z / w finite.
  constexpr double kLeastSlack = std::numeric_limits<double>::min();
  loop_.run(nv, [&](int begin, int end, int) {
    GroupRowsVector scaling;
    for (int k = begin; k < end; ++k) {
      const GroupRules& rules = problem.rules_of(problem.groups[k]);
      const int rows = static_cast<int>(rules.rows.rows());
      scaling = z.segment(first_row[k], rows).cwiseQuotient(
          w.segment(first_row[k], rows).cwiseMax(kLeastSlack));
      phi_factors[k] = factor_phi(twin_count(k) * rules.hessian, rules.rows, scaling);
    }
  });
  // Each part adds only into its own range of block columns (so no entry
  // has two writers), taking the groups that add there.
  double* values = cholesky_->values();
  const int parts = static_cast<int>(part_groups_.size());
  loop_.run_parts(parts, [&](int part) {
    const int first = part_first_column_[part], last = part_first_column_[part + 1];
    std::fill(values + column_starts_[D * first], values + column_starts_[D * last], 0.0);
    auto owned = [&](int column) { return column >= first && column < last; };
    // Adds left right^T (D x D) to block column col_block at its rank-th
    // block row; on the diagonal only its upper triangle, the one stored.
    auto add_product = [&](int col_block, int rank, const BlockByVertexD& left, const BlockByVertexD& right,
                           bool diagonal) {
      for (int cj = 0; cj < D; ++cj) {
        double* column = values + column_starts_[D * col_block + cj] + D * rank;
        const int rows = diagonal ? cj + 1 : D;
        for (int ri = 0; ri < rows; ++ri) column[ri] += left.row(ri).dot(right.row(cj));
      }
    };
    const std::vector<VertexSlots>& slots = worked_slots();
    auto add_group = [&](int k) {
      const ForceGroup& v = problem.groups[k];
      const VertexSlots& slot = slots[k];
      const int a = v.row_a / D, b = v.row_b / D;
      const bool ab = slot.ab >= 0 && owned(std::max(a, b));
      // With C = A R^-1 per side: the blocks C_a C_a^T, C_b C_b^T, C_a C_b^T.
      BlockByVertexD a_part, b_part;
      if (v.row_a >= 0 && (owned(a) || ab)) {
        a_part = divide_by_factor<D>(v.on_a.topRows<D>(), phi_factors[k]);
        if (owned(a)) add_product(a, slot.aa, a_part, a_part, true);
      }
      if (v.row_b >= 0 && (owned(b) || ab)) {
        b_part = divide_by_factor<D>(v.on_b.topRows<D>(), phi_factors[k]);
        if (owned(b)) add_product(b, slot.bb, b_part, b_part, true);
      }
      if (ab) {  // C_a C_b^T: rows of a, columns of b
        if (slot.ab_transposed) add_product(a, slot.ab, b_part, a_part, false);
        else add_product(b, slot.ab, a_part, b_part, false);
      }
    };
    if (parts == 1) {
      for (int k = 0; k < nv; ++k) add_group(k);
    } else {
      for (int k : part_groups_[part]) add_group(k);
    }
  });
}

void EquilibriumSolver::assemble(const EquilibriumProblem& problem, const std::vector<int>& first_row,
                                 const Eigen::VectorXd& w, const Eigen::VectorXd& z,
                                 std::vector<PhiFactor>& phi_factors) {
  if (block_rows_ == 3) assemble_normal_matrix<3>(problem, first_row, w, z, phi_factors);
  else assemble_normal_matrix<6>(problem, first_row, w, z, phi_factors);
}

bool EquilibriumSolver::factorize_shifted() {
  // Near the optimum the scales of z/w spread over many orders and the
  // matrix can lose positive definiteness in rounding; a small diagonal
  // shift, raised until the factorisation succeeds, restores it, and the
  // next iterations correct the slightly perturbed step.
  if (cholesky_->factorize()) return true;
  double* values = cholesky_->values();
  std::vector<double> unshifted(values, values + cholesky_->nonzeros());
  double largest = 0.0;
  for (int col = 0; col < size_; ++col) {
    largest = std::max(largest, std::abs(values[column_starts_[col + 1] - 1]));
  }
  for (double shift = 1e-14; shift <= 1e-8; shift *= 100.0) {
    std::copy(unshifted.begin(), unshifted.end(), values);
    for (int col = 0; col < size_; ++col) values[column_starts_[col + 1] - 1] += shift * largest;
    if (cholesky_->factorize()) return true;
  }
  return false;
}

bool EquilibriumSolver::prepare_response(const EquilibriumProblem& problem,
                                         const InteriorPointSolution& solution, bool merge) {
  response_ready_ = false;
  if (!cholesky_) return false;
  const std::vector<int> first_row = problem.inequality_starts();
  const int m_total = first_row.back();
  if (solution.w.size() != m_total || solution.z.size() != m_total) return false;
  find_twins(problem, merge);
  if (twins_.merged_of.empty()) {
    assemble(problem, first_row, solution.w, solution.z, response_phi_);
  } else {
    InteriorPointSolution merged;
    merge_solution(solution, first_row, merged);
    assemble(merge_twins(problem), merged_first_rows(first_row), merged.w, merged.z, response_phi_);
  }
  response_ready_ = factorize_shifted();
  return response_ready_;
}

Eigen::VectorXd EquilibriumSolver::multiplier_response(const Eigen::VectorXd& delta_rhs) const {
  if (!response_ready_) throw std::logic_error("multiplier_response before prepare_response");
  return cholesky_->solve(delta_rhs);
}

Eigen::Vector4d EquilibriumSolver::group_response(const EquilibriumProblem& problem, int group,
                                                  const Eigen::VectorXd& multipliers) const {
  const Eigen::Vector4d reaction = problem.reaction(problem.groups[group], multipliers);
  if (twins_.merged_of.empty()) return solve_phi(response_phi_[group], reaction);
  // A class of m twins has Phi m times a twin's, and m times its reaction.
  const int merged = twins_.merged_of[group];
  return solve_phi(response_phi_[merged], twins_.count[merged] * reaction);
}

InteriorPointInfo EquilibriumSolver::solve(const EquilibriumProblem& problem,
                                           const InteriorPointSettings& settings,
                                           InteriorPointSolution& solution, bool warm_start) {
  find_twins(problem, settings.merge_twins);
  if (twins_.merged_of.empty()) return solve_groups(problem, settings, solution, warm_start);
  const std::vector<int> first_row = problem.inequality_starts();
  const bool warm = warm_start && solution.x.size() == problem.variable_count() &&
                    solution.y.size() == size_ && solution.w.size() == first_row.back() &&
                    solution.z.size() == first_row.back();
  InteriorPointSolution merged;
  if (warm) merge_solution(solution, first_row, merged);
  InteriorPointInfo info = solve_groups(merge_twins(problem), settings, merged, warm);
  split_solution(merged, first_row, solution);
  // The mean complementarity of the problem's rows: the total gap is the
  // same, over more rows.
  if (first_row.back() > 0) info.complementarity *= static_cast<double>(merged.w.size()) / first_row.back();
  return info;
}

InteriorPointInfo EquilibriumSolver::solve_groups(const EquilibriumProblem& problem,
                                                  const InteriorPointSettings& settings,
                                                  InteriorPointSolution& solution, bool warm_start) {
  return block_rows_ == 3 ? solve_rows<3>(problem, settings, solution, warm_start)
                          : solve_rows<6>(problem, settings, solution, warm_start);
}

template <int D>
InteriorPointInfo EquilibriumSolver::solve_rows(const EquilibriumProblem& problem,
                                                const InteriorPointSettings& settings,
                                                InteriorPointSolution& solution, bool warm_start) {
  InteriorPointInfo info;
  const int nv = static_cast<int>(problem.groups.size());
  const Eigen::VectorXd& b = problem.rhs;
  // Each group's inequality rows start at first_row[k] in w and z. Their
  // constant sides (G x_k >= lower) are 0 but for groups with bounds (a
  // bounded cable's row, friction with a given strength): add_bound turns
  // G x_k into G x_k - lower.
  const std::vector<int> first_row = problem.inequality_starts();
  const int m_total = first_row[nv];
  auto add_bound = [&](int k, auto&& rows) {
    const GroupRules& rules = problem.rules_of(problem.groups[k]);
    if (rules.bound_coefficients.size()) rows += problem.groups[k].bound * rules.bound_coefficients;
  };
  auto rows_of = [&](int k) -> const RowsMatrix& { return problem.rules_of(problem.groups[k]).rows; };
  auto ineq = [&](auto& v, int k) {
    return v.segment(first_row[k], first_row[k + 1] - first_row[k]);
  };

  Eigen::VectorXd& x = solution.x;
  Eigen::VectorXd& y = solution.y;
  Eigen::VectorXd& w = solution.w;
  Eigen::VectorXd& z = solution.z;
  const bool sizes_match = x.size() == 4 * nv && y.size() == size_ && w.size() == m_total &&
                           z.size() == m_total;
  const bool cold_start = !(warm_start && sizes_match);
  if (!cold_start) {
    // Interior-point iterates must start strictly inside the cone.
    constexpr double kMargin = 1e-2;
    for (int k = 0; k < nv; ++k) {
      ineq(w, k).noalias() = rows_of(k) * x.segment<4>(4 * k);
      add_bound(k, ineq(w, k));
      ineq(w, k) = ineq(w, k).cwiseMax(kMargin);
    }
    z = z.cwiseMax(kMargin);
  } else {
    x = Eigen::VectorXd::Zero(4 * nv);
    y = Eigen::VectorXd::Zero(size_);
    w = Eigen::VectorXd::Ones(m_total);
    z = Eigen::VectorXd::Ones(m_total);
  }
  if (nv == 0 && size_ == 0) {
    info.status = SolverStatus::converged;
    return info;
  }
  if (!cholesky_) {
    info.status = SolverStatus::numerical_error;
    return info;
  }

  const double rhs_scale = 1.0 + (b.size() ? b.lpNorm<Eigen::Infinity>() : 0.0);
  double largest_linear = 0.0;
  for (const GroupRules& rules : problem.rules) {
    largest_linear = std::max(largest_linear, rules.linear.lpNorm<Eigen::Infinity>());
  }
  const double dual_scale = 1.0 + largest_linear;

  // The residuals at the iterate, a Newton direction, and the residual of
  // that direction (turned into its correction by an in-place solve).
  NewtonVectors r{Eigen::VectorXd(4 * nv), Eigen::VectorXd(size_), Eigen::VectorXd(m_total),
                  Eigen::VectorXd(m_total)};
  NewtonVectors step_direction = r, error = r;
  std::vector<PhiFactor> phi_factors(nv);
  Eigen::VectorXd rhs(size_);
  const int factorizations_before = cholesky_->factorizations();

  // Passes over the groups, split over loop_'s threads. A pass that adds
  // into balance rows (which groups of two parts may share) gives each part
  // after the first a rows vector of its own, summed in at the end.
  std::vector<Eigen::VectorXd> row_parts(loop_.parts() - 1);
  // Generic, not std::function: the per-group body is inlined into the
  // loop (an indirect call per group was 3 % of an important-weights run).
  auto for_groups = [&](const auto& per_group) {
    loop_.run(nv, [&](int begin, int end, int) {
      for (int k = begin; k < end; ++k) per_group(k);
    });
  };
  auto for_groups_into = [&](Eigen::VectorXd& rows, const auto& per_group) {
    const int parts = loop_.parts_for(nv);
    loop_.run(nv, [&](int begin, int end, int part) {
      Eigen::VectorXd& target = part == 0 ? rows : row_parts[part - 1];
      if (part > 0) target.setZero(size_);
      for (int k = begin; k < end; ++k) per_group(k, target);
    });
    for (int part = 1; part < parts; ++part) rows += row_parts[part - 1];
  };

  // Solves the Newton system in place: `v` holds the right-hand sides on
  // entry and the direction on return. With the current factorisation and
  // phi_factors: eliminating dz and dw row by row, then each group's dx,
  // leaves the normal equations in dy.
  auto solve_newton = [&](NewtonVectors& v) {
    rhs = -v.y;
    for_groups_into(rhs, [&](int k, Eigen::VectorXd& rows) {
      // Per inequality row (c + Z g) / W, combined as G^T (...).
      GroupRowsVector per_row = (ineq(v.z, k) + ineq(z, k).cwiseProduct(ineq(v.w, k))).cwiseQuotient(ineq(w, k));
      const Vector4 reduced = -v.x.segment<4>(4 * k) - rows_of(k).transpose() * per_row;
      const Vector4 t = solve_phi(phi_factors[k], reduced);
      v.x.segment<4>(4 * k) = t;  // dx, completed below with the A^T dy part
      add_group_effect<D>(problem.groups[k], -t, rows);
    });
    cholesky_->solve(rhs, v.y);
    for_groups([&](int k) {
      v.x.segment<4>(4 * k) += solve_phi(phi_factors[k], group_reaction<D>(problem.groups[k], v.y));
      ineq(v.w, k).noalias() += rows_of(k) * v.x.segment<4>(4 * k);  // dw = G dx + g
    });
    v.z = -(v.z + z.cwiseProduct(v.w)).cwiseQuotient(w);
  };
  // How far `dir` is from solving the Newton system for `e`: the residual of
  // each block, computed from the problem's data (not from phi_factors), so
  // that solving for it corrects the rounding of the elimination.
  auto newton_residual = [&](const NewtonVectors& e, const NewtonVectors& dir, NewtonVectors& out) {
    out.y = e.y;
    for_groups_into(out.y, [&](int k, Eigen::VectorXd& rows) {
      const ForceGroup& v = problem.groups[k];
      const GroupRules& rules = problem.rules_of(v);
      const Vector4 dxk = dir.x.segment<4>(4 * k);
      add_group_effect<D>(v, dxk, rows);
      out.x.segment<4>(4 * k) = e.x.segment<4>(4 * k) + twin_count(k) * rules.hessian.cwiseProduct(dxk) -
                                group_reaction<D>(v, dir.y) - rules.rows.transpose() * ineq(dir.z, k);
      ineq(out.w, k) = ineq(e.w, k) - ineq(dir.w, k);
      ineq(out.w, k).noalias() += rules.rows * dxk;
    });
    out.z = e.z + z.cwiseProduct(dir.w) + w.cwiseProduct(dir.z);
  };
  auto largest = [](const NewtonVectors& v) {
    double m = 0.0;
    for (const Eigen::VectorXd* part : {&v.x, &v.y, &v.w, &v.z}) {
      if (part->size()) m = std::max(m, part->lpNorm<Eigen::Infinity>());
    }
    return m;
  };
  // Newton direction with iterative refinement: near the optimum z / w
  // spreads over twenty orders of magnitude and the elimination loses
  // digits (its residual is about 1e-11 on a 10,000-block wall); left alone,
  // that error would stop the iterations short of the tolerance. Far from
  // the optimum it is negligible beside the iterate's own error, and the
  // check (a pass over every group) is skipped. `iterate_error` is the
  // current iterate's scaled error.
  constexpr int kRefinements = 3;
  constexpr double kRefineBelow = 1e-4;
  constexpr double kNoRefinement = std::numeric_limits<double>::infinity();
  auto newton_direction = [&](const NewtonVectors& e, NewtonVectors& out, double iterate_error) {
    const auto start = Clock::now();
    out = e;  // same sizes: no allocation
    solve_newton(out);
    const double target = std::max(1e-14 * largest(e), 1e-2 * iterate_error);
    double previous = std::numeric_limits<double>::infinity();
    for (int refinement = 0; refinement < kRefinements && iterate_error <= kRefineBelow; ++refinement) {
      newton_residual(e, out, error);
      const double size = largest(error);
      if (size <= target || size >= 0.5 * previous) break;
      previous = size;
      solve_newton(error);  // now the correction
      out.x += error.x;
      out.y += error.y;
      out.w += error.w;
      out.z += error.z;
    }
    info.solve_seconds += seconds_since(start);
  };

  // A class of twins has m times each twin's dual residual.
  auto dual_residual_of = [&](const Eigen::VectorXd& residual) {
    if (twins_.count.empty()) return residual.size() ? residual.lpNorm<Eigen::Infinity>() : 0.0;
    double largest = 0.0;
    for (int k = 0; k < nv; ++k) {
      largest = std::max(largest, residual.segment<4>(4 * k).lpNorm<Eigen::Infinity>() / twins_.count[k]);
    }
    return largest;
  };
  auto objective_value = [&] {
    double sum = 0.0;
    for (int k = 0; k < nv; ++k) {
      const GroupRules& rules = problem.rules_of(problem.groups[k]);
      const Vector4 xk = x.segment<4>(4 * k);
      sum += twin_count(k) * (0.5 * xk.dot(rules.hessian.cwiseProduct(xk)) + rules.linear.dot(xk));
    }
    return sum;
  };

  // The most accurate iterate within the inaccurate tolerance: when
  // rounding stops the iterations short of the tolerance (active
  // constraints whose slacks fall to 1e-12), it is the answer, reported as
  // inaccurate. Copied only once a later iterate is less accurate, by
  // undoing the step that left it: while the error falls, as it does near
  // the optimum of almost every solve, no copy exists (160 MB on a
  // 100,052-block vault, whose error also rises in its early iterations).
  // The least error at any accuracy only tells when the solve has stalled.
  double least_error = std::numeric_limits<double>::infinity();
  int least_error_iteration = 0;
  // The step lengths of the last step taken.
  double last_primal_step = 0.0, last_dual_step = 0.0;
  struct Iterate {
    double error = std::numeric_limits<double>::infinity();
    int iteration = 0;
    bool copied = false;  // false: the best is the current iterate or the one before the last step
    Eigen::VectorXd x, y, w, z;
    InteriorPointInfo info;
  } best;
  // Copies the iterate before the last step into `best` (step_direction
  // still holds that step's direction); it is lost if that is not finite.
  auto copy_previous_as_best = [&] {
    best.x = x - last_primal_step * step_direction.x;
    best.y = y - last_dual_step * step_direction.y;
    best.w = w - last_primal_step * step_direction.w;
    best.z = z - last_dual_step * step_direction.z;
    best.copied = true;
    if (!best.x.allFinite() || !best.y.allFinite() || !best.w.allFinite() || !best.z.allFinite()) {
      best.error = std::numeric_limits<double>::infinity();
    }
  };

  bool starting = cold_start;
  for (int iteration = 0;; ++iteration) {
    auto start = Clock::now();
    // Residuals.
    r.y = -b;
    for_groups_into(r.y, [&](int k, Eigen::VectorXd& rows) {
      const ForceGroup& v = problem.groups[k];
      const GroupRules& rules = problem.rules_of(v);
      const Vector4 xk = x.segment<4>(4 * k);
      add_group_effect<D>(v, xk, rows);
      r.x.segment<4>(4 * k) = twin_count(k) * (rules.hessian.cwiseProduct(xk) + rules.linear) -
                              group_reaction<D>(v, y) - rules.rows.transpose() * ineq(z, k);
      ineq(r.w, k) = -ineq(w, k);
      ineq(r.w, k).noalias() += rules.rows * xk;
      add_bound(k, ineq(r.w, k));
    });
    // The total gap, not its mean, bounds the objective's error.
    const double duality_gap = w.dot(z);
    const double mu = m_total > 0 ? duality_gap / m_total : 0.0;
    info.iterations = iteration;
    info.primal_residual = std::max(r.y.size() ? r.y.lpNorm<Eigen::Infinity>() : 0.0,
                                    r.w.size() ? r.w.lpNorm<Eigen::Infinity>() : 0.0);
    info.dual_residual = dual_residual_of(r.x);
    info.complementarity = mu;
    const bool best_is_previous = !best.copied && std::isfinite(best.error) && best.iteration == iteration - 1;
    if (!std::isfinite(mu) || !std::isfinite(info.primal_residual) ||
        !std::isfinite(info.dual_residual)) {
      if (best_is_previous) copy_previous_as_best();
      info.status = SolverStatus::numerical_error;
      break;
    }
    const double error_now = std::max({info.primal_residual / rhs_scale,
                                       info.dual_residual / dual_scale,
                                       duality_gap / (settings.objective_floor + std::abs(objective_value()))});
    if (error_now <= settings.tolerance) {
      info.status = SolverStatus::converged;
      break;
    }
    if (settings.certify_below > 0.0 && !starting &&
        compression_only_imbalance(problem, x) <= settings.certify_below) {
      info.status = SolverStatus::certified;
      break;
    }
    if (!starting && error_now < least_error) {
      least_error = error_now;
      least_error_iteration = iteration;
    }
    if (!starting && error_now <= settings.inaccurate_tolerance && error_now < best.error) {
      best.error = error_now;
      best.iteration = iteration;
      best.info = info;
      if (best.copied) {  // an older copy is no longer needed
        best.copied = false;
        for (Eigen::VectorXd* v : {&best.x, &best.y, &best.w, &best.z}) v->resize(0);
      }
    } else if (best_is_previous) {
      copy_previous_as_best();
    }
    const int stalled = iteration - least_error_iteration;
    if ((least_error <= settings.inaccurate_tolerance && stalled > kStallIterations) ||
        stalled > kHopelessIterations) {
      info.status = SolverStatus::max_iterations;
      break;
    }
    if (iteration >= settings.max_iterations) {
      info.status = SolverStatus::max_iterations;
      break;
    }
    if (stop_requested()) {
      info.status = SolverStatus::interrupted;
      break;
    }

    // Eliminate each vertex's unknowns and assemble the normal matrix.
    assemble_normal_matrix<D>(problem, first_row, w, z, phi_factors);
    info.assembly_seconds += seconds_since(start);
    start = Clock::now();
    const bool factored = factorize_shifted();
    info.factorization_seconds += seconds_since(start);
    if (!factored) {
      info.status = SolverStatus::numerical_error;
      break;
    }

    // Predictor: the affine-scaling direction. It only sets the centring
    // and the second-order term (and, at a cold start, the heuristic
    // starting point), so it is not refined: the corrector, the step taken,
    // is.
    r.z = w.cwiseProduct(z);
    newton_direction(r, step_direction, kNoRefinement);
    if (starting) {
      // Mehrotra's starting point (Nocedal & Wright, 16.60 for QPs): the
      // full affine step from x = 0, w = z = 1, with slacks and multipliers
      // moved back to at least kStartFloor. It balances the loads from the
      // first iteration on, where the plain start spends several iterations
      // reaching feasibility.
      starting = false;
      x += step_direction.x;
      y += step_direction.y;
      w = (w + step_direction.w).cwiseAbs().cwiseMax(kStartFloor);
      z = (z + step_direction.z).cwiseAbs().cwiseMax(kStartFloor);
      continue;
    }
    // The affine step's primal and dual lengths apart, as the steps taken
    // are (Mehrotra's heuristic with separate steps, as LP codes use it):
    // where only one side is blocked, mu_affine and so the centring come
    // out smaller. 10,051-block wall and 10,027-block vault: 22 -> 19
    // iterations; the robustness sweep 5,798 -> 5,533, every analysis
    // still converged.
    const double affine_primal = step_to_boundary(w, step_direction.w);
    const double affine_dual = step_to_boundary(z, step_direction.z);
    const double mu_affine = (w + affine_primal * step_direction.w).dot(z + affine_dual * step_direction.z) /
                             static_cast<double>(m_total);
    const double centering = std::pow(mu_affine / mu, 3);
    // Corrector: second-order term and centring, same factorisation.
    r.z = w.cwiseProduct(z) + step_direction.w.cwiseProduct(step_direction.z) -
          Eigen::VectorXd::Constant(m_total, centering * mu);
    newton_direction(r, step_direction, error_now);
    // Primal (x, w) and dual (y, z) steps of their own lengths, as LP
    // interior points take them: the Hessian is the tiny regularisation but
    // for the tension unknowns, so the dual residual the difference leaves,
    // (primal - dual step) H dx, is small and the next iterations remove it.
    // 10,027-block vault: 28 iterations -> 25; the robustness sweep: 3 %
    // fewer, every analysis still converged.
    const double primal_boundary = step_to_boundary(w, step_direction.w);
    const double dual_boundary = step_to_boundary(z, step_direction.z);
    if (std::isnan(primal_boundary) || std::isnan(dual_boundary)) {  // never step onto NaN
      info.status = SolverStatus::numerical_error;
      break;
    }
    double primal_step = std::min(1.0, settings.step_fraction * primal_boundary);
    double dual_step = std::min(1.0, settings.step_fraction * dual_boundary);
    // Unless that residual would hold the iterations back: when tension
    // unknowns carry force (an infeasible structure), |H dx| is not small
    // and the dual residual stalled at (primal - dual step) |H dx| ~ 1e-9
    // (a running-bond wall pushed by 1 g: 40 iterations, inaccurate); then
    // both take the shorter step.
    if (primal_step != dual_step) {
      double hessian_step = 0.0;
      for (int k = 0; k < nv; ++k) {
        const Vector4 h_dx =
            problem.rules_of(problem.groups[k]).hessian.cwiseProduct(step_direction.x.segment<4>(4 * k));
        hessian_step = std::max(hessian_step, h_dx.lpNorm<Eigen::Infinity>());
      }
      if (std::abs(primal_step - dual_step) * hessian_step > 0.1 * error_now * dual_scale) {
        primal_step = dual_step = std::min(primal_step, dual_step);
      }
    }
    if (!(std::min(primal_step, dual_step) > 1e-12)) {
      info.status = SolverStatus::numerical_error;
      break;
    }
    x += primal_step * step_direction.x;
    y += dual_step * step_direction.y;
    w += primal_step * step_direction.w;
    z += dual_step * step_direction.z;
    last_primal_step = primal_step;
    last_dual_step = dual_step;
  }
  // Short of convergence (or of a certificate, which is the iterate it
  // stopped at) the most accurate iterate within the inaccurate tolerance
  // is the answer, and says so; without one, the last iterate stays, with
  // its status. An interrupted solve stays interrupted: it carries no
  // verdict.
  if (info.status != SolverStatus::converged && info.status != SolverStatus::certified &&
      std::isfinite(best.error)) {
    const int iterations = info.iterations;
    const SolverStatus status = info.status;
    info = best.info;
    info.iterations = iterations;
    info.status = status == SolverStatus::interrupted ? status : SolverStatus::inaccurate;
    if (best.copied) {  // else the best is the iterate the solve stopped at
      x = std::move(best.x);
      y = std::move(best.y);
      w = std::move(best.w);
      z = std::move(best.z);
    }
  }
  info.factorizations = cholesky_->factorizations() - factorizations_before;
  info.groups = nv;
  info.objective = objective_value();
  return info;
}

bool carries_alone(EquilibriumSolver& solver, EquilibriumProblem problem, const Eigen::VectorXd& load,
                   double stable_tolerance, int max_iterations, int& iterations) {
  problem.rhs = load;
  InteriorPointSettings verdict;
  verdict.max_iterations = max_iterations;
  verdict.certify_below = stable_tolerance;
  InteriorPointSolution forces;
  const InteriorPointInfo info = solver.solve(problem, verdict, forces);
  iterations = info.iterations;
  return info.status == SolverStatus::certified;
}

}  // namespace ashlar
