// An interior-point method for one step's contact problem (the laws of
// contact_solver.hpp), for the steps that projected Gauss-Seidel and
// Newton's method do not finish: a wall shaken past its load factor,
// where a mechanism of many blocks slides and rocks on many joints at
// once, stalled hundreds of tolerances above its answer after thousands of
// sweeps.
//
// Coulomb's law at velocity level is written, after De Saxce and Feng
// (1991), as a cone complementarity problem in the modified relative
// velocity: per row, with u the relative velocity (contact frame) and
// s = mu |u_t|,
//   P in K = { mu P_n >= |P_t| },  U = (u_n - target_n + s, u_t) in K*,  P . U = 0,
// K* = { U_n >= mu |U_t| } the dual cone. With s held, this is the
// optimality system of a convex second-order cone program in the bodies'
// velocities v,
//   minimise 1/2 (v - v_free)^T M (v - v_free)  over  J v + e in K*,
// whose multipliers are the impulses. It is solved by a primal-dual
// interior-point method (Nesterov-Todd scaling, Mehrotra's predictor and
// corrector; Vandenberghe 2010, "The CVXOPT linear and quadratic cone
// program solvers"); each iteration solves the bodies' system
// (M + J^T S J) dv = r, S a 3 x 3 block per row, by a sparse Cholesky
// factorisation (6 unknowns per free body). The shift s is then taken
// again from the answer's slips, and the cone program solved again from
// its answer (a fixed point on s; Acary, Bremond and Huber 2018, "On
// solving contact problems with Coulomb friction: formulations and
// numerical comparisons"), until Coulomb's law holds (each row's residual
// of contact_solver.hpp within the tolerance) or the fixed point stalls.
//
// Rows of zero or infinite friction are not of this form (their cone has
// no interior): a step with such a row is left as it came.
#pragma once

#include <vector>

#include "dynamics/contact_solver.hpp"

namespace ashlar {

struct ContactInteriorReport {
  int fixed_point_iterations = 0;  // cone programs solved
  int iterations = 0;              // interior-point iterations in all (one factorisation each)
  double largest = 0.0;            // the largest row residual (m/s) as left
  bool improved = false;           // the impulses and velocities were changed
};

// Solves the rows of a step whose bodies' velocities hold their impulses
// applied (as ContactSolver::solve keeps them), until every row's residual
// is at most `tolerance` (m/s), the shift moves by less than a tenth of it
// in a round, or `max_fixed_point` cone programs. The impulses and
// velocities are left at the round's answer of least residual when that is
// below the start's, else as they came. An interior point's impulses are
// never on their cones' boundary: the residuals count a row a sweep's pass
// would open as open, and friction it would put on its limit as on it.
// s: the fixed point's shift per row (m/s), in and out; one of another
// size than the rows starts at zero. A caller that calls again on the
// same step passes it back to go on with the fixed point.
ContactInteriorReport solve_contact_interior(std::vector<ContactRow>& rows, BodyVelocities& bodies,
                                             double tolerance, int max_fixed_point, std::vector<double>& s);

}  // namespace ashlar
