// A semismooth Newton method for one step's contact problem (the laws of
// contact_solver.hpp), for the steps projected Gauss-Seidel does not
// finish: where the load cycles between the redundant points of a face
// (four corners, three independent) or between points sliding at their
// friction limit, whose friction and pressure are tied through the
// blocks' rotation, the sweeps stall a few times above the tolerance.
//
// The laws are written as the zero of Alart and Curnier's function (Alart
// and Curnier 1991; Christensen, Klarbring, Pang and Stromberg 1998),
// per row k, in velocity units (m/s), with u = U - (target_n, 0, 0):
//   F_n = (P_n - max(0, P_n - rho_n u_n)) / rho_n
//   F_t = (P_t - proj_D(P_t - rho_t u_t)) / rho_t,
//     D the disc of radius mu max(0, P_n - rho_n u_n),
// with rho_n = 1 / W_nn and rho_t = 1 / the largest eigenvalue of W_tt
// (the sweeps' step sizes; W = J M^-1 J^T the row's Delassus block). F is
// zero exactly when the row's laws hold. Each iteration solves the
// generalised Jacobian's linear system per row's state (open: dP = -P;
// pressed and sticking: du = -u; pressed and sliding: du_n = -u_n and the
// slip direction's linearisation) together with the bodies' equations
// dv = M^-1 J^T dP, one sparse system in the bodies' velocities and the
// rows' impulses (6 unknowns per free body, 3 per row: its size is linear
// in the model), factored by a sparse LU. The redundant points make it
// singular; a proximal term eps_c dP_c on each row's equations (eps_c a
// Levenberg-Marquardt damping times W_cc, of the order of |F| and raised
// when the line search has to cut a step) keeps it solvable without
// moving the solution (it vanishes with dP). A backtracking line search
// on |F|^2 takes the step. A step of more than 1,000 rows is solved on a
// part of it (a sparse LU of the whole step's problem each iteration cost
// seconds on 4,700 rows): the rows whose |F_k| is above the tolerance,
// from the worst down, each with every row at its free bodies, up to
// 200 rows; the other rows' impulses are held.
#pragma once

#include <vector>

#include "dynamics/contact_solver.hpp"

namespace ashlar {

struct ContactNewtonReport {
  int iterations = 0;       // Newton iterations (one sparse LU each)
  double largest = 0.0;     // the largest |F_k| of the rows as left (m/s)
};

// Iterates on rows and bodies (impulses and the velocities they give, as
// ContactSolver::solve keeps them) until every row's |F_k| is at most
// `tolerance` (m/s), `max_iterations` iterations, or a stall (|F|_max
// down by less than 1 % in 5 iterations). The impulses and velocities
// are left at the last iterate when its largest |F_k| is below the
// start's, else as they came. The impulses are not projected on their
// cones (at F = 0 they are in them). Past 1,000 rows, all of this holds
// of the part solved (see above), and `largest` is the part's.
ContactNewtonReport solve_contact_newton(std::vector<ContactRow>& rows, BodyVelocities& bodies, double tolerance,
                                         int max_iterations);

}  // namespace ashlar
