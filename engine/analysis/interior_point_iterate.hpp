// The shapes the interior-point solver (interior_point.hpp) works in.
//
// For a problem of n force groups and r balance rows (scaled units):
//   x  4 n   the groups' unknowns (forces)
//   y  r     the balance rows' multipliers
//   w  m     the inequality rows' slacks (G x - lower, >= 0)
//   z  m     the inequality rows' multipliers (>= 0)
// with m the inequality rows of all groups, group k's rows at
// [first[k], first[k + 1]) of w and z (InequalityRows).
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <utility>
#include <vector>

#include "analysis/equilibrium_problem.hpp"

namespace ashlar {

// Primal x (4 per force group, scaled), equality multipliers y, inequality
// slacks w and multipliers z (the group's rule rows per group, in order).
struct InteriorPointIterate {
  Eigen::VectorXd x, y, w, z;
};

// An iterate, and where a warm start from it begins.
struct InteriorPointSolution : InteriorPointIterate {
  // When the solve finished by the active-set polish (interior_point.cpp):
  // the interior iterate it polished, from which a warm start begins (the
  // polished point is a vertex of the optimal face, and a solve started
  // next to it is started on the boundary: a 512-voussoir arch's
  // thickness search from polished points took 62 iterations where 28 and
  // stopped at max_iterations on a stable arch). Empty otherwise.
  InteriorPointIterate interior;
};

// Where a warm start from `solution` begins.
inline const InteriorPointIterate& starting_point(const InteriorPointSolution& solution) {
  return solution.interior.x.size() > 0 ? solution.interior : solution;
}

// Where each group's inequality rows sit in w and z.
struct InequalityRows {
  std::vector<int> first;  // group k's rows from first[k]; first.back(): all of them (m)

  int total() const { return first.back(); }
  // Group k's rows of a vector shaped like w or z.
  template <typename Vector>
  auto of(Vector& v, int k) const {
    return v.segment(first[k], first[k + 1] - first[k]);
  }
};

// Inequality rows of one group at most: compression, tension and a
// friction pyramid of up to 1024 sides.
constexpr int kMaxGroupRows = 2 + 1024;
// One value per inequality row of a group, on the stack: the per-group
// passes run millions of times and must not allocate.
using GroupRowsVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxGroupRows, 1>;

// The constant sides of group k's inequality rows (G x_k >= lower) are 0
// but for groups with bounds (a bounded cable's row, friction with a given
// strength): this turns `rows` = G x_k into G x_k - lower.
template <typename Rows>
void subtract_lower_bound(const EquilibriumProblem& problem, int k, Rows&& rows) {
  const GroupRules& rules = problem.rules_of(problem.groups[k]);
  if (rules.bound_coefficients.size()) rows += problem.groups[k].bound * rules.bound_coefficients;
}

// Group k's slack residual at `iterate`: G x_k - lower - w_k. G x_k as
// one expression over G's four columns: Eigen's general product for a few
// rows by 4 was most of this function's time.
inline GroupRowsVector slack_residual_of(const EquilibriumProblem& problem, const InequalityRows& inequality,
                                         const InteriorPointSolution& iterate, int k) {
  const auto& g = problem.rules_of(problem.groups[k]).rows;
  const auto x = iterate.x.segment<4>(4 * k);
  GroupRowsVector out = g.col(0) * x(0) + g.col(1) * x(1) + g.col(2) * x(2) + g.col(3) * x(3) -
                        inequality.of(iterate.w, k);
  subtract_lower_bound(problem, k, out);
  return out;
}

// Four vectors shaped like the unknowns: x (4 per group), y (one per balance
// row), w and z (one per inequality row). As a direction: (dx, dy, dw, dz).
// As the right-hand side or the residual of the Newton system, in the same
// shape:
//   H dx - A^T dy - G^T dz = -x,   A dx = -y,   G dx - dw = -w,   Z dw + W dz = -z
// (x: the dual residual, y: the balance rows', w: the slacks', z: the
// complementarity), where the solver keeps only x and y (w and z empty:
// NewtonSystem makes them group by group). One shape for both lets a
// solve overwrite its right-hand side with its direction.
struct NewtonVectors {
  Eigen::VectorXd x, y, w, z;

  // Uninitialised vectors for `groups` groups, `balance_rows` balance rows
  // and `inequality_rows` inequality rows.
  static NewtonVectors sized(int groups, int balance_rows, int inequality_rows) {
    return {Eigen::VectorXd(4 * groups), Eigen::VectorXd(balance_rows), Eigen::VectorXd(inequality_rows),
            Eigen::VectorXd(inequality_rows)};
  }
  // The largest magnitude of any entry.
  double largest() const {
    double m = 0.0;
    for (const Eigen::VectorXd* part : {&x, &y, &w, &z}) {
      if (part->size()) m = std::max(m, part->lpNorm<Eigen::Infinity>());
    }
    return m;
  }
};

}  // namespace ashlar
