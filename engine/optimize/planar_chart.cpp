#include "optimize/planar_chart.hpp"

#include <Eigen/IterativeLinearSolvers>
#include <algorithm>
#include <limits>

#include "core/error.hpp"

namespace ashlar {

namespace {

// A constraint row whose squared gradient shrinks below this fraction once
// its components along earlier rows are removed is redundant; the shift
// (of the largest squared gradient) is far below that, far above rounding.
constexpr double kRankThreshold = 1e-7;
constexpr double kPivotShift = 1e-15;
// A projection's Newton steps must at least halve the residual, within a
// limit; otherwise the point is too far from the chart's base.
constexpr double kMinContraction = 0.5;
constexpr int kMaxNewtonIterations = 20;
// Relative residuals of the linear solves: the target, and the worst that
// counts as rounding (ill-conditioned charts stall between the two).
constexpr double kExactSolve = 1e-14;
constexpr double kRoundedSolve = 1e-9;
constexpr int kMaxKrylovIterations = 200;

}  // namespace

std::vector<int> independent_rows(const Eigen::SparseMatrix<double>& jacobian,
                                  NormalFactor& factor) {
  const Eigen::SparseMatrix<double> normal = jacobian * jacobian.transpose();
  const Eigen::VectorXd squared_norms = normal.diagonal();
  std::vector<int> rows;
  if (normal.rows() == 0 || squared_norms.maxCoeff() == 0.0) return rows;
  const double shift = kPivotShift * squared_norms.maxCoeff();
  factor.setShift(shift);
  factor.compute(normal);
  if (factor.info() != Eigen::Success) {
    throw InvalidArgument("design: the constraint Jacobian could not be factorised");
  }
  for (Eigen::Index k = 0; k < normal.rows(); ++k) {
    const int row = factor.permutationPinv().indices()[k];
    if (factor.vectorD()[k] - shift > kRankThreshold * squared_norms[row]) rows.push_back(row);
  }
  std::sort(rows.begin(), rows.end());
  return rows;
}

Eigen::SparseMatrix<double> selection(const std::vector<int>& rows, int count) {
  std::vector<Eigen::Triplet<double>> ones;
  for (size_t k = 0; k < rows.size(); ++k) ones.emplace_back(static_cast<int>(k), rows[k], 1.0);
  Eigen::SparseMatrix<double> select(static_cast<int>(rows.size()), count);
  select.setFromTriplets(ones.begin(), ones.end());
  return select;
}

PlanarChart::PlanarChart(const DesignSpace& space, const Eigen::VectorXd& base) : space_(&space) {
  const Eigen::SparseMatrix<double> full = space.constraint_jacobian(base);
  // The rows are independent by construction but for rare cases (positions
  // that move together within one plane, an asymmetric mesh under a mirror)
  // that would make A_b A^T singular. The factor that finds them then
  // preconditions the solves.
  auto factor = std::make_shared<NormalFactor>();
  rows_ = independent_rows(full, *factor);
  selection_ = selection(rows_, space.constraint_count());
  base_jacobian_ = selection_ * full;
  tolerances_ = selection_ * space.constraint_tolerances();
  if (rank() == 0) return;
  if (rank() < full.rows()) factor->compute(base_jacobian_ * base_jacobian_.transpose());
  normal_factor_ = std::move(factor);
}

Eigen::SparseMatrix<double> PlanarChart::jacobian(const Eigen::VectorXd& z) const {
  return selection_ * space_->constraint_jacobian(z);
}

std::optional<Eigen::VectorXd> PlanarChart::project(const Eigen::VectorXd& z) const {
  Eigen::VectorXd y = z;
  double previous = std::numeric_limits<double>::infinity();
  for (int iteration = 0; rank() > 0; ++iteration) {
    const Eigen::VectorXd residual = selection_ * space_->constraint_values(y);
    if (!residual.allFinite()) return std::nullopt;
    const double excess = (residual.cwiseAbs().array() / tolerances_.array()).maxCoeff();
    if (excess <= 1.0) break;
    // Newton converges quadratically; when it stalls, rounding must explain it.
    const double size = residual.cwiseAbs().maxCoeff();
    if (size > kMinContraction * previous || iteration == kMaxNewtonIterations) {
      if (excess <= kRowSlack) break;
      return std::nullopt;
    }
    previous = size;
    const std::optional<Eigen::VectorXd> step =
        solve(jacobian(y) * base_jacobian_.transpose(), residual);
    if (!step) return std::nullopt;
    y -= base_jacobian_.transpose() * *step;
  }
  return y;
}

Eigen::VectorXd PlanarChart::pull_back(const Eigen::VectorXd& y,
                                       const Eigen::VectorXd& gradient) const {
  if (rank() == 0) return gradient;
  const Eigen::SparseMatrix<double> at_y = jacobian(y);
  const std::optional<Eigen::VectorXd> multipliers =
      solve(base_jacobian_ * at_y.transpose(), base_jacobian_ * gradient);
  if (!multipliers) {
    throw GeometryError("planar chart: the gradient cannot be mapped at this design");
  }
  return gradient - at_y.transpose() * *multipliers;
}

// Systems with A(y) A_b^T or its transpose: a sparse LU per Newton step
// would cost several factorisations per design, so BiCGSTAB solves them,
// preconditioned by the chart's factor of A_b A_b^T, which they approach as
// y approaches the base (a handful of iterations near it).
std::optional<Eigen::VectorXd> PlanarChart::solve(const Eigen::SparseMatrix<double>& matrix,
                                                  const Eigen::VectorXd& rhs) const {
  Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, FactorPreconditioner> solver;
  solver.preconditioner().factor = normal_factor_.get();
  solver.setTolerance(kExactSolve);
  solver.setMaxIterations(kMaxKrylovIterations);
  solver.compute(matrix);
  const Eigen::VectorXd solution = solver.solve(rhs);
  if (!solution.allFinite() || solver.error() > kRoundedSolve) return std::nullopt;
  return solution;
}

}  // namespace ashlar
