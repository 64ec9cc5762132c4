#include "optimize/optimizer.hpp"

#include "optimize/optimizer_checks.hpp"

#include <LBFGSB.h>

#include <cmath>
#include <exception>
#include <limits>
#include <optional>
#include <stdexcept>

#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar {
namespace {

constexpr int kMaxLineSearchTrials = 20;
constexpr double kArmijo = 1e-4;  // sufficient decrease: a fraction of the linear prediction
constexpr double kAutomaticStep = 0.01;

// One evaluation, in the problem's variables v.
struct Trial {
  bool admissible = false;  // false: no value (the reason is in `rejection`)
  std::string rejection;
  double value = 0.0;
  bool stable = false;
  Eigen::VectorXd gradient;                // d value / d v
  Eigen::VectorXd unconstrained_gradient;  // before the chart's pull-back (designs)
  Eigen::VectorXd point;                   // v moved onto the constraint set
};

// A minimisation in variables v within box bounds.
class Problem {
public:
  virtual ~Problem() = default;
  virtual Eigen::VectorXd start() const = 0;
  virtual const Eigen::VectorXd& lower() const = 0;
  virtual const Eigen::VectorXd& upper() const = 0;
  // Not admissible when v lies outside the admissible set; then the
  // objective is not called.
  virtual Trial evaluate(const Eigen::VectorXd& v) = 0;
  // The history's step between two Trial::points.
  virtual double distance(const Eigen::VectorXd& from, const Eigen::VectorXd& to) const = 0;
  // Re-linearises the constraint set at trial.point (whose variables become
  // trial.point) and re-expresses trial.gradient there.
  virtual void recenter(Trial&) {}
  int evaluations() const { return evaluations_; }

protected:
  int evaluations_ = 0;
};

class DesignProblem : public Problem {
public:
  DesignProblem(const DesignSpace& space, const DesignObjective& objective)
      : space_(space),
        objective_(objective),
        chart_(space, space.start()),
        lower_(space.lower_bounds()),
        upper_(space.upper_bounds()) {}

  Eigen::VectorXd start() const override { return space_.start(); }
  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }

  Trial evaluate(const Eigen::VectorXd& z) override {
    Trial trial;
    std::optional<Eigen::VectorXd> planar = chart_.project(z);
    if (!planar) {
      trial.rejection = "the step is too long to keep the faces planar";
      return trial;
    }
    trial.rejection = space_.rejection(*planar);
    if (!trial.rejection.empty()) return trial;
    ++evaluations_;
    const DesignEvaluation evaluation = objective_(space_.design(*planar));
    trial.admissible = true;
    trial.value = evaluation.value;
    trial.stable = evaluation.stable;
    trial.unconstrained_gradient = space_.reduce(evaluation.gradient);
    trial.gradient = chart_.pull_back(*planar, trial.unconstrained_gradient);
    trial.point = std::move(*planar);
    return trial;
  }

  double distance(const Eigen::VectorXd& from, const Eigen::VectorXd& to) const override {
    return space_.largest_move(from, to);
  }

  void recenter(Trial& trial) override {
    chart_ = PlanarChart(space_, trial.point);
    trial.gradient = chart_.pull_back(trial.point, trial.unconstrained_gradient);
  }

private:
  const DesignSpace& space_;
  const DesignObjective& objective_;
  PlanarChart chart_;
  Eigen::VectorXd lower_, upper_;
};

class ParameterProblem : public Problem {
public:
  ParameterProblem(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                   const Eigen::VectorXd& initial, const ParameterObjective& objective)
      : lower_(lower), upper_(upper), initial_(initial), objective_(objective) {}

  Eigen::VectorXd start() const override { return initial_; }
  const Eigen::VectorXd& lower() const override { return lower_; }
  const Eigen::VectorXd& upper() const override { return upper_; }

  Trial evaluate(const Eigen::VectorXd& parameters) override {
    ++evaluations_;
    ParameterEvaluation evaluation = objective_(parameters);
    if (evaluation.gradient.size() != parameters.size()) {
      throw InvalidArgument("parameter gradient: " + std::to_string(evaluation.gradient.size()) +
                            " entries, expected one per parameter (" +
                            std::to_string(parameters.size()) + ")");
    }
    Trial trial;
    trial.admissible = true;
    trial.value = evaluation.value;
    trial.stable = evaluation.stable;
    trial.gradient = std::move(evaluation.gradient);
    trial.unconstrained_gradient = trial.gradient;
    trial.point = parameters;
    return trial;
  }

  double distance(const Eigen::VectorXd& from, const Eigen::VectorXd& to) const override {
    return (to - from).norm();
  }

private:
  Eigen::VectorXd lower_, upper_, initial_;
  const ParameterObjective& objective_;
};

// Ends a run from anywhere inside it (also from within LBFGS++).
struct Stop {
  OptimizeStatus status;
  std::string message;
};

struct Outcome {
  OptimizeStatus status = OptimizeStatus::converged;
  std::string message;
  Eigen::VectorXd point;
  std::vector<OptimizeStep> history;
};

// Armijo backtracking for LBFGS++'s L-BFGS-B solver. Rejected designs
// (infinite values) make it shorten the step; a Wolfe search could not stop
// next to them. The solver skips curvature pairs with s'y <= 0 itself, which
// is why it also serves unbounded problems (LBFGSSolver does not check).
// Reports the point it accepts (its last evaluation) so that every iterate
// is recorded.
template <typename Scalar>
class ArmijoBoxLineSearch {
public:
  using Vector = Eigen::Matrix<Scalar, Eigen::Dynamic, 1>;
  template <typename Objective>
  static void LineSearch(Objective& f, Scalar& fx, Vector& x, Vector& grad, Scalar& step,
                         const Scalar& /*step_max*/, const Vector& drt, const Vector& xp,
                         const LBFGSpp::LBFGSBParam<Scalar>& param) {
    const Scalar initial = fx;
    const Scalar slope = grad.dot(drt);
    if (!(step > 0) || !(slope < 0)) {
      throw std::logic_error("the search direction does not descend within the bounds");
    }
    for (int trial = 0; trial < param.max_linesearch; ++trial, step /= 2) {
      x.noalias() = xp + step * drt;
      fx = f(x, grad);
      if (fx <= initial + param.ftol * step * slope) {
        f.accepted(x);
        return;
      }
    }
    throw std::runtime_error("no step along the search direction decreased the value enough");
  }
};

class Driver {
public:
  Driver(Problem& problem, const OptimizeSettings& settings, double initial_step)
      : problem_(problem),
        settings_(settings),
        initial_step_(initial_step),
        started_(Clock::now()) {}

  Outcome run() {
    Outcome outcome;
    try {
      v_ = problem_.start();
      Trial first = evaluate(v_);
      if (!first.admissible) {
        throw Stop{OptimizeStatus::evaluation_failed,
                   "the initial design is not admissible: " + first.rejection};
      }
      accept(v_, first);
      run_with_restarts();
    } catch (const Stop& stop) {
      outcome.status = stop.status;
      outcome.message = stop.message;
    }
    if (callback_error_) std::rethrow_exception(callback_error_);
    outcome.point = current_.point.size() == 0 ? problem_.start() : current_.point;
    outcome.history = std::move(history_);
    return outcome;
  }

private:
  // The objective, wrapped: a GeometryError rejects the point, other errors
  // and non-finite answers stop the run, a stable answer is accepted and
  // stops it.
  Trial evaluate(const Eigen::VectorXd& v) {
    Trial trial;
    try {
      trial = problem_.evaluate(v);
    } catch (const GeometryError& e) {
      trial.admissible = false;
      trial.rejection = e.what();
    } catch (const std::exception& e) {
      throw Stop{OptimizeStatus::evaluation_failed, std::string("evaluation failed: ") + e.what()};
    }
    last_rejection_ = trial.rejection;
    if (trial.admissible && (!std::isfinite(trial.value) || !trial.gradient.allFinite())) {
      throw Stop{OptimizeStatus::evaluation_failed,
                 "evaluation failed: the objective returned a non-finite value or gradient"};
    }
    if (trial.admissible && trial.stable) accept(v, trial);
    return trial;
  }

  // Records an iterate, then stops the run when it is done.
  void accept(const Eigen::VectorXd& v, const Trial& trial) {
    const bool first = history_.empty();
    OptimizeStep step;
    step.iteration = static_cast<int>(history_.size());
    step.value = trial.value;
    step.step = first ? 0.0 : problem_.distance(current_.point, trial.point);
    step.seconds = seconds_since(started_);
    step.stable = trial.stable;
    const double previous = current_.value;
    v_ = v;
    current_ = trial;
    history_.push_back(step);
    if (settings_.on_step) {
      try {
        settings_.on_step(step);
      } catch (...) {
        callback_error_ = std::current_exception();
        throw Stop{OptimizeStatus::evaluation_failed, "on_step threw"};
      }
    }
    const std::string after = " after " + std::to_string(step.iteration) + " iterations";
    if (trial.stable) throw Stop{OptimizeStatus::stable, "stable" + after};
    const double norm = free_gradient_norm();
    const double change = std::abs(previous - trial.value);
    std::string reason;
    if (norm <= settings_.gradient_tolerance) {
      reason = "the gradient norm " + message_number(norm, kGivenValueDigits) + " in the free variables is within gradient_tolerance";
    } else if (!first && change <= settings_.value_tolerance * std::max(1.0, std::abs(trial.value))) {
      reason = "the last step changed the value by " + message_number(change, kGivenValueDigits) + ", within value_tolerance";
    }
    if (!reason.empty()) {
      // Stationary because bounds hold variables the gradient pushes past them.
      const double held = std::sqrt(std::max(0.0, current_.gradient.squaredNorm() - norm * norm));
      if (held > settings_.gradient_tolerance) {
        throw Stop{OptimizeStatus::at_bound, "stopped at a bound" + after + ": " + reason +
                                                 "; bounds hold variables against a gradient of norm " +
                                                 message_number(held, kGivenValueDigits)};
      }
      throw Stop{OptimizeStatus::converged, "converged" + after + ": " + reason};
    }
    if (step.iteration >= settings_.max_iterations) {
      throw Stop{OptimizeStatus::max_iterations,
                 "stopped" + after + " (max_iterations), not stable"};
    }
  }

  // The gradient without the components that push against an active bound.
  double free_gradient_norm() const {
    const Eigen::VectorXd& g = current_.gradient;
    double sum = 0.0;
    for (Eigen::Index i = 0; i < g.size(); ++i) {
      const bool held = (v_[i] <= problem_.lower()[i] && g[i] > 0.0) ||
                        (v_[i] >= problem_.upper()[i] && g[i] < 0.0);
      if (!held) sum += g[i] * g[i];
    }
    return std::sqrt(sum);
  }

  // L-BFGS restarts from the last iterate, with a fresh curvature model and a
  // chart centred there, when its line search fails after some progress.
  // LBFGS++, the line searches and the charts report failures as
  // std::logic_error or std::runtime_error; objective errors are Stops.
  void run_with_restarts() {
    for (;;) {
      const size_t accepted_before = history_.size();
      std::string failure;
      try {
        if (settings_.method == OptimizeMethod::gradient) {
          run_gradient_descent();
        } else {
          run_lbfgs();
        }
        // LBFGS++ returns by itself only when the gradient is lost in rounding.
        throw Stop{OptimizeStatus::converged, "converged: the gradient is below rounding"};
      } catch (const std::logic_error& e) {
        failure = e.what();
      } catch (const std::runtime_error& e) {
        failure = e.what();
      }
      const bool progressed = history_.size() > accepted_before;
      if (settings_.method == OptimizeMethod::lbfgs && progressed && recentered()) continue;
      std::string message = "line search failed: " + failure;
      if (!last_rejection_.empty()) {
        message += " (the last trial design was rejected: " + last_rejection_ + ")";
      }
      throw Stop{OptimizeStatus::line_search_failed, message};
    }
  }

  // Re-linearises the problem at the current iterate; false when it cannot.
  bool recentered() {
    try {
      problem_.recenter(current_);
    } catch (const Error&) {
      return false;
    }
    v_ = current_.point;
    return true;
  }

  // The scale of v that makes L-BFGS's first step (a unit step along the
  // normalised gradient in w = v / scale) initial_step long in its largest
  // component. Restarts use it too: a scale from a short last step would
  // shrink gradients in w below the rounding of w.
  double first_step_scale() const {
    const Eigen::VectorXd& g = current_.gradient;
    return initial_step_ * g.norm() / g.cwiseAbs().maxCoeff();
  }

  // Steepest descent in v, projected onto the bounds, with backtracking; the
  // chart is re-centred at every iterate so that the direction is the
  // steepest one within the constraint set.
  void run_gradient_descent() {
    double length = initial_step_ / current_.gradient.cwiseAbs().maxCoeff();
    for (;;) {
      if (!recentered()) throw std::runtime_error("the constraints cannot be linearised here");
      const Eigen::VectorXd g = current_.gradient;
      for (int trial = 0;; ++trial, length /= 2) {
        if (trial == kMaxLineSearchTrials) {
          throw std::runtime_error("no step along the steepest descent decreased the value enough");
        }
        const Eigen::VectorXd v =
            (v_ - length * g).cwiseMax(problem_.lower()).cwiseMin(problem_.upper());
        if (v == v_) throw std::runtime_error("the steps became too short to change the design");
        const double predicted = g.dot(v - v_);
        const Trial next = evaluate(v);
        if (next.admissible && next.value <= current_.value + kArmijo * predicted) {
          accept(v, next);
          break;
        }
      }
      length *= 2;  // the next line search starts longer than this one ended
    }
  }

  // The objective as LBFGS++ sees it, in scaled variables w = v / scale.
  class ScaledObjective {
  public:
    ScaledObjective(Driver& driver, double scale)
        : driver_(driver), scale_(scale), start_(driver.v_ / scale) {}
    const Eigen::VectorXd& start() const { return start_; }
    double scale() const { return scale_; }

    double operator()(const Eigen::VectorXd& w, Eigen::VectorXd& gradient) {
      last_ = w == start_ ? driver_.current_ : driver_.evaluate(unscaled(w));
      if (!last_.admissible) {
        gradient.setZero();
        return std::numeric_limits<double>::infinity();
      }
      gradient = last_.gradient * scale_;
      return last_.value;
    }
    // Line searches end at their last evaluation: that is the iterate.
    void accepted(const Eigen::VectorXd& w) { driver_.accept(unscaled(w), last_); }

  private:
    // Clamped: rounding in LBFGS++'s steps must not leave the bounds.
    Eigen::VectorXd unscaled(const Eigen::VectorXd& w) const {
      return (w * scale_).cwiseMax(driver_.problem_.lower()).cwiseMin(driver_.problem_.upper());
    }

    Driver& driver_;
    double scale_;
    Eigen::VectorXd start_;
    Trial last_;
  };

  void run_lbfgs() {
    ScaledObjective objective(*this, first_step_scale());
    Eigen::VectorXd w = objective.start();
    double value = 0.0;
    LBFGSpp::LBFGSBParam<double> param;
    // Stopping is accept()'s business.
    param.epsilon = 0.0;
    param.epsilon_rel = 0.0;
    param.past = 0;
    param.max_linesearch = kMaxLineSearchTrials;
    param.ftol = kArmijo;
    LBFGSpp::LBFGSBSolver<double, ArmijoBoxLineSearch> solver(param);
    const Eigen::VectorXd lower = problem_.lower() / objective.scale();
    const Eigen::VectorXd upper = problem_.upper() / objective.scale();
    solver.minimize(objective, w, value, lower, upper);
  }

  Problem& problem_;
  const OptimizeSettings& settings_;
  double initial_step_;
  Clock::time_point started_;
  Eigen::VectorXd v_;
  Trial current_;
  std::vector<OptimizeStep> history_;
  std::string last_rejection_;  // why the last evaluated design was rejected, if it was
  std::exception_ptr callback_error_;
};

// The parts of a design's and a parameter run's results that are alike.
template <class Result>
void report_outcome(Outcome&& outcome, int evaluations, Result& result) {
  result.status = outcome.status;
  result.stable = outcome.status == OptimizeStatus::stable;
  result.history = std::move(outcome.history);
  result.evaluations = evaluations;
  result.message = std::move(outcome.message);
}

}  // namespace

void check_optimize_settings(const OptimizeSettings& settings) {
  if (settings.method != OptimizeMethod::lbfgs && settings.method != OptimizeMethod::gradient) {
    throw InvalidArgument("optimize: method must be lbfgs or gradient");
  }
  if (settings.max_iterations < 0) {
    throw InvalidArgument("optimize: max_iterations must be >= 0, got " +
                          std::to_string(settings.max_iterations));
  }
  const auto check = [](double value, const char* name, const char* unit) {
    if (!(std::isfinite(value) && value >= 0.0)) {
      throw InvalidArgument(std::string("optimize: ") + name + " must be a finite number >= 0" +
                            unit + ", got " + message_number(value, kGivenValueDigits));
    }
  };
  check(settings.gradient_tolerance, "gradient_tolerance", "");
  check(settings.value_tolerance, "value_tolerance", "");
  check(settings.initial_step, "initial_step", " (m; 0 for automatic)");
  if (!(settings.bracket_tolerance > 0.0 && settings.bracket_tolerance < 1.0)) {
    throw InvalidArgument("optimize: bracket_tolerance must be in (0, 1), got " +
                          message_number(settings.bracket_tolerance, kGivenValueDigits));
  }
}

// Checks parameter bounds and the start; returns each parameter's scale:
// its range where finite, else max(1, |initial|).
Eigen::VectorXd parameter_scales(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                 const Eigen::VectorXd& initial) {
  const Eigen::Index n = initial.size();
  if (lower.size() != n || upper.size() != n) {
    throw InvalidArgument(
        "optimize parameters: lower, upper and initial must have equal sizes, got " +
        std::to_string(lower.size()) + ", " + std::to_string(upper.size()) + " and " +
        std::to_string(n));
  }
  Eigen::VectorXd scale(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::string which = "optimize parameters: parameter " + std::to_string(i + 1);
    if (std::isnan(lower[i]) || std::isnan(upper[i]) || lower[i] > upper[i]) {
      throw InvalidArgument(which + ": its bounds [" + message_number(lower[i], kGivenValueDigits) + ", " + message_number(upper[i], kGivenValueDigits) +
                            "] are not an interval");
    }
    if (!std::isfinite(initial[i]) || initial[i] < lower[i] || initial[i] > upper[i]) {
      throw InvalidArgument(which + ": its initial value " + message_number(initial[i], kGivenValueDigits) +
                            " is not within its bounds [" + message_number(lower[i], kGivenValueDigits) + ", " +
                            message_number(upper[i], kGivenValueDigits) + "]");
    }
    const double range = upper[i] - lower[i];
    scale[i] = std::isfinite(range) && range > 0.0 ? range : std::max(1.0, std::abs(initial[i]));
  }
  return scale;
}

std::vector<BoundSide> active_bounds(const Eigen::VectorXd& p, const Eigen::VectorXd& lower,
                                     const Eigen::VectorXd& upper) {
  std::vector<BoundSide> sides(static_cast<size_t>(p.size()), BoundSide::none);
  for (Eigen::Index i = 0; i < p.size(); ++i) {
    if (p[i] <= lower[i]) sides[i] = BoundSide::lower;
    else if (p[i] >= upper[i]) sides[i] = BoundSide::upper;
  }
  return sides;
}

const char* status_name(OptimizeStatus status) {
  return kOptimizeStatusNames.name(status);
}

OptimizeResult optimize_design(const DesignSpace& space, const DesignObjective& objective,
                               const OptimizeSettings& settings) {
  check_optimize_settings(settings);
  if (!objective) throw InvalidArgument("optimize: no objective given");
  DesignProblem problem(space, objective);
  const double initial_step =
      settings.initial_step > 0.0 ? settings.initial_step : kAutomaticStep * space.model_size();
  Outcome outcome = Driver(problem, settings, initial_step).run();
  OptimizeResult result;
  result.design = space.design(outcome.point);
  report_outcome(std::move(outcome), problem.evaluations(), result);
  return result;
}

ParameterResult optimize_parameters(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                    const Eigen::VectorXd& initial,
                                    const ParameterObjective& objective,
                                    const OptimizeSettings& settings) {
  check_optimize_settings(settings);
  if (!objective) throw InvalidArgument("optimize parameters: no objective given");
  const Eigen::Index n = initial.size();
  parameter_scales(lower, upper, initial);
  double widest = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::isfinite(upper[i] - lower[i])) widest = std::max(widest, upper[i] - lower[i]);
  }
  if (widest == 0.0) widest = std::max(1.0, n ? initial.cwiseAbs().maxCoeff() : 0.0);
  ParameterProblem problem(lower, upper, initial, objective);
  const double initial_step =
      settings.initial_step > 0.0 ? settings.initial_step : kAutomaticStep * widest;
  Outcome outcome = Driver(problem, settings, initial_step).run();
  ParameterResult result;
  result.parameters = std::move(outcome.point);
  result.active_bounds = active_bounds(result.parameters, lower, upper);
  report_outcome(std::move(outcome), problem.evaluations(), result);
  return result;
}

}  // namespace ashlar
