#include "analysis/newton_system.hpp"

#include <algorithm>

namespace ashlar {

template <int D>
NewtonSystem<D>::NewtonSystem(const EquilibriumProblem& problem, const InequalityRows& inequality,
                              const TwinGroups& twins, NormalMatrix& normal, GroupPasses& passes,
                              const InteriorPointSolution& iterate)
    : problem_(problem),
      inequality_(inequality),
      twins_(twins),
      normal_(normal),
      passes_(passes),
      iterate_(iterate),
      phi_factors_(problem.groups.size()),
      rhs_(normal.rows()),
      error_(NewtonVectors::sized(static_cast<int>(problem.groups.size()), normal.rows(), inequality.total())) {}

template <int D>
void NewtonSystem<D>::assemble() {
  normal_.assemble<D>(problem_, inequality_.first, iterate_.w, iterate_.z, twins_, phi_factors_);
}

template <int D>
void NewtonSystem<D>::solve(NewtonVectors& v) {
  const Eigen::VectorXd& w = iterate_.w;
  const Eigen::VectorXd& z = iterate_.z;
  const InequalityRows& ineq = inequality_;
  rhs_ = -v.y;
  passes_.each_into(rhs_, [&](int k, Eigen::VectorXd& rows) {
    // Per inequality row (c + Z g) / W, combined as G^T (...).
    GroupRowsVector per_row =
        (ineq.of(v.z, k) + ineq.of(z, k).cwiseProduct(ineq.of(v.w, k))).cwiseQuotient(ineq.of(w, k));
    const Eigen::Vector4d reduced =
        -v.x.template segment<4>(4 * k) - problem_.rules_of(problem_.groups[k]).rows.transpose() * per_row;
    const Eigen::Vector4d t = solve_phi(phi_factors_[k], reduced);
    v.x.template segment<4>(4 * k) = t;  // dx, completed below with the A^T dy part
    add_group_effect<D>(problem_.groups[k], -t, rows);
  });
  normal_.solve(rhs_, v.y);
  passes_.each([&](int k) {
    v.x.template segment<4>(4 * k) += solve_phi(phi_factors_[k], group_reaction<D>(problem_.groups[k], v.y));
    // dw = G dx + g
    ineq.of(v.w, k).noalias() += problem_.rules_of(problem_.groups[k]).rows * v.x.template segment<4>(4 * k);
  });
  v.z = -(v.z + z.cwiseProduct(v.w)).cwiseQuotient(w);
}

// Computed from the problem's data (not from phi_factors_), so that
// solving for it corrects the rounding of the elimination.
template <int D>
void NewtonSystem<D>::residual(const NewtonVectors& e, const NewtonVectors& dir, NewtonVectors& out) {
  const InequalityRows& ineq = inequality_;
  out.y = e.y;
  passes_.each_into(out.y, [&](int k, Eigen::VectorXd& rows) {
    const ForceGroup& v = problem_.groups[k];
    const GroupRules& rules = problem_.rules_of(v);
    const Eigen::Vector4d dxk = dir.x.template segment<4>(4 * k);
    add_group_effect<D>(v, dxk, rows);
    out.x.template segment<4>(4 * k) = e.x.template segment<4>(4 * k) +
                                       twins_.count(k) * rules.hessian.cwiseProduct(dxk) -
                                       group_reaction<D>(v, dir.y) - rules.rows.transpose() * ineq.of(dir.z, k);
    ineq.of(out.w, k) = ineq.of(e.w, k) - ineq.of(dir.w, k);
    ineq.of(out.w, k).noalias() += rules.rows * dxk;
  });
  out.z = e.z + iterate_.z.cwiseProduct(dir.w) + iterate_.w.cwiseProduct(dir.z);
}

// Iterative refinement: near the optimum z / w spreads over twenty orders
// of magnitude and the elimination loses digits (its residual is about
// 1e-11 on a 10,000-block wall); left alone, that error would stop the
// iterations short of the tolerance. Far from the optimum it is negligible
// beside the iterate's own error, and the check (a pass over every group)
// is skipped.
template <int D>
void NewtonSystem<D>::direction(const NewtonVectors& e, NewtonVectors& out, double iterate_error) {
  constexpr int kRefinements = 3;
  constexpr double kRefineBelow = 1e-4;
  out = e;  // same sizes: no allocation
  solve(out);
  const double target = std::max(1e-14 * e.largest(), 1e-2 * iterate_error);
  double previous = std::numeric_limits<double>::infinity();
  for (int refinement = 0; refinement < kRefinements && iterate_error <= kRefineBelow; ++refinement) {
    residual(e, out, error_);
    const double size = error_.largest();
    if (size <= target || size >= 0.5 * previous) break;
    previous = size;
    solve(error_);  // now the correction
    out.x += error_.x;
    out.y += error_.y;
    out.w += error_.w;
    out.z += error_.z;
  }
}

template class NewtonSystem<3>;
template class NewtonSystem<6>;

}  // namespace ashlar
