// Coupled rigid-block analysis (CRA; Kao, Iannuzzo, Thomaszewski, Coros,
// Van Mele and Block, "Coupled Rigid-Block Analysis: Stability-Aware
// Design of Complex Discrete-Element Assemblies", Computer-Aided Design 146,
// 2022, eq. 11 and its penalty form), solved with IPOPT.
//
// Rigid-block equilibrium alone may rely on forces no motion could
// mobilise; CRA couples the forces with a virtual displacement of the
// blocks. On the structure's interfaces (Structure::interfaces under the
// contact options), with the contact vertices and interface frames of the
// equilibrium QP (equilibrium_problem.hpp: n from block a into block b,
// tangents u, v), the unknowns are, in scaled units (forces in mean block
// weights Wm, lengths in mean block sizes L):
//   per contact vertex k   f_k = (f_n, f_u, f_v)   force on b from a, f_n >= 0
//                          (cra_penalty: f_n = f+ - f-, f+, f- >= 0)
//                          d_k = (d_n, d_u, d_v)   b's displacement relative to a there
//                          alpha_k >= 0            friction-sliding alignment factor
//   per analysed block     q = (t / L, theta)      virtual translation and small rotation
//                          (3 in a planar problem: t_x, t_z, theta_y)
// and the program is
//   minimise   sum_k f_n^2 + alpha_k^2           (cra_penalty: f+^2 + w f-^2 + alpha^2)
//   subject to A f = p                  balance of every free block (the QP's rows)
//              d = A^T q                linearised compatibility at every vertex
//              friction rows (f_n, f_u, f_v) >= 0      (cra_penalty: on f+)
//              -eps <= d_n,  |d_n|, |d_u|, |d_v| <= d_bnd   no penetration beyond eps
//              f_n (d_n + eps) = 0      (cra_penalty: f+ (d_n + eps) = 0, f+ f- = 0),
//                                       given to IPOPT as "<= 0" (the same set, as both
//                                       factors are >= 0, but one-sided); cra relaxes it
//                                       to <= kappa eps (CraSettings::complementarity, 0
//                                       by default), which large hyperstatic assemblies need
//              (f_u, f_v) = -alpha_k (d_u, d_v)   friction against the sliding
// with eps = CraSettings::overlap and d_bnd = displacement_bound (both in L).
// Friction is bounded by the equilibrium QP's rows: the pyramid of
// friction_sides sides inscribed in the Coulomb cone (or the box), where
// compas_cra uses a circumscribed octagon; friction_sides = 8 comes closest
// on the safe side.
//
// Verdict: stable when IPOPT solved the program (status converged, or
// inaccurate at 100 x tolerance) and its forces, tension dropped, balance
// every block within stable_tolerance by the equilibrium method's own test
// (compression_only_imbalance). For cra an infeasible program (status
// infeasible) means unstable; for cra_penalty the tension left does. The
// displacement is not the verdict: friction that acts pushes the sliding it
// opposes to d_bnd (alpha is minimised), and compressed vertices sit at
// d_n = -eps, in stable structures too. An unstable cra_penalty answer's
// displacement shows how the structure starts to fail.
//
// Cost: IPOPT (MUMPS) on 7 (cra_penalty: 8) unknowns per contact vertex
// plus 6 per block, sparse Jacobian and Hessian; tens to hundreds of
// iterations, each a sparse indefinite factorisation.
#pragma once

#include "analysis/equilibrium.hpp"

namespace ashlar {

// Runs CRA (settings.method cra or cra_penalty) on `structure`. Result:
// forces in the fields the equilibrium method fills (vertex_forces as
// (c, s, f_u, f_v) in N, s = f- for cra_penalty, interfaces, block_tension),
// the displacements (m, rad), status, iterations (IPOPT's), seconds.
// infeasibility: 0 when stable; cra_penalty: the tension left over the total
// weight; cra: infinite when infeasible, else the imbalance without tension.
// penalty and objective: IPOPT's optimum (scaled). Throws InvalidArgument
// for bad settings, for a method other than cra / cra_penalty, and for a
// structure with cables (CRA models contacts only). Interrupts
// (stop_requested) end the solve with status interrupted and no verdict.
EquilibriumResult analyze_cra(const Structure& structure, const AnalysisSettings& settings);

// Throws InvalidArgument, naming the setting and its value, unless the CRA
// settings are in range.
void check_cra_settings(const CraSettings& settings);

}  // namespace ashlar
