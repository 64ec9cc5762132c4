#include "analysis/normal_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "analysis/interior_point_iterate.hpp"
#include "analysis/twin_groups.hpp"

namespace ashlar {

NormalMatrix::NormalMatrix(const EquilibriumProblem& problem, ParallelLoop& loop,
                           const SparseCholeskyOptions& factorisation)
    : loop_(loop), pattern_(problem) {
  UpperPattern upper = pattern_.upper_triangle();
  pattern_.find_slots(problem, pattern_slots_);
  if (problem.row_count > 0) {
    SparseCholeskyOptions by_bodies = factorisation;
    by_bodies.block_rows = problem.block_rows;
    cholesky_ = std::make_unique<SparseCholesky>(problem.row_count, std::move(upper.column_starts),
                                                 std::move(upper.row_indices), by_bodies);
  }
  partition();
}

bool NormalMatrix::fits(const EquilibriumProblem& problem) const {
  if (problem.row_count != rows() || problem.block_rows != block_rows() ||
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

bool NormalMatrix::refit(const EquilibriumProblem& problem) {
  if (problem.row_count != rows() || problem.block_rows != block_rows()) return false;
  std::vector<GroupSlots> slots;
  if (!pattern_.find_slots(problem, slots)) return false;
  pattern_slots_ = std::move(slots);
  // The twin classes and the assembly's parts were of the old groups.
  merged_slots_.clear();
  partition();
  return true;
}

void NormalMatrix::work_on(const TwinGroups& twins) {
  merged_slots_.clear();
  if (twins.merged()) {
    merged_slots_.resize(twins.classes());
    for (size_t j = 0; j < merged_slots_.size(); ++j) {
      merged_slots_[j] = pattern_slots_[twins.first_member(static_cast<int>(j))];
    }
  }
  merged_slots_.shrink_to_fit();
  partition();
}

void NormalMatrix::partition() {
  const std::vector<GroupSlots>& slots = worked_slots();
  parts_ = partition_assembly(slots, pattern_.blocks(), block_rows(),
                              loop_.parts_for(static_cast<int>(slots.size())));
}

template <int D>
void NormalMatrix::assemble(const EquilibriumProblem& problem, const std::vector<int>& first_row,
                            const Eigen::VectorXd& w, const Eigen::VectorXd& z, const TwinGroups& twins,
                            std::vector<PhiFactor>& phi_factors) {
  using BlockByVertexD = Eigen::Matrix<double, D, 4>;
  const int nv = static_cast<int>(problem.groups.size());
  phi_factors.resize(nv);
  // Slacks of active rows may be (near) zero; keep z / w finite.
  constexpr double kLeastSlack = std::numeric_limits<double>::min();
  loop_.run(nv, [&](int begin, int end, int) {
    GroupRowsVector scaling;  // z / w of group k's rows
    for (int k = begin; k < end; ++k) {
      const GroupRules& rules = problem.rules_of(problem.groups[k]);
      const int rows = static_cast<int>(rules.rows.rows());
      scaling = z.segment(first_row[k], rows).cwiseQuotient(w.segment(first_row[k], rows).cwiseMax(kLeastSlack));
      phi_factors[k] = factor_phi(twins.count(k) * rules.hessian, rules.rows, scaling);
    }
  });
  // Each part adds only into its own range of block columns (so no entry
  // has two writers), taking the groups that add there.
  double* values = cholesky_->values();
  const std::vector<int>& column_starts = cholesky_->column_starts();
  const int parts = static_cast<int>(parts_.groups.size());
  loop_.run_parts(parts, [&](int part) {
    const int first = parts_.first_column[part], last = parts_.first_column[part + 1];
    std::fill(values + column_starts[D * first], values + column_starts[D * last], 0.0);
    auto owned = [&](int column) { return column >= first && column < last; };
    // Adds left right^T (D x D) to block column col_block at its rank-th
    // block row; on the diagonal only its upper triangle, the one stored.
    auto add_product = [&](int col_block, int rank, const BlockByVertexD& left, const BlockByVertexD& right,
                           bool diagonal) {
      for (int cj = 0; cj < D; ++cj) {
        double* column = values + column_starts[D * col_block + cj] + D * rank;
        const int rows = diagonal ? cj + 1 : D;
        for (int ri = 0; ri < rows; ++ri) column[ri] += left.row(ri).dot(right.row(cj));
      }
    };
    const std::vector<GroupSlots>& slots = worked_slots();
    auto add_group = [&](int k) {
      const ForceGroup& v = problem.groups[k];
      const GroupSlots& slot = slots[k];
      const int a = v.row_a / D, b = v.row_b / D;
      const bool ab = slot.ab >= 0 && owned(std::max(a, b));
      // With C = A R^-1 per side: the blocks C_a C_a^T, C_b C_b^T, C_a C_b^T.
      // A's rows on a are T times its rows on b (ForceGroup::on_a), so C_a = T C_b.
      const bool on_a = v.row_a >= 0 && (owned(a) || ab), on_b = v.row_b >= 0 && (owned(b) || ab);
      if (!on_a && !on_b) return;
      const BlockByVertexD b_part = divide_by_factor<D>(v.on_b.topRows<D>(), phi_factors[k]);
      BlockByVertexD a_part;
      if (on_a) {
        // ForceGroup::add_effect_at_a's map, by rows: column by column
        // through it this pass took 3,582 perf samples against 2,898 (the
        // imperfect dome's load capacity).
        a_part = -b_part;
        const Vec3& l = v.lever;
        if constexpr (D == 6) {
          a_part.row(3) += l.y() * b_part.row(2) - l.z() * b_part.row(1);
          a_part.row(4) += l.z() * b_part.row(0) - l.x() * b_part.row(2);
          a_part.row(5) += l.x() * b_part.row(1) - l.y() * b_part.row(0);
        } else {
          a_part.row(2) += l.z() * b_part.row(0) - l.x() * b_part.row(1);
        }
        if (owned(a)) add_product(a, slot.aa, a_part, a_part, true);
      }
      if (on_b && owned(b)) add_product(b, slot.bb, b_part, b_part, true);
      if (ab) {  // C_a C_b^T: rows of a, columns of b
        if (slot.ab_transposed) add_product(a, slot.ab, b_part, a_part, false);
        else add_product(b, slot.ab, a_part, b_part, false);
      }
    };
    if (parts == 1) {
      for (int k = 0; k < nv; ++k) add_group(k);
    } else {
      for (int k : parts_.groups[part]) add_group(k);
    }
  });
}

template void NormalMatrix::assemble<3>(const EquilibriumProblem&, const std::vector<int>&, const Eigen::VectorXd&,
                                        const Eigen::VectorXd&, const TwinGroups&, std::vector<PhiFactor>&);
template void NormalMatrix::assemble<6>(const EquilibriumProblem&, const std::vector<int>&, const Eigen::VectorXd&,
                                        const Eigen::VectorXd&, const TwinGroups&, std::vector<PhiFactor>&);

void NormalMatrix::assemble_any(const EquilibriumProblem& problem, const std::vector<int>& first_row,
                                const Eigen::VectorXd& w, const Eigen::VectorXd& z, const TwinGroups& twins,
                                std::vector<PhiFactor>& phi_factors) {
  if (block_rows() == 3) assemble<3>(problem, first_row, w, z, twins, phi_factors);
  else assemble<6>(problem, first_row, w, z, twins, phi_factors);
}

bool NormalMatrix::factorize_shifted() {
  // Near the optimum the scales of z/w spread over many orders and the
  // matrix can lose positive definiteness in rounding; a small diagonal
  // shift, raised until the factorisation succeeds, restores it, and the
  // next iterations correct the slightly perturbed step.
  if (cholesky_->factorize()) return true;
  double* values = cholesky_->values();
  const std::vector<int>& column_starts = cholesky_->column_starts();
  std::vector<double> unshifted(values, values + cholesky_->nonzeros());
  double largest = 0.0;
  for (int col = 0; col < rows(); ++col) {
    largest = std::max(largest, std::abs(values[column_starts[col + 1] - 1]));
  }
  for (double shift = 1e-14; shift <= 1e-8; shift *= 100.0) {
    std::copy(unshifted.begin(), unshifted.end(), values);
    for (int col = 0; col < rows(); ++col) values[column_starts[col + 1] - 1] += shift * largest;
    if (cholesky_->factorize()) return true;
  }
  return false;
}

}  // namespace ashlar
