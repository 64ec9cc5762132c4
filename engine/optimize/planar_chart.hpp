// The chart that keeps a design space's designs planar (see the comment
// of design_space.hpp, "The equations are nonlinear"), and the rank tools
// it shares with the design space.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <memory>
#include <optional>
#include <vector>

#include "optimize/design_space.hpp"

namespace ashlar {

using NormalFactor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

// The rows of `jacobian` that do not depend on rows before them, found by a
// sparse LDL^T of jacobian jacobian^T: a dependent row leaves a pivot at
// rounding level, and a small shift keeps the factorisation going past it.
// `factor` keeps that shifted factorisation. Throws InvalidArgument when it
// cannot be factorised.
std::vector<int> independent_rows(const Eigen::SparseMatrix<double>& jacobian, NormalFactor& factor);

// The rows.size() x count matrix that picks `rows` of a count-row matrix.
Eigen::SparseMatrix<double> selection(const std::vector<int>& rows, int count);

// A smooth map from reduced variables z onto the designs that satisfy the
// constraint equations, linearised at a base design (see the comment of
// design_space.hpp).
// Cheap to copy; it refers to `space`, which must outlive it.
class PlanarChart {
public:
  // base: z of a design on (or within tolerance of) the constraint set.
  PlanarChart(const DesignSpace& space, const Eigen::VectorXd& base);

  // y = z + A_b^T lambda with c(y) = 0 to tolerance, found by Newton's
  // method from lambda = 0; std::nullopt when it does not converge (z too
  // far from the base for this chart).
  std::optional<Eigen::VectorXd> project(const Eigen::VectorXd& z) const;
  // The derivative with respect to z of f(project(z)), given y = project(z)
  // and gradient = df/dy (size variable_count()). Throws GeometryError when
  // y is too far from the base for this chart.
  Eigen::VectorXd pull_back(const Eigen::VectorXd& y, const Eigen::VectorXd& gradient) const;
  // Number of independent constraint rows kept at the base.
  int rank() const { return static_cast<int>(rows_.size()); }

private:
  // Eigen's preconditioner interface around the chart's factor.
  struct FactorPreconditioner {
    const NormalFactor* factor = nullptr;
    FactorPreconditioner() = default;
    template <typename Matrix>
    explicit FactorPreconditioner(const Matrix&) {}
    template <typename Matrix>
    FactorPreconditioner& analyzePattern(const Matrix&) {
      return *this;
    }
    template <typename Matrix>
    FactorPreconditioner& factorize(const Matrix&) {
      return *this;
    }
    template <typename Matrix>
    FactorPreconditioner& compute(const Matrix&) {
      return *this;
    }
    Eigen::VectorXd solve(const Eigen::VectorXd& b) const { return factor->solve(b); }
    Eigen::ComputationInfo info() const { return Eigen::Success; }
  };

  Eigen::SparseMatrix<double> jacobian(const Eigen::VectorXd& z) const;
  std::optional<Eigen::VectorXd> solve(const Eigen::SparseMatrix<double>& matrix,
                                       const Eigen::VectorXd& rhs) const;

  const DesignSpace* space_;
  std::vector<int> rows_;                              // independent rows at the base
  Eigen::SparseMatrix<double> selection_;              // rows_ x constraint_count()
  Eigen::SparseMatrix<double> base_jacobian_;          // A_b: rows_ x variable_count()
  Eigen::VectorXd tolerances_;                         // of rows_
  std::shared_ptr<const NormalFactor> normal_factor_;  // of A_b A_b^T; shared by copies
};

}  // namespace ashlar
