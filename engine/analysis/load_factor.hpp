// How far a structure is from collapse: the load factor (the largest
// multiple of a load that it carries, with the collapse mechanism) and the
// friction demand (the smallest friction coefficient with which it stands).
//
// Both work on the program of compression-only equilibria that respect
// friction (equilibrium_program.hpp), which COIN-OR Clp solves exactly: the
// load factor is one linear program in the contact forces and the factor;
// the friction demand, where the coefficient multiplies the unknowns, is a
// bracketing search (narrowed first by the equilibrium analysis's verdicts)
// over programs of the friction an equilibrium must borrow beyond the
// cones (the first by the barrier and crossover, then each warm-started
// from the last basis). Both are lower-bound
// (static) answers of limit analysis with the options' friction cone
// approximation; with sliding they assume associative friction, like the
// equilibrium analysis.
#pragma once

#include <vector>

#include "core/enum_names.hpp"
#include "core/progress.hpp"
#include "analysis/equilibrium_problem.hpp"
#include "analysis/margin_status.hpp"
#include "analysis/mechanism.hpp"

namespace ashlar {

// What the factor multiplies.
enum class LoadPattern {
  body_force,   // a force lambda * weight * direction at every free block's centroid
                // (a uniform acceleration lambda * g; a tilt by atan(lambda))
  point_loads,  // the structure's point loads (live); the weights stay (dead)
};
inline constexpr EnumNames<LoadPattern, 2> kLoadPatternNames{
    {{{LoadPattern::body_force, "body_force"}, {LoadPattern::point_loads, "point_loads"}}}};

struct LoadFactorSettings {
  EquilibriumOptions problem;            // friction, cone approximation, contact detection
  LoadPattern pattern = LoadPattern::body_force;
  Vec3 direction = Vec3(1.0, 0.0, 0.0);  // body_force only; normalised; in the x-z plane
                                         // for a planar structure
};

struct LoadFactor {
  // optimal; unbounded (no load is too much: factor = +inf); infeasible
  // (no multiple of the load lets it stand: factor NaN); floating (a free
  // block with no contact path to a support: NaN); stopped,
  // numerical_difficulties or unexpected (Clp failed: NaN); interrupted
  // (Ctrl-C or a sandbox deadline: NaN, and stable false: no verdict).
  MarginStatus status = MarginStatus::optimal;
  double factor = 0.0;  // the largest multiple lambda; negative when it needs a push
  // It stands with no load (lambda = 0): the equilibrium analysis's verdict,
  // which a program that failed afterwards (stopped, ...) leaves standing.
  bool stable = false;
  std::vector<BlockMotion> mechanism;  // per block, zero for supports; empty unless optimal
  std::vector<LimitInterface> limit;   // interfaces that move in the mechanism
  int iterations = 0;                  // Clp's: barrier iterations, crossover and simplex pivots
  double seconds = 0.0;
};

// Throws InvalidArgument for bad options (a zero direction, a direction out
// of a planar structure's plane, point_loads with no point loads).
// progress: told every Clp iteration, as (iterations so far, kTotalUnknown).
LoadFactor load_factor(const Structure& structure, const LoadFactorSettings& settings,
                       const ProgressCount& progress = {});

// The structure with the load that `factor` multiplies applied as point
// loads: a body force factor * weight * direction at every free block's
// centroid added (body_force), or its point loads multiplied by factor
// (point_loads). Analysed at the load factor, it is the equilibrium at the
// limit, whose line of thrust touches the hinges. Throws InvalidArgument
// for a non-finite factor or a zero direction.
Structure structure_at_factor(const Structure& structure, const LoadFactorSettings& settings, double factor);

struct FrictionDemandSettings {
  // The cone approximation (friction_model, friction_sides) and the
  // contacts; its friction is ignored: it is what the search finds.
  EquilibriumOptions problem;
  // Relative width of the final bracket [lower, friction], in (0, 1).
  double bracket_tolerance = 1e-6;
};

struct FrictionDemand {
  // optimal; unstable when it does not stand even without sliding
  // (friction +inf); floating (+inf); stopped, numerical_difficulties or
  // unexpected (NaN); interrupted (Ctrl-C or a sandbox deadline: the
  // bracket found so far, [lower, friction], or NaN before there is one).
  // The kinematic search (kinematic.hpp) adds its own.
  MarginStatus status = MarginStatus::optimal;
  double friction = 0.0;       // the smallest coefficient, to the tolerance (upper end of the bracket)
  double lower = 0.0;          // the largest coefficient found too small
  std::vector<int> critical;   // interfaces at the friction limit in the final equilibrium
  int programs = 0;            // feasibility programs solved
  int iterations = 0;          // the interior point's (3D programs); Clp's barrier iterations and simplex pivots
  double seconds = 0.0;
};

// Throws InvalidArgument for a bracket_tolerance outside (0, 1).
// progress: the bracket's digits, as -log10 of its relative width, of
// those the tolerance asks for (core/progress.hpp; none when empty).
FrictionDemand friction_demand(const Structure& structure, const FrictionDemandSettings& settings,
                               const ProgressCount& progress = {});

}  // namespace ashlar
