// How far an interior-point iterate (interior_point_iterate.hpp) is from
// the optimum of the equilibrium QP:
//
//   r.x = H x + q - A^T y - G^T z      dual residual       (4 per group)
//   r.y = A x - b                      balance residual    (balance rows)
//   G x - lower - w                    slack residual      (inequality rows)
//
// (H, q: the group's Hessian and linear term, m times a twin's for a class
// of m twins), the Newton system's right-hand side (newton_system.hpp,
// which computes the slack residual group by group as it solves), and the
// scaled error that decides convergence: the largest of the balance and
// slack residuals over rhs_scale, the dual residual over dual_scale, and
// the total duality gap w^T z relative to the objective (all
// dimensionless, scaled units).
#pragma once

#include <Eigen/Core>

#include "analysis/equilibrium_problem.hpp"
#include "analysis/group_passes.hpp"
#include "analysis/interior_point.hpp"
#include "analysis/interior_point_iterate.hpp"
#include "analysis/twin_groups.hpp"

namespace ashlar {

class IterateResiduals {
public:
  // For `problem` (the groups worked on); every reference must outlive this.
  IterateResiduals(const EquilibriumProblem& problem, const InequalityRows& inequality, const TwinGroups& twins,
                   GroupPasses& passes);

  // Fills r.x and r.y at `iterate`, and info's primal and dual
  // residuals and complementarity (the mean w_i z_i); returns the total
  // duality gap w^T z. D: balance rows per body.
  template <int D>
  double measure(const InteriorPointSolution& iterate, NewtonVectors& r, InteriorPointInfo& info);
  // The scaled error of an iterate measured so (`info`, `duality_gap`), the
  // gap relative to objective_floor + |objective at x|.
  double scaled_error(const InteriorPointInfo& info, double duality_gap, double objective_floor,
                      const Eigen::VectorXd& x) const;
  // The QP's objective at x (scaled).
  double objective(const Eigen::VectorXd& x) const;
  // What the dual residual is measured against: 1 + the largest linear term.
  double dual_scale() const { return dual_scale_; }

private:
  // The largest dual residual of a twin: a class of m twins has m times
  // each twin's.
  double dual_residual(const Eigen::VectorXd& residual) const;

  const EquilibriumProblem& problem_;
  const InequalityRows& inequality_;
  const TwinGroups& twins_;
  GroupPasses& passes_;
  double rhs_scale_ = 1.0;
  double dual_scale_ = 1.0;
};

}  // namespace ashlar
