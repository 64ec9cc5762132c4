#include "analysis/iterate_residuals.hpp"

#include <algorithm>
#include <cmath>

namespace ashlar {

IterateResiduals::IterateResiduals(const EquilibriumProblem& problem, const InequalityRows& inequality,
                                   const TwinGroups& twins, GroupPasses& passes)
    : problem_(problem), inequality_(inequality), twins_(twins), passes_(passes) {
  const Eigen::VectorXd& b = problem.rhs;
  rhs_scale_ = 1.0 + (b.size() ? b.lpNorm<Eigen::Infinity>() : 0.0);
  double largest_linear = 0.0;
  for (const GroupRules& rules : problem.rules) {
    largest_linear = std::max(largest_linear, rules.linear.lpNorm<Eigen::Infinity>());
  }
  dual_scale_ = 1.0 + largest_linear;
}

template <int D>
double IterateResiduals::measure(const InteriorPointSolution& iterate, NewtonVectors& r, InteriorPointInfo& info) {
  const InequalityRows& ineq = inequality_;
  const Eigen::VectorXd& x = iterate.x;
  const Eigen::VectorXd& y = iterate.y;
  const Eigen::VectorXd& w = iterate.w;
  const Eigen::VectorXd& z = iterate.z;
  r.y = -problem_.rhs;
  passes_.each_into(r.y, [&](int k, Eigen::VectorXd& rows) {
    const ForceGroup& v = problem_.groups[k];
    const GroupRules& rules = problem_.rules_of(v);
    const Eigen::Vector4d xk = x.segment<4>(4 * k);
    add_group_effect<D>(v, xk, rows);
    r.x.segment<4>(4 * k) = twins_.count(k) * (rules.hessian.cwiseProduct(xk) + rules.linear) -
                            group_reaction<D>(v, y) - rules.rows.transpose() * ineq.of(z, k);
  });
  const double slack_residual = passes_.largest([&](int k) {
    const GroupRowsVector slack = slack_residual_of(problem_, ineq, iterate, k);
    return slack.size() ? slack.lpNorm<Eigen::Infinity>() : 0.0;
  });
  // The total gap, not its mean, bounds the objective's error.
  const double duality_gap = w.dot(z);
  const int m_total = ineq.total();
  info.primal_residual = std::max(r.y.size() ? r.y.lpNorm<Eigen::Infinity>() : 0.0, slack_residual);
  info.dual_residual = dual_residual(r.x);
  info.complementarity = m_total > 0 ? duality_gap / m_total : 0.0;
  return duality_gap;
}

template double IterateResiduals::measure<3>(const InteriorPointSolution&, NewtonVectors&, InteriorPointInfo&);
template double IterateResiduals::measure<6>(const InteriorPointSolution&, NewtonVectors&, InteriorPointInfo&);

double IterateResiduals::scaled_error(const InteriorPointInfo& info, double duality_gap, double objective_floor,
                                      const Eigen::VectorXd& x) const {
  return std::max({info.primal_residual / rhs_scale_, info.dual_residual / dual_scale_,
                   duality_gap / (objective_floor + std::abs(objective(x)))});
}

double IterateResiduals::objective(const Eigen::VectorXd& x) const {
  double sum = 0.0;
  for (size_t k = 0; k < problem_.groups.size(); ++k) {
    const GroupRules& rules = problem_.rules_of(problem_.groups[k]);
    const Eigen::Vector4d xk = x.segment<4>(4 * k);
    sum += twins_.count(static_cast<int>(k)) * (0.5 * xk.dot(rules.hessian.cwiseProduct(xk)) + rules.linear.dot(xk));
  }
  return sum;
}

double IterateResiduals::dual_residual(const Eigen::VectorXd& residual) const {
  if (!twins_.merged()) return residual.size() ? residual.lpNorm<Eigen::Infinity>() : 0.0;
  double largest = 0.0;
  for (size_t k = 0; k < problem_.groups.size(); ++k) {
    const double twins = twins_.count(static_cast<int>(k));
    largest = std::max(largest, residual.segment<4>(4 * k).lpNorm<Eigen::Infinity>() / twins);
  }
  return largest;
}

}  // namespace ashlar
