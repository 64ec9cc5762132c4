#include "analysis/clp_barrier.hpp"

#include <ClpCholeskyBase.hpp>
#include <ClpEventHandler.hpp>
#include <ClpInterior.hpp>
#include <ClpMatrixBase.hpp>
#include <ClpSimplex.hpp>
#include <ClpSolve.hpp>
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/sparse_cholesky.hpp"

namespace ashlar {

static_assert(sizeof(CoinWorkDouble) == sizeof(double), "Clp built with long double work arrays");

// M = A D A^T + diag(d_slack + delta^2) for the barrier's diagonal D: its
// upper triangle's pattern, and for every column of A the slots of the
// entries it adds to with their products a_i a_j, fixed with the matrix.
struct BarrierNormalEquations {
  int rows = 0, columns = 0;
  // The matrix as Clp holds it, which the pairs' products come from.
  std::vector<int> column_length, column_rows;
  std::vector<double> column_values;
  std::vector<int> pair_start;         // column c adds pairs [pair_start[c], pair_start[c + 1])
  std::vector<int> pair_slot;          // where, in the pattern's values
  std::vector<double> pair_product;    // a_i a_j
  std::vector<int> diagonal_slot;      // per row
  std::unique_ptr<SparseCholesky> cholesky;
  Eigen::VectorXd rhs, solution;

  explicit BarrierNormalEquations(const ClpMatrixBase& matrix)
      : rows(matrix.getNumRows()), columns(matrix.getNumCols()) {
    const CoinBigIndex* start = matrix.getVectorStarts();
    const int* length = matrix.getVectorLengths();
    const int* row = matrix.getIndices();
    const double* value = matrix.getElements();
    column_length.assign(length, length + columns);
    // Each column's entries by row.
    std::vector<std::vector<std::pair<int, double>>> entries(columns);
    for (int c = 0; c < columns; ++c) {
      for (CoinBigIndex k = start[c]; k < start[c] + length[c]; ++k) {
        column_rows.push_back(row[k]);
        column_values.push_back(value[k]);
        if (value[k] != 0.0) entries[c].emplace_back(row[k], value[k]);
      }
      std::sort(entries[c].begin(), entries[c].end());
    }
    // Upper triangle: entry (i, j), i <= j, in column j.
    std::vector<std::vector<int>> upper(rows);
    for (int i = 0; i < rows; ++i) upper[i].push_back(i);
    for (const auto& column : entries) {
      for (size_t l = 0; l < column.size(); ++l) {
        for (size_t k = 0; k < l; ++k) upper[column[l].first].push_back(column[k].first);
      }
    }
    std::vector<int> column_starts(rows + 1, 0), row_indices;
    for (int j = 0; j < rows; ++j) {
      std::sort(upper[j].begin(), upper[j].end());
      upper[j].erase(std::unique(upper[j].begin(), upper[j].end()), upper[j].end());
      row_indices.insert(row_indices.end(), upper[j].begin(), upper[j].end());
      column_starts[j + 1] = static_cast<int>(row_indices.size());
    }
    auto slot = [&](int i, int j) {
      const auto first = row_indices.begin() + column_starts[j], last = row_indices.begin() + column_starts[j + 1];
      return static_cast<int>(std::lower_bound(first, last, i) - row_indices.begin());
    };
    pair_start.assign(columns + 1, 0);
    for (int c = 0; c < columns; ++c) {
      const auto& column = entries[c];
      for (size_t l = 0; l < column.size(); ++l) {
        for (size_t k = 0; k <= l; ++k) {
          pair_slot.push_back(slot(column[k].first, column[l].first));
          pair_product.push_back(column[k].second * column[l].second);
        }
      }
      pair_start[c + 1] = static_cast<int>(pair_slot.size());
    }
    diagonal_slot.resize(rows);
    for (int i = 0; i < rows; ++i) diagonal_slot[i] = slot(i, i);
    // Whole: the programs of several blocks run on the cores side by side.
    SparseCholeskyOptions whole;
    whole.split_from_rows = std::numeric_limits<int>::max();
    cholesky = std::make_unique<SparseCholesky>(rows, std::move(column_starts), std::move(row_indices), whole);
    rhs.resize(rows);
  }

  // Whether `matrix` is the one analysed, entry for entry.
  bool fits(const ClpMatrixBase& matrix) const {
    if (matrix.getNumRows() != rows || matrix.getNumCols() != columns) return false;
    const CoinBigIndex* start = matrix.getVectorStarts();
    const int* length = matrix.getVectorLengths();
    const int* row = matrix.getIndices();
    const double* value = matrix.getElements();
    for (int c = 0, k = 0; c < columns; ++c) {
      if (length[c] != column_length[c]) return false;
      for (CoinBigIndex e = start[c]; e < start[c] + length[c]; ++e, ++k) {
        if (row[e] != column_rows[k] || value[e] != column_values[k]) return false;
      }
    }
    return true;
  }

  // Fills M for the diagonal of the columns and then of the rows' slacks,
  // and factors it; a matrix that is not numerically positive definite
  // (a degenerate iterate) gets its diagonal raised by a growing fraction
  // of its largest entry until it factors, up to 1e-3 of it.
  void factorize(const double* diagonal, double delta_squared) {
    double* values = cholesky->values();
    std::fill(values, values + cholesky->nonzeros(), 0.0);
    for (int c = 0; c < columns; ++c) {
      const double d = diagonal[c];
      if (d == 0.0) continue;
      for (int p = pair_start[c]; p < pair_start[c + 1]; ++p) values[pair_slot[p]] += d * pair_product[p];
    }
    double largest = 0.0;
    for (int i = 0; i < rows; ++i) {
      values[diagonal_slot[i]] += diagonal[columns + i] + delta_squared;
      largest = std::max(largest, values[diagonal_slot[i]]);
    }
    for (double shift = 1e-12; !cholesky->factorize() && shift <= 1e-3 && std::isfinite(largest); shift *= 1e3) {
      for (int i = 0; i < rows; ++i) values[diagonal_slot[i]] += shift * largest;
    }
  }

  void solve(double* region) {
    rhs = Eigen::Map<const Eigen::VectorXd>(region, rows);
    cholesky->solve(rhs, solution);
    std::copy(solution.data(), solution.data() + rows, region);
  }
};

namespace {

// Clp's hooks into the normal equations: its ordering and symbolic
// factorisation are the analysed pattern's; nothing is ever dropped.
class CholmodCholesky : public ClpCholeskyBase {
public:
  explicit CholmodCholesky(BarrierNormalEquations& normal) : normal_(normal) {}

  int order(ClpInterior* model) override {
    model_ = model;
    numberRows_ = model->numberRows();
    delete[] rowsDropped_;
    rowsDropped_ = new char[numberRows_]();
    numberRowsDropped_ = 0;
    return 0;
  }
  int symbolic() override { return 0; }
  // A failed factorisation leaves the last factor (Clp aborts the process
  // on a nonzero status); the iterate's accuracy checks then end the solve.
  int factorize(const CoinWorkDouble* diagonal, int* rowsDropped) override {
    const double delta = model_->delta();
    normal_.factorize(diagonal, delta * delta);
    std::fill(rowsDropped, rowsDropped + numberRows_, 0);
    choleskyCondition_ = 1.0;
    return 0;
  }
  void solve(CoinWorkDouble* region) override { normal_.solve(region); }
  ClpCholeskyBase* clone() const override { return new CholmodCholesky(*this); }

private:
  BarrierNormalEquations& normal_;
};

}  // namespace

BarrierSolver::BarrierSolver() = default;
BarrierSolver::~BarrierSolver() = default;
BarrierSolver::BarrierSolver(BarrierSolver&&) noexcept = default;
BarrierSolver& BarrierSolver::operator=(BarrierSolver&&) noexcept = default;

int BarrierSolver::solve(ClpSimplex& model, int iteration_limit) {
  const ClpMatrixBase& matrix = *model.clpMatrix();
  if (!normal_ || !normal_->fits(matrix)) normal_ = std::make_unique<BarrierNormalEquations>(matrix);
  // As ClpSolve's barrier without crossover, with this Cholesky.
  ClpInterior barrier;
  barrier.borrowModel(model);
  barrier.eventHandler()->setSimplex(nullptr);
  if (barrier.numberRows() + barrier.numberColumns() > 10000) barrier.setMaximumBarrierIterations(1000);
  if (iteration_limit > 0) barrier.setMaximumBarrierIterations(iteration_limit);
  barrier.setCholesky(new CholmodCholesky(*normal_));
  barrier.scaling(0);
  barrier.primalDual();
  const int status = barrier.status();
  iterations_ = barrier.numberIterations();
  if (barrier.numberFixed()) barrier.fixFixed(false);
  barrier.returnModel(model);
  if (status < 0) {
    // Stopped without a verdict (no progress: 1 of the 49 blocks of an 8 x
    // 6 dome): Clp's own barrier, which crosses over to the simplex then.
    ClpSolve clp;
    clp.setSolveType(ClpSolve::useBarrierNoCross);
    clp.setPresolveType(ClpSolve::presolveOff);
    clp.setSpecialOption(2, 1);  // no interrupt handler: solvers run side by side
    model.initialSolve(clp);
    iterations_ += model.numberIterations();
    return model.status();
  }
  model.setProblemStatus(status);
  model.setNumberIterations(iterations_);
  return status;
}

}  // namespace ashlar
