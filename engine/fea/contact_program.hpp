// The FEA's unilateral contact problem as an interior-point program
// (IPOPT), for when the active-set iteration in fea.cpp wanders:
//
//   minimise    1/2 u^T K u - f^T u
//   subject to  t1_k . g_k(u) = 0,  t2_k . g_k(u) = 0,  s_k n_k . g_k(u) >= 0
//               -bound <= u_i <= bound
//
// g_k(u) = sum_j w_kj u_(node kj): tie k's relative displacement (own node
// minus the point it touches); n_k, t1_k, t2_k its interface's normal and
// tangents; s_k = +1 when the tie's node is on the interface's block b, -1
// on a (so s_k n_k . g_k is the opening). The interior-point method does
// not depend on guessing which nodes open, so it finds the solution where
// the active-set iteration cycles; the bound makes the program bounded when
// the structure is a mechanism, whose displacements then reach it.
//
// Only fea.cpp uses this; IPOPT's headers stay in contact_program.cpp.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "core/types.hpp"

namespace ashlar {

// One tie, as the program sees it.
struct ContactRow {
  std::vector<int> nodes;        // the tie's own node first, then the nodes of the point it touches
  std::vector<double> weights;   // 1, then minus the interpolation weights
  Vec3 normal, tangent1, tangent2;
  double side = 1.0;             // s_k
};

struct ContactProgramResult {
  bool solved = false;       // IPOPT reached its tolerance (or an acceptable level)
  bool interrupted = false;  // Ctrl-C, SIGTERM or a deadline (core/interrupt.hpp)
  int iterations = 0;
  Eigen::VectorXd displacements;      // 3 per node, m
  std::vector<double> normal_forces;  // per row, N: the opening constraint's multiplier, >= 0
};

// stiffness: K's upper triangle (N/m), n x n with n = 3 x nodes; loads: f
// (N); bound (m): on every displacement component; displacement_scale (m)
// and force_scale (N): typical sizes (the all-tied solve's largest
// displacement, the total weight), so that IPOPT works on O(1) numbers;
// start: displacements to start from (m), e.g. the all-tied solve's.
ContactProgramResult solve_contact_program(const Eigen::SparseMatrix<double, Eigen::ColMajor, int>& stiffness,
                                           const Eigen::VectorXd& loads, const std::vector<ContactRow>& rows,
                                           double bound, double displacement_scale, double force_scale,
                                           const Eigen::VectorXd& start);

}  // namespace ashlar
