// Where the interior-point iterations (interior_point.hpp) start, and how
// far each step goes: the starting point (warm or cold, then Mehrotra's
// heuristic), the predictor-corrector's centring, and the primal and dual
// step lengths along a Newton direction (newton_system.hpp). Iterates and
// directions are shaped as in interior_point_iterate.hpp (scaled units).
#pragma once

#include <Eigen/Core>

#include "analysis/equilibrium_problem.hpp"
#include "analysis/interior_point_iterate.hpp"

namespace ashlar {

// Lengths of one step: x and w move by primal times their direction, y and
// z by dual times theirs.
struct StepLengths {
  double primal = 0.0, dual = 0.0;
};

// Largest step in (0, 1] keeping v + step * dv >= 0; NaN if dv is not
// finite (a direction that must not be taken).
double step_to_boundary(const Eigen::VectorXd& v, const Eigen::VectorXd& dv);

// The first iterate of `problem` with `balance_rows` rows: from `iterate`
// itself when `warm` (its slacks recomputed from x, both w and z moved
// strictly inside the cone), else x = 0, y = 0, w = z = 1 (the point
// Mehrotra's start, take_mehrotra_start, moves from).
void start_iterate(const EquilibriumProblem& problem, const InequalityRows& inequality, int balance_rows, bool warm,
                   InteriorPointSolution& iterate);

// Mehrotra's starting point from the cold start and its affine direction.
void take_mehrotra_start(const NewtonVectors& affine, InteriorPointSolution& iterate);

// Mehrotra's corrector, whose complementarity part of the Newton
// right-hand side is w z + dw_aff dz_aff - sigma mu: sigma mu, with the
// centring sigma from how far the affine direction `affine` can go (mu:
// the iterate's mean complementarity).
double corrector_centring(const InteriorPointSolution& iterate, const NewtonVectors& affine, double mu);

// The primal and dual step lengths along `direction` from `iterate`, a
// fraction `step_fraction` of the way to the boundary; `error` is the
// iterate's scaled error and `dual_scale` what dual residuals are measured
// against. False when no step can be taken (a direction that is not finite
// or a vanishing step).
bool choose_step_lengths(const EquilibriumProblem& problem, const InteriorPointSolution& iterate,
                         const NewtonVectors& direction, double step_fraction, double error, double dual_scale,
                         StepLengths& lengths);

// iterate += the step `lengths` along `direction`.
void take_step(const NewtonVectors& direction, const StepLengths& lengths, InteriorPointSolution& iterate);

}  // namespace ashlar
