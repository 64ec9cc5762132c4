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
      rhs_(normal.rows()) {}

template <int D>
void NewtonSystem<D>::assemble() {
  normal_.assemble<D>(problem_, inequality_.first, iterate_.w, iterate_.z, twins_, phi_factors_);
}

template <int D>
void NewtonSystem<D>::solve(NewtonVectors& v, const Complementarity* complementarity) {
  const Eigen::VectorXd& w = iterate_.w;
  const Eigen::VectorXd& z = iterate_.z;
  const InequalityRows& ineq = inequality_;
  rhs_ = -v.y;
  passes_.each_into(rhs_, [&](int k, Eigen::VectorXd& rows) {
    Eigen::Vector4d reduced = -v.x.template segment<4>(4 * k);
    if (complementarity) {
      // The group's e.w and e.z, into v's rows (the corrector's read the
      // predictor's direction there first).
      auto ew = ineq.of(v.w, k);
      auto ez = ineq.of(v.z, k);
      const GroupRowsVector wz = ineq.of(w, k).cwiseProduct(ineq.of(z, k));
      if (complementarity->corrector) {
        ez = wz + ew.cwiseProduct(ez) - GroupRowsVector::Constant(ez.size(), complementarity->centring);
      } else {
        ez = wz;
      }
      ew = slack_residual_of(problem_, ineq, iterate_, k);
      // Per inequality row (c + Z g) / W, combined as G^T (...).
      const GroupRowsVector per_row = (ez + ineq.of(z, k).cwiseProduct(ew)).cwiseQuotient(ineq.of(w, k));
      reduced.noalias() -= problem_.rules_of(problem_.groups[k]).rows.transpose() * per_row;
    }
    const Eigen::Vector4d t = solve_phi(phi_factors_[k], reduced);
    v.x.template segment<4>(4 * k) = t;  // dx, completed below with the A^T dy part
    add_group_effect<D>(problem_.groups[k], -t, rows);
  });
  normal_.solve(rhs_, v.y);
  passes_.each([&](int k) {
    v.x.template segment<4>(4 * k) += solve_phi(phi_factors_[k], group_reaction<D>(problem_.groups[k], v.y));
    if (complementarity) {
      // dw = G dx + e.w, dz = -(e.z + Z dw) / W
      auto dw = ineq.of(v.w, k);
      dw.noalias() += problem_.rules_of(problem_.groups[k]).rows * v.x.template segment<4>(4 * k);
      ineq.of(v.z, k) = -(ineq.of(v.z, k) + ineq.of(z, k).cwiseProduct(dw)).cwiseQuotient(ineq.of(w, k));
    }
  });
}

// Computed from the problem's data (not from phi_factors_), so that
// solving for it corrects the rounding of the elimination. Only the x and
// y parts: `dir`'s dw and dz are computed from its dx row by row (solve()),
// so the last two equations hold to the rounding of one row's product.
template <int D>
double NewtonSystem<D>::residual(const NewtonVectors& e, const NewtonVectors& dir, NewtonVectors& out,
                                 bool store_x) {
  const InequalityRows& ineq = inequality_;
  out.y = e.y;
  const double x_largest = passes_.largest_into(out.y, [&](int k, Eigen::VectorXd& rows) {
    const ForceGroup& v = problem_.groups[k];
    const GroupRules& rules = problem_.rules_of(v);
    const Eigen::Vector4d dxk = dir.x.template segment<4>(4 * k);
    add_group_effect<D>(v, dxk, rows);
    const Eigen::Vector4d rx = e.x.template segment<4>(4 * k) + twins_.count(k) * rules.hessian.cwiseProduct(dxk) -
                               group_reaction<D>(v, dir.y) - rules.rows.transpose() * ineq.of(dir.z, k);
    if (store_x) out.x.template segment<4>(4 * k) = rx;
    return rx.template lpNorm<Eigen::Infinity>();
  });
  return std::max(x_largest, out.y.size() ? out.y.template lpNorm<Eigen::Infinity>() : 0.0);
}

// Iterative refinement: near the optimum z / w spreads over twenty orders
// of magnitude and the elimination loses digits (its residual is about
// 1e-11 on a 10,000-block wall); left alone, that error would stop the
// iterations short of the tolerance. Far from the optimum it is negligible
// beside the iterate's own error, and the check (a pass over every group)
// is skipped.
template <int D>
void NewtonSystem<D>::direction(const NewtonVectors& e, Complementarity complementarity, NewtonVectors& out,
                                double iterate_error) {
  constexpr int kRefinements = 3;
  constexpr double kRefineBelow = 1e-4;
  out.x = e.x;  // same sizes: no allocation
  out.y = e.y;
  solve(out, &complementarity);
  const double target = std::max(1e-14 * e.largest(), 1e-2 * iterate_error);
  double previous = std::numeric_limits<double>::infinity();
  for (int refinement = 0; refinement < kRefinements && iterate_error <= kRefineBelow; ++refinement) {
    // Most checks end here, the residual already small: its x part is kept
    // only once a correction has been solved for.
    const bool stored = error_.x.size() == e.x.size();
    const double size = residual(e, out, error_, stored);
    if (size <= target || size >= 0.5 * previous) break;
    if (!stored) {
      error_.x.resize(e.x.size());
      residual(e, out, error_, true);
    }
    previous = size;
    solve(error_, nullptr);  // now the correction's dx and dy; its dw = G dx and dz = -Z dw / W
    out.x += error_.x;
    out.y += error_.y;
    passes_.each([&](int k) {
      const GroupRowsVector dw = problem_.rules_of(problem_.groups[k]).rows * error_.x.template segment<4>(4 * k);
      inequality_.of(out.w, k) += dw;
      inequality_.of(out.z, k) -=
          inequality_.of(iterate_.z, k).cwiseProduct(dw).cwiseQuotient(inequality_.of(iterate_.w, k));
    });
  }
}

template class NewtonSystem<3>;
template class NewtonSystem<6>;

}  // namespace ashlar
