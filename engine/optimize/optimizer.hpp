// Geometry and parameter optimisation by gradient descent or L-BFGS. No
// analysis happens here: the objective is a callback, typically a structure's
// infeasibility penalty (the equilibrium QP's optimal value) with its exact
// gradient. Evaluations are assumed expensive, so the optimiser stops as soon
// as one reports `stable` and never evaluates a design the design space
// rejects (see design_space.hpp).
//
// Outcomes are statuses in the result (OSQP style); only bad input throws
// (InvalidArgument, naming the bad setting).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "optimize/planar_chart.hpp"

namespace ashlar {

// The objective at one design.
struct DesignEvaluation {
  double value = 0.0;    // to minimise (e.g. the dimensionless infeasibility)
  bool stable = false;   // the goal is reached: optimisation stops here
  DesignPoint gradient;  // d value / d position, the design's shape (1/m)
};
// May throw ashlar::Error: a GeometryError rejects the design (the optimiser
// shortens its step), any other error ends with status evaluation_failed.
using DesignObjective = std::function<DesignEvaluation(const DesignPoint&)>;

enum class OptimizeMethod {
  // L-BFGS-B (LBFGS++'s LBFGSBSolver; infinite bounds when none are set)
  // with Armijo backtracking, which shortens steps at rejected designs.
  lbfgs,
  gradient,  // steepest descent with an Armijo backtracking line search
};
inline constexpr EnumNames<OptimizeMethod, 2> kOptimizeMethodNames{
    {{{OptimizeMethod::lbfgs, "lbfgs"}, {OptimizeMethod::gradient, "gradient"}}}};

// One accepted iterate; iteration 0 is the initial design.
struct OptimizeStep {
  int iteration = 0;
  double value = 0.0;
  double step = 0.0;     // largest move from the previous iterate (m; parameters: 2-norm)
  double seconds = 0.0;  // wall time since the optimisation started
  bool stable = false;
};

struct OptimizeSettings {
  OptimizeMethod method = OptimizeMethod::lbfgs;
  // Accepted steps at most (0: evaluate the start only).
  int max_iterations = 50;
  // Converged when the 2-norm of the gradient in the free variables (those
  // not held by an active bound) is at most this (value per unit of the
  // variables: per metre for designs, whose reduced variables are lengths).
  double gradient_tolerance = 1e-9;
  // Converged when a step changes the value by at most this x max(1, |value|).
  double value_tolerance = 1e-12;
  // Length of the first step: the largest change it makes to one variable
  // (designs: a displacement component before the planar-face correction,
  // m; parameters: one parameter). 0: 1% of the model size; for parameters
  // 1% of the widest finite range, else of max(1, largest |initial|).
  double initial_step = 0.0;
  // Called after each accepted iterate, iteration 0 included. An exception
  // it throws ends the optimisation and propagates to the caller.
  std::function<void(const OptimizeStep&)> on_step;
};

enum class OptimizeStatus {
  stable,              // an evaluation reported stable
  converged,           // stationary (gradient or value tolerance) but not stable
  max_iterations,      // max_iterations steps taken
  line_search_failed,  // no step was accepted (e.g. rejected designs block every one)
  evaluation_failed,   // the objective threw, or returned a non-finite value
};
inline constexpr EnumNames<OptimizeStatus, 5> kOptimizeStatusNames{
    {{{OptimizeStatus::stable, "stable"},
      {OptimizeStatus::converged, "converged"},
      {OptimizeStatus::max_iterations, "max_iterations"},
      {OptimizeStatus::line_search_failed, "line_search_failed"},
      {OptimizeStatus::evaluation_failed, "evaluation_failed"}}}};
// "stable", "converged", "max_iterations", "line_search_failed",
// "evaluation_failed".
const char* status_name(OptimizeStatus status);

struct OptimizeResult {
  DesignPoint design;  // the last accepted design (the stable one when stable)
  OptimizeStatus status = OptimizeStatus::converged;
  bool stable = false;
  std::vector<OptimizeStep> history;  // accepted iterates, the initial design first
  int evaluations = 0;                // objective calls
  std::string message;                // why it stopped, for people
};

// Minimises objective over the designs of `space`, starting at space.start().
// Throws InvalidArgument for invalid settings.
OptimizeResult optimize_design(const DesignSpace& space, const DesignObjective& objective,
                               const OptimizeSettings& settings = {});

// Optimisation of a parametric model's parameters, whose caller chains the
// design gradient through the model to get the parameter gradient.
struct ParameterEvaluation {
  double value = 0.0;
  bool stable = false;
  Eigen::VectorXd gradient;  // d value / d parameter, one entry per parameter
};
// Errors are handled as for DesignObjective.
using ParameterObjective = std::function<ParameterEvaluation(const Eigen::VectorXd&)>;

struct ParameterResult {
  Eigen::VectorXd parameters;  // the last accepted parameters
  OptimizeStatus status = OptimizeStatus::converged;
  bool stable = false;
  std::vector<OptimizeStep> history;
  int evaluations = 0;
  std::string message;
};

// Minimises objective for lower <= parameters <= upper (bounds may be
// infinite) from `initial`, which must lie within them: L-BFGS-B, or
// projected gradient descent; every evaluated point lies within the bounds.
// Throws InvalidArgument for mismatched sizes, lower > upper, NaN, an
// initial point outside the bounds, or invalid settings.
ParameterResult optimize_parameters(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                    const Eigen::VectorXd& initial,
                                    const ParameterObjective& objective,
                                    const OptimizeSettings& settings = {});

}  // namespace ashlar
