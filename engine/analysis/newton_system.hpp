// The Newton system of one interior-point iterate (interior_point.hpp):
//
//   H dx - A^T dy - G^T dz = -e.x      (4 per group: H diagonal, scaled)
//   A dx                   = -e.y      (balance rows)
//   G dx - dw              = -e.w      (inequality rows)
//   Z dw + W dz            = -e.z      (inequality rows; W, Z = diag(w, z))
//
// with (w, z) the iterate's slacks and multipliers and e any right-hand
// side in NewtonVectors' shape. Eliminating dz and dw row by row, then
// each group's dx (Phi = H + G^T Z W^-1 G, phi_factor.hpp), leaves the
// normal equations A Phi^-1 A^T dy = ... (normal_matrix.hpp), whose one
// factorisation per iteration serves the predictor, the corrector and
// their refinements.
//
// D: balance rows per body (6, or 3 planar), at compile time.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <vector>

#include "analysis/equilibrium_problem.hpp"
#include "analysis/group_passes.hpp"
#include "analysis/interior_point_iterate.hpp"
#include "analysis/normal_matrix.hpp"
#include "analysis/phi_factor.hpp"
#include "analysis/twin_groups.hpp"

namespace ashlar {

template <int D>
class NewtonSystem {
public:
  // The system of `problem` (the groups worked on, twins merged or not) at
  // `iterate`, whose w and z it reads at every call: they must not change
  // between factor() and the direction() calls that use it. Every
  // reference must outlive this.
  NewtonSystem(const EquilibriumProblem& problem, const InequalityRows& inequality, const TwinGroups& twins,
               NormalMatrix& normal, GroupPasses& passes, const InteriorPointSolution& iterate);

  // Eliminates every group's unknowns at the iterate and fills the normal
  // matrix.
  void assemble();
  // Factorises it; false when that fails (numerically not positive definite).
  bool factor() { return normal_.factorize_shifted(); }

  // The complementarity part of a right-hand side: the predictor's w z,
  // or the corrector's w z + dw_aff dz_aff - centring (step_policy.hpp's
  // corrector_centring), with (dw_aff, dz_aff) the predictor's direction.
  struct Complementarity {
    bool corrector = false;
    double centring = 0.0;
  };
  // The Newton direction into `out` for the right-hand side whose x and y
  // parts are `e`'s (the iterate's residuals, iterate_residuals.hpp), w
  // part the iterate's slack residual G x - lower - w, and z part
  // `complementarity`; for the corrector `out` holds the predictor's
  // direction on entry. The last two parts are computed group by group as
  // the solve goes, never stored (two inequality-sized vectors: 115 MB on
  // a 100,052-block vault). With iterative refinement when the iterate's
  // scaled error `iterate_error` is small enough for the elimination's
  // rounding to matter (kNoRefinement: never).
  void direction(const NewtonVectors& e, Complementarity complementarity, NewtonVectors& out,
                 double iterate_error);
  static constexpr double kNoRefinement = std::numeric_limits<double>::infinity();

private:
  // Solves in place: `v` holds the right-hand side's x and y parts on
  // entry and the direction on return. Its w and z parts are those of
  // direction(), or with `complementarity` null 0 (v.w and v.z empty: only
  // dx and dy computed).
  void solve(NewtonVectors& v, const Complementarity* complementarity);
  // How far `dir` is from solving the first two equations for `e`: its
  // largest magnitude, the y part into out.y and, with `store_x`, the x
  // part into out.x.
  double residual(const NewtonVectors& e, const NewtonVectors& dir, NewtonVectors& out, bool store_x);

  const EquilibriumProblem& problem_;
  const InequalityRows& inequality_;
  const TwinGroups& twins_;
  NormalMatrix& normal_;
  GroupPasses& passes_;
  const InteriorPointSolution& iterate_;
  std::vector<PhiFactor> phi_factors_;  // per group, at the last assemble()
  Eigen::VectorXd rhs_;                 // the normal equations' right-hand side
  // x, y: a direction's residual, then its correction; x sized at the
  // first refinement that solves (none of the 100,052-block vault's: 38 MB
  // of its peak).
  NewtonVectors error_;
};

extern template class NewtonSystem<3>;
extern template class NewtonSystem<6>;

}  // namespace ashlar
