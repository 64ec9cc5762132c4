#include "core/split_cholesky.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <utility>

#include "core/blas.hpp"
#include "core/cholmod_system.hpp"
#include "core/sparse_pattern.hpp"

namespace ashlar {

// One side of the split: the rows of part A (or B) followed by the
// separator's, factored with the separator last.
struct SplitCholesky::Side {
  std::unique_ptr<CholmodSystem> system;
  int own = 0;                      // rows of this part, its factor's first; separator rows follow
  FactorRows rows;                  // the whole matrix's rows it holds, own rows first
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

  // Factors this side (its values read from the whole matrix's) and forms
  // its Schur share T.
  bool factorize(const BlockPattern& pattern, const double* whole_values) {
    if (!system->factorize(PatternColumns(pattern, whole_values, rows))) return false;
    system->trailing_block_reversed(own, reversed_trailing);  // L_SS
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

  // Forward solve of this side with b_S = 0: y = L^-1 P b; its separator
  // rows give M_SA M_AA^-1 b_A = L_SA y_A = -L_SS y_S.
  void forward(const Eigen::VectorXd& rhs) {
    const int n = system->rows(), s = separator_rows();
    permuted.resize(n);
    for (int k = 0; k < n; ++k) permuted[k] = k < own ? rhs[rows.caller_row[k]] : 0.0;
    const double* y = system->solve(CholmodSystem::Solve::forward, permuted.data());
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
    const double* u = system->solve(CholmodSystem::Solve::backward, back.data());
    for (int k = 0; k < own; ++k) out[rows.caller_row[k]] = u[k];
  }
};

SplitCholesky::SplitCholesky() : sides_{std::make_unique<Side>(), std::make_unique<Side>()} {}

SplitCholesky::~SplitCholesky() = default;

std::unique_ptr<SplitCholesky> SplitCholesky::analyse(int n, const std::vector<int>& column_starts,
                                                      const std::vector<int>& row_indices, int block_rows,
                                                      int max_separator_rows) {
  std::unique_ptr<SplitCholesky> out(new SplitCholesky());
  if (!out->split(n, column_starts, row_indices, block_rows, max_separator_rows)) out.reset();
  return out;
}

bool SplitCholesky::split(int n, const std::vector<int>& column_starts, const std::vector<int>& row_indices,
                          int block_rows, int max_separator_rows) {
  const std::vector<int> part = bisect(n, column_starts, row_indices);
  if (part.empty()) return false;
  // Local numbering per side: own rows first, then the separator's.
  std::vector<int> local(n);
  int counts[3] = {0, 0, 0};
  for (int i = 0; i < n; ++i) local[i] = counts[part[i]]++;
  const int s = counts[2];
  if (s == 0 || s > max_separator_rows || std::min(counts[0], counts[1]) < n / 8) return false;
  separator_.reserve(s);
  for (int i = 0; i < n; ++i) {
    if (part[i] == 2) separator_.push_back(i);
  }
  // Each side's entries in its local numbering (own rows, then the
  // separator's), upper triangle: {column, row}.
  std::vector<std::array<int, 2>> entries[2];
  std::vector<int> own_rows[2];  // the whole matrix's row of each own row
  for (int p = 0; p < 2; ++p) {
    sides_[p]->own = counts[p];
    own_rows[p].reserve(counts[p]);
    for (int i = 0; i < n; ++i) {
      if (part[i] == p) own_rows[p].push_back(i);
    }
  }
  auto local_index = [&](int i, int p) { return part[i] == 2 ? sides_[p]->own + local[i] : local[i]; };
  for (int j = 0; j < n; ++j) {
    for (int e = column_starts[j]; e < column_starts[j + 1]; ++e) {
      const int i = row_indices[e];
      if (part[i] != 2 && part[j] != 2 && part[i] != part[j]) return false;  // not a separator
      for (int p = 0; p < 2; ++p) {
        if ((part[i] == 2 || part[i] == p) && (part[j] == 2 || part[j] == p)) {
          const int a = local_index(i, p), b = local_index(j, p);
          entries[p].push_back({std::max(a, b), std::min(a, b)});
        }
      }
      if (part[i] == 2 && part[j] == 2) {
        separator_entries_.push_back({e, std::max(local[i], local[j]), std::min(local[i], local[j])});
      }
    }
  }
  // The two sides' orderings and analyses, each on its own core (their
  // METIS calls one at a time, core/cholmod_system.cpp).
  bool ordered[2] = {false, false};
  loop_.run_parts(2, [&](int p) {
    Side& side = *sides_[p];
    const int rows = side.own + s;
    const ColumnPattern upper = compress_columns(rows, entries[p]);
    const std::vector<int> order =
        order_with_last_rows(rows, upper.column_starts, upper.row_indices, side.own, block_rows);
    if (order.empty()) return;  // local row at factor row k
    std::vector<int> position(rows);
    for (int k = 0; k < rows; ++k) position[order[k]] = k;
    // The side's lower triangle in factor order, which CHOLMOD factors in
    // place.
    for (auto& [column, row] : entries[p]) {
      const int a = position[row], b = position[column];
      column = std::min(a, b);
      row = std::max(a, b);
    }
    const ColumnPattern lower = compress_columns(rows, entries[p]);
    std::vector<std::array<int, 2>>().swap(entries[p]);
    std::vector<int> caller_rows(rows);
    for (int k = 0; k < rows; ++k) {
      const int local_row = order[k];
      caller_rows[k] = local_row < side.own ? own_rows[p][local_row] : separator_[local_row - side.own];
    }
    side.rows = FactorRows(n, std::move(caller_rows), block_rows);
    side.system = std::make_unique<CholmodSystem>(rows, lower.column_starts.data(), lower.row_indices.data(),
                                                  CholmodSystem::Triangle::lower);
    side.system->analyze_as_ordered();
    side.separator_slot.resize(s);
    for (int k = 0; k < s; ++k) side.separator_slot[k] = order[side.own + k] - side.own;
    ordered[p] = true;
  });
  return ordered[0] && ordered[1];
}

double SplitCholesky::factor_nonzeros() const {
  const double s = static_cast<double>(separator_.size());
  // The two sides' factors hold their separator block too; the dense
  // Schur factor replaces them.
  return sides_[0]->system->factor_nonzeros() + sides_[1]->system->factor_nonzeros() - s * (s + 1) / 2;
}

bool SplitCholesky::factorize(const BlockPattern& pattern, const double* values) {
  bool factored[2] = {false, false};
  loop_.run_parts(2, [&](int p) { factored[p] = sides_[p]->factorize(pattern, values); });
  if (!factored[0] || !factored[1]) return false;
  // Schur complement of M onto S: T_A + T_B - M_SS (lower triangle).
  const int s = separator_rows();
  schur_.setZero(s, s);
  for (const std::unique_ptr<Side>& side : sides_) side->add_schur_share(schur_);
  for (const SeparatorEntry& entry : separator_entries_) schur_(entry.row, entry.column) -= values[entry.value];
  int info = 0;
  dpotrf_("L", &s, schur_.data(), &s, &info, 1);
  return info == 0 && schur_.diagonal().allFinite();
}

void SplitCholesky::solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& out) {
  out.resize(rhs.size());
  loop_.run_parts(2, [&](int p) { sides_[p]->forward(rhs); });
  const int s = separator_rows();
  separator_rhs_.resize(s);
  for (int k = 0; k < s; ++k) separator_rhs_[k] = rhs[separator_[k]];
  separator_rhs_ -= sides_[0]->separator_part + sides_[1]->separator_part;
  const int one = 1;
  int info = 0;
  dpotrs_("L", &s, &one, schur_.data(), &s, separator_rhs_.data(), &s, &info, 1);
  loop_.run_parts(2, [&](int p) { sides_[p]->backward(separator_rhs_, out); });
  for (int k = 0; k < s; ++k) out[separator_[k]] = separator_rhs_[k];
}

}  // namespace ashlar
