// Geometry and parameter optimisation by gradient descent or L-BFGS. No
// analysis happens here: the objective is a callback, typically a structure's
// infeasibility penalty (the equilibrium QP's optimal value) with its exact
// gradient. Evaluations are assumed expensive, so the optimiser stops as soon
// as one reports `stable` and never evaluates a design the design space
// rejects (see design_space.hpp).
//
// Optimisation to a margin (optimize_parameters_to_target) is the other
// problem: the least material (a cheap objective with its gradient) among
// the parameters whose margin reaches a target (an expensive verdict, with
// a violation measure and its gradient where it is violated). See there.
//
// Outcomes are statuses in the result (OSQP style); only bad input throws
// (InvalidArgument, naming the bad setting).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
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
  bool stable = false;   // optimisation to a target: the margin reaches it
  // Optimisation to a target: the margin there (NaN when the target has no
  // number of its own, as stable, or when it was not computed).
  double margin = std::numeric_limits<double>::quiet_NaN();
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
  // Optimisation to a target only: the margin's boundary is located by
  // bisection along each segment searched until the segment is at most this
  // long, in units of each parameter's scale (upper - lower where both are
  // finite, else max(1, |initial|)). In (0, 1).
  double bracket_tolerance = 1e-3;
  // Called after each accepted iterate, iteration 0 included. An exception
  // it throws ends the optimisation and propagates to the caller.
  std::function<void(const OptimizeStep&)> on_step;
};

enum class OptimizeStatus {
  stable,              // an evaluation reported stable
  converged,           // stationary (gradient or value tolerance) but not stable; to a
                       // target: the least objective on the margin's boundary
  // Stationary (gradient or value tolerance) with variables held at their
  // bounds by a gradient that pushes past them (of norm > gradient_tolerance).
  at_bound,
  max_iterations,      // max_iterations steps taken
  line_search_failed,  // no step was accepted (e.g. rejected designs block every one)
  evaluation_failed,   // the objective threw, or returned a non-finite value
};
inline constexpr EnumNames<OptimizeStatus, 6> kOptimizeStatusNames{
    {{{OptimizeStatus::stable, "stable"},
      {OptimizeStatus::converged, "converged"},
      {OptimizeStatus::at_bound, "at_bound"},
      {OptimizeStatus::max_iterations, "max_iterations"},
      {OptimizeStatus::line_search_failed, "line_search_failed"},
      {OptimizeStatus::evaluation_failed, "evaluation_failed"}}}};
// "stable", "converged", "at_bound", "max_iterations", "line_search_failed",
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

// Where a parameter ended relative to its bounds.
enum class BoundSide { none, lower, upper };
inline constexpr EnumNames<BoundSide, 3> kBoundSideNames{
    {{{BoundSide::none, "none"}, {BoundSide::lower, "lower"}, {BoundSide::upper, "upper"}}}};

struct ParameterResult {
  Eigen::VectorXd parameters;  // the last accepted parameters
  OptimizeStatus status = OptimizeStatus::converged;
  bool stable = false;  // to a target: the margin reaches it at `parameters`
  std::vector<OptimizeStep> history;
  int evaluations = 0;  // objective calls (to a target: margin calls)
  std::string message;
  // Per parameter: at its lower or upper bound (exactly), or neither.
  std::vector<BoundSide> active_bounds;
  // To a target: the margin at `parameters` (NaN as in OptimizeStep), and
  // whether the margin's boundary holds the result (a segment ending there
  // was bisected to bracket_tolerance).
  double margin = std::numeric_limits<double>::quiet_NaN();
  bool on_boundary = false;
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

// ----------------------------------------------------------------------------
// Optimisation to a margin.

// Whether the margin at some parameters reaches its target.
struct MarginCheck {
  bool feasible = false;  // the margin reaches the target
  // >= 0, continuous, 0 where feasible: how far it is from the target (e.g.
  // the target load factor less the factor, the penalty where it falls).
  double violation = 0.0;
  // d violation / d parameter, only when asked for (empty, or all zero,
  // when unknown).
  Eigen::VectorXd violation_gradient;
  double margin = std::numeric_limits<double>::quiet_NaN();  // reported (NaN: none)
};
// (parameters, whether the violation's gradient is wanted). Errors are
// handled as for ParameterObjective.
using MarginFunction = std::function<MarginCheck(const Eigen::VectorXd&, bool)>;

// Minimises `objective` (its `stable` is ignored) over lower <= p <= upper
// among the parameters whose margin is feasible, from `initial`.
//
// The margin is a verdict, not smooth (hinges change between joints), and
// expensive; the objective (material) is smooth and cheap. So:
//  1. From an infeasible start, optimize_parameters minimises the violation
//     by steepest descent until the margin is feasible (restoration);
//     settings.method is not used (L-BFGS keeps its first step's scale
//     squared on a violation with no curvature, such as a target less a
//     load factor, and crawls).
//  2. From a feasible point: projected steepest descent of the objective,
//     in variables scaled by each parameter's scale. A step that stays
//     feasible is taken; one that ends infeasible is bisected back onto the
//     margin's boundary (the feasible end of a segment at most
//     bracket_tolerance long), whose normal, the violation's gradient at the
//     infeasible end, then projects the descent onto the boundary's tangent;
//     a tangent step that ends infeasible is restored along the normal, by
//     bisection again. A step is accepted when the objective decreases.
// It stops converged when the projected descent vanishes (a KKT point of the
// boundary and the bounds) or steps no longer than bracket_tolerance
// decrease the objective; at_bound when bounds alone hold it.
// history: the initial point and every accepted point (`value` the
// objective, `stable` feasible). Throws as optimize_parameters.
ParameterResult optimize_parameters_to_target(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                              const Eigen::VectorXd& initial, const ParameterObjective& objective,
                                              const MarginFunction& margin, const OptimizeSettings& settings = {});

}  // namespace ashlar
