// optimize_parameters_to_target: the least objective among the parameters
// whose margin reaches a target (see optimizer.hpp for the method).
#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <tuple>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "optimize/optimizer.hpp"
#include "optimize/optimizer_checks.hpp"

namespace ashlar {
namespace {

constexpr double kAutomaticStep = 0.01;  // the first step: 1% of the parameters' scales
// The projected descent has vanished when it is this fraction of the
// objective's gradient (both in scaled variables).
constexpr double kStationary = 1e-6;
// A tangent step that ends beyond the boundary is restored along the normal
// by steps that double from the tangent step's length, at most this often.
constexpr int kRestoreDoublings = 8;

struct Stop {
  OptimizeStatus status;
  std::string message;
};

// A feasible point, in scaled variables u = p / scale.
struct Iterate {
  Eigen::VectorXd u;
  double value = 0.0;
  Eigen::VectorXd gradient;  // d value / d u
  MarginCheck margin;
};

class TargetDescent {
public:
  TargetDescent(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, const Eigen::VectorXd& scale,
                const ParameterObjective& objective, const MarginFunction& margin, const OptimizeSettings& settings,
                ParameterResult& result)
      : scale_(scale),
        lower_(lower.cwiseQuotient(scale)),
        upper_(upper.cwiseQuotient(scale)),
        objective_(objective),
        margin_(margin),
        settings_(settings),
        result_(result),
        tolerance_(settings.bracket_tolerance),
        started_(Clock::now()) {}

  // Restores the margin from `initial` when it falls short, then descends.
  void run(const Eigen::VectorXd& initial) {
    try {
      Eigen::VectorXd start = initial;
      const MarginCheck first = check(start, false);
      if (first.feasible) {
        current_ = iterate_at(start.cwiseQuotient(scale_), first);
        record(0.0);
      } else if (!restore(start)) {
        return;
      }
      descend();
    } catch (const Stop& stop) {
      result_.status = stop.status;
      result_.message = stop.message;
    }
  }

  const Iterate& current() const { return current_; }
  bool on_boundary() const { return bisected_; }
  int evaluations() const { return evaluations_; }

private:
  Eigen::VectorXd unscaled(const Eigen::VectorXd& u) const { return u.cwiseProduct(scale_); }
  Eigen::VectorXd clamp(const Eigen::VectorXd& u) const { return u.cwiseMax(lower_).cwiseMin(upper_); }

  // The margin at p; a GeometryError (the generator refused the parameters)
  // counts as falling short, with no gradient; other errors end the run.
  MarginCheck check(const Eigen::VectorXd& p, bool gradient) {
    ++evaluations_;
    MarginCheck m;
    try {
      m = margin_(p, gradient);
    } catch (const GeometryError&) {
      m = MarginCheck{};
      m.violation = std::numeric_limits<double>::infinity();
      return m;
    } catch (const std::exception& e) {
      throw Stop{OptimizeStatus::evaluation_failed, std::string("evaluation failed: ") + e.what()};
    }
    if (gradient && m.violation_gradient.size() != 0 && m.violation_gradient.size() != p.size()) {
      throw InvalidArgument("margin gradient: " + std::to_string(m.violation_gradient.size()) +
                            " entries, expected one per parameter (" + std::to_string(p.size()) + ")");
    }
    return m;
  }

  Iterate iterate_at(const Eigen::VectorXd& u, const MarginCheck& margin) {
    ParameterEvaluation e;
    try {
      e = objective_(unscaled(u));
    } catch (const std::exception& error) {
      throw Stop{OptimizeStatus::evaluation_failed, std::string("evaluation failed: ") + error.what()};
    }
    if (e.gradient.size() != u.size()) {
      throw InvalidArgument("parameter gradient: " + std::to_string(e.gradient.size()) +
                            " entries, expected one per parameter (" + std::to_string(u.size()) + ")");
    }
    if (!std::isfinite(e.value) || !e.gradient.allFinite()) {
      throw Stop{OptimizeStatus::evaluation_failed,
                 "evaluation failed: the objective returned a non-finite value or gradient"};
    }
    return Iterate{u, e.value, e.gradient.cwiseProduct(scale_), margin};
  }

  void record(double step) {
    OptimizeStep s;
    s.iteration = static_cast<int>(result_.history.size());
    s.value = current_.value;
    s.step = step;
    s.seconds = seconds_since(started_);
    s.stable = current_.margin.feasible;
    s.margin = current_.margin.margin;
    result_.history.push_back(s);
    if (settings_.on_step) settings_.on_step(s);
  }

  // Minimises the violation until the margin reaches the target; false when
  // it does not (the result then says why).
  bool restore(const Eigen::VectorXd& start) {
    std::optional<Iterate> last;  // the last evaluation: what the restoration accepts
    const ParameterObjective violation = [&](const Eigen::VectorXd& p) {
      const MarginCheck m = check(p, true);
      if (!std::isfinite(m.violation)) throw GeometryError("the margin could not be computed here");
      last = iterate_at(p.cwiseQuotient(scale_), m);
      ParameterEvaluation e;
      e.value = m.violation;
      e.stable = m.feasible;
      e.gradient = m.violation_gradient.size() ? m.violation_gradient : Eigen::VectorXd::Zero(p.size());
      return e;
    };
    // Steepest descent, whose steps double while they succeed: the
    // violation may be linear (a target less a load factor), where L-BFGS,
    // with no curvature to learn, keeps its first step's scale squared.
    OptimizeSettings restoring = settings_;
    restoring.method = OptimizeMethod::gradient;
    restoring.on_step = [&](const OptimizeStep& step) {
      current_ = *last;
      record(step.step);
    };
    const ParameterResult restored =
        optimize_parameters(lower_.cwiseProduct(scale_), upper_.cwiseProduct(scale_), start, violation, restoring);
    if (restored.stable) return true;
    result_.status = restored.status;
    result_.message = "the margin does not reach the target: " + restored.message;
    return false;
  }

  // Zeroes the components of d that push past an active bound at u.
  void hold_bounds(const Eigen::VectorXd& u, Eigen::VectorXd& d, bool& held) const {
    for (Eigen::Index j = 0; j < d.size(); ++j) {
      if ((u[j] <= lower_[j] && d[j] < 0.0) || (u[j] >= upper_[j] && d[j] > 0.0)) {
        if (d[j] != 0.0) held = true;
        d[j] = 0.0;
      }
    }
  }

  // Bisects between a feasible and an infeasible point until they are at
  // most the tolerance apart; returns the feasible end and sets the normal
  // from the violation's gradient at the infeasible end (or, when that is
  // unknown, the segment's direction).
  std::pair<Eigen::VectorXd, MarginCheck> bisect(Eigen::VectorXd feasible, MarginCheck feasible_margin,
                                                 Eigen::VectorXd infeasible, Eigen::VectorXd& normal) {
    while ((infeasible - feasible).norm() > tolerance_) {
      const Eigen::VectorXd middle = 0.5 * (feasible + infeasible);
      const MarginCheck m = check(unscaled(middle), false);
      if (m.feasible) {
        feasible = middle;
        feasible_margin = m;
      } else {
        infeasible = middle;
      }
    }
    const MarginCheck outside = check(unscaled(infeasible), true);
    Eigen::VectorXd n = outside.violation_gradient.size() ? Eigen::VectorXd(outside.violation_gradient.cwiseProduct(scale_))
                                                          : Eigen::VectorXd::Zero(feasible.size());
    if (!n.allFinite() || n.norm() == 0.0) n = infeasible - feasible;
    normal = n.norm() > 0.0 ? Eigen::VectorXd(n.normalized()) : Eigen::VectorXd();
    return {feasible, feasible_margin};
  }

  std::string after() const {
    return " after " + std::to_string(result_.history.size() - 1) + " iterations";
  }

  void descend() {
    const double initial_step = settings_.initial_step;
    double length = kAutomaticStep;
    bool first_step = true;
    for (;;) {
      const Eigen::VectorXd& u = current_.u;
      const Eigen::VectorXd& g = current_.gradient;
      Eigen::VectorXd d = -g;
      bool bound_held = false, boundary_held = false;
      hold_bounds(u, d, bound_held);
      // Alternating projections onto the boundary's tangent and the bounds.
      for (int round = 0; round < 3 && normal_.size() && d.dot(normal_) > 0.0; ++round) {
        d -= d.dot(normal_) * normal_;
        boundary_held = true;
        hold_bounds(u, d, bound_held);
      }
      if (d.norm() <= kStationary * g.norm()) {
        if (boundary_held) {
          throw Stop{OptimizeStatus::converged,
                     "converged" + after() + ": the least objective on the margin's boundary"};
        }
        if (bound_held) {
          throw Stop{OptimizeStatus::at_bound,
                     "stopped at a bound" + after() + ": the objective decreases only past the bounds"};
        }
        throw Stop{OptimizeStatus::converged, "converged" + after() + ": the objective's gradient vanishes"};
      }
      if (static_cast<int>(result_.history.size()) - 1 >= settings_.max_iterations) {
        throw Stop{OptimizeStatus::max_iterations, "stopped" + after() + " (max_iterations), the margin reached"};
      }
      const Eigen::VectorXd direction = d.normalized();
      if (first_step && initial_step > 0.0) {
        length = initial_step / direction.cwiseAbs().cwiseProduct(scale_).maxCoeff();
      }
      first_step = false;
      bool replan = false;
      for (;;) {
        if (length <= tolerance_) {
          throw Stop{OptimizeStatus::converged,
                     "converged" + after() + ": no step longer than bracket_tolerance decreases the objective" +
                         (on_boundary() ? " along the margin's boundary" : "")};
        }
        const Eigen::VectorXd q = clamp(u + length * direction);
        if ((q - u).norm() <= tolerance_) {
          length /= 2;
          continue;
        }
        const MarginCheck at_q = check(unscaled(q), false);
        Eigen::VectorXd candidate;
        MarginCheck candidate_margin;
        Eigen::VectorXd normal;
        bool full = false;
        if (at_q.feasible) {
          candidate = q;
          candidate_margin = at_q;
          full = true;
        } else if (boundary_held) {
          // Restore the tangent step along the normal.
          double inside = 0.0, beta = length;
          std::optional<Eigen::VectorXd> restored;
          MarginCheck restored_margin;
          for (int k = 0; k < kRestoreDoublings; ++k, beta *= 2) {
            const Eigen::VectorXd r = clamp(q - beta * normal_);
            const MarginCheck m = check(unscaled(r), false);
            if (m.feasible) {
              restored = r;
              restored_margin = m;
              break;
            }
            inside = beta;
          }
          if (!restored) {
            length /= 2;
            continue;
          }
          std::tie(candidate, candidate_margin) =
              bisect(*restored, restored_margin, clamp(q - inside * normal_), normal);
        } else {
          std::tie(candidate, candidate_margin) = bisect(u, current_.margin, q, normal);
          if ((candidate - u).norm() == 0.0 && normal.size() && normal_.size() == 0) {
            // The boundary lies within the tolerance of u: descend along it.
            normal_ = normal;
            bisected_ = true;
            replan = true;
            break;
          }
        }
        Iterate next = iterate_at(candidate, candidate_margin);
        if (next.value < current_.value - 1e-14 * std::max(1.0, std::abs(current_.value))) {
          const double moved = (next.u - u).norm();
          const double step = (unscaled(next.u) - unscaled(u)).norm();
          current_ = std::move(next);
          // A tangent step that stays feasible keeps the boundary's normal
          // for the next direction; the point is on the boundary only when
          // bisected onto it.
          bisected_ = !full;
          if (!full) {
            normal_ = normal;
          } else if (!boundary_held) {
            normal_.resize(0);
          }
          if (full) length *= 2;
          record(step);
          if (moved <= tolerance_) {
            throw Stop{OptimizeStatus::converged,
                       "converged" + after() + ": the last step was within bracket_tolerance" +
                           (on_boundary() ? " of the margin's boundary" : "")};
          }
          break;
        }
        length /= 2;
      }
      if (replan) continue;
    }
  }

  Eigen::VectorXd scale_, lower_, upper_;
  const ParameterObjective& objective_;
  const MarginFunction& margin_;
  const OptimizeSettings& settings_;
  ParameterResult& result_;
  double tolerance_;
  Clock::time_point started_;
  Iterate current_;
  // Unit, towards violation: the boundary's normal at (or, after a tangent
  // step, near) the current point; empty in the interior.
  Eigen::VectorXd normal_;
  bool bisected_ = false;  // the current point is a bisection's feasible end
  int evaluations_ = 0;
};

}  // namespace

ParameterResult optimize_parameters_to_target(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                              const Eigen::VectorXd& initial, const ParameterObjective& objective,
                                              const MarginFunction& margin, const OptimizeSettings& settings) {
  check_optimize_settings(settings);
  if (!objective || !margin) throw InvalidArgument("optimize parameters: no objective or no margin given");
  const Eigen::VectorXd scale = parameter_scales(lower, upper, initial);
  ParameterResult result;
  TargetDescent descent(lower, upper, scale, objective, margin, settings, result);
  descent.run(initial);
  const Iterate& end = descent.current();
  result.parameters = end.u.size() ? Eigen::VectorXd(end.u.cwiseProduct(scale)) : initial;
  result.stable = end.u.size() && end.margin.feasible;
  result.margin = end.margin.margin;
  result.on_boundary = result.stable && descent.on_boundary();
  result.active_bounds = active_bounds(result.parameters, lower, upper);
  result.evaluations = descent.evaluations();
  return result;
}

}  // namespace ashlar
