// One force group's block of the interior-point Newton system after its
// slacks are eliminated, kept as a triangular factor:
//
//     Phi = diag(hessian) + G^T diag(z / w) G = R^T R        (4 x 4)
//
// with hessian the group's diagonal Hessian (4, scaled), G its inequality
// rows (rows x 4) and z / w one barrier scaling per row. The solver
// (interior_point.hpp) multiplies by Phi^-1 only through R: solve_phi for a
// group's direction, divide_by_factor for its share of the normal matrix
// A Phi^-1 A^T (normal_matrix.hpp). Header-only: these run millions of
// times inside the per-group passes and must inline there.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace ashlar {

// A group's factor R of Phi = R^T R (4 x 4 upper triangular), its 10
// entries packed by rows, diagonal stored inverted: 80 bytes a group
// instead of a full matrix's 128 (100 MB less on a 100,052-block vault).
struct PhiFactor {
  double packed[10];
  double& operator()(int i, int j) { return packed[i * (7 - i) / 2 + j]; }
  double operator()(int i, int j) const { return packed[i * (7 - i) / 2 + j]; }
};

// A group's inequality rows G (rows x 4).
using GroupRowsMatrix = Eigen::Matrix<double, Eigen::Dynamic, 4>;

// Phi = diag(hessian) + G^T diag(scaling) G as R^T R. Forming Phi itself
// would not do: near the optimum scaling spreads from 1e-13 to 1e13, and
// adding 1e13 g g^T rounds away the regularisation (1e-6) in the
// directions that stay free, which are the very directions Phi^-1 is
// about. Instead each row scaling_i g_i g_i^T is added to Phi = L D L^T (L
// unit lower triangular, D = diag(hessian) at first) as a positive
// rank-one update (Gill, Golub, Murray & Saunders 1974, method C1): what a
// large row adds is absorbed into its pivot and L's column, and only what
// remains, of the free directions' size, reaches the later pivots, as with
// Givens rotations of R, which this replaced: one division per nonzero
// instead of a square root and a division (the group factorisations were
// 13 % of an important-weights run). Then R = D^(1/2) L^T, its diagonal
// stored inverted: the solves below multiply by it.
inline PhiFactor factor_phi(const Eigen::Vector4d& hessian, const GroupRowsMatrix& rows,
                            const Eigen::Ref<const Eigen::VectorXd>& scaling) {
  Eigen::Vector4d d = hessian;
  double lower[4][4] = {};  // L below the diagonal, lower[l][j] for l > j
  for (Eigen::Index i = 0; i < rows.rows(); ++i) {
    Eigen::Vector4d v = rows.row(i).transpose();
    // alpha: the weight of what is left of the row. It is spent (0) once a
    // pivot with no Hessian takes it all; a NaN scaling goes on into the
    // factor, where the solver's checks stop the solve.
    double alpha = scaling(i);
    for (int j = 0; j < 4 && alpha != 0.0; ++j) {
      const double p = v(j);
      if (p == 0.0) continue;
      const double pivot = d(j) + alpha * p * p;
      const double inverse = 1.0 / pivot;  // one division, not two
      const double beta = alpha * p * inverse;
      alpha *= d(j) * inverse;
      d(j) = pivot;
      for (int l = j + 1; l < 4; ++l) {
        v(l) -= p * lower[l][j];
        lower[l][j] += beta * v(l);
      }
    }
  }
  PhiFactor r{};
  for (int j = 0; j < 4; ++j) {
    const double root = std::sqrt(d(j));
    r(j, j) = 1.0 / root;
    for (int l = j + 1; l < 4; ++l) r(j, l) = root * lower[l][j];
  }
  return r;
}

// Phi^-1 v for Phi = R^T R (R from factor_phi): two triangular solves,
// never Phi^-1 itself (whose product with v would round the stiff
// directions' tiny components to the size of the free ones). Inlined into
// the per-group passes, where a chain of dependent steps of one group
// overlaps the next group's work: important weights on one core 10.75 s
// -> 10.2 s.
[[gnu::always_inline]] inline Eigen::Vector4d solve_phi(const PhiFactor& r, Eigen::Vector4d v) {
  v(0) *= r(0, 0);  // R^T t = v
  v(1) = (v(1) - r(0, 1) * v(0)) * r(1, 1);
  v(2) = (v(2) - r(0, 2) * v(0) - r(1, 2) * v(1)) * r(2, 2);
  v(3) = (v(3) - r(0, 3) * v(0) - r(1, 3) * v(1) - r(2, 3) * v(2)) * r(3, 3);
  v(3) *= r(3, 3);  // R u = t
  v(2) = (v(2) - r(2, 3) * v(3)) * r(2, 2);
  v(1) = (v(1) - r(1, 2) * v(2) - r(1, 3) * v(3)) * r(1, 1);
  v(0) = (v(0) - r(0, 1) * v(1) - r(0, 2) * v(2) - r(0, 3) * v(3)) * r(0, 0);
  return v;
}

// A R^-1 for a D x 4 matrix A (a group's effect on one body's D balance
// rows): A Phi^-1 A^T = (A R^-1)(A R^-1)^T.
template <int D>
Eigen::Matrix<double, D, 4> divide_by_factor(const Eigen::Matrix<double, D, 4>& a, const PhiFactor& r) {
  Eigen::Matrix<double, D, 4> out = a;
  for (int j = 0; j < 4; ++j) {
    for (int l = 0; l < j; ++l) out.col(j) -= r(l, j) * out.col(l);
    out.col(j) *= r(j, j);
  }
  return out;
}

}  // namespace ashlar
