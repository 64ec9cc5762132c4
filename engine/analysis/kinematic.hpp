// The kinematic method: stability when joints slide without dilatancy and
// the structure starts unstressed (no prestress).
//
// The rigid-block equilibrium (the lower-bound theorem) lets friction use
// any normal force an equilibrium has, including normal forces that nothing
// in the structure creates: a block clamped between two walls "stands" on
// friction from a squeeze the walls never apply. Real joints slide without
// opening (no dilatancy), so friction can use only the normal force the
// loads themselves press into a joint.
//
// Formulation (non-associative friction by successive associative problems,
// as Gilbert, Casapulla & Ahmed 2006 do for limit analysis): each round
// solves ashlar's equilibrium QP with friction bounded not by mu times the
// unknown compression but by a given shear strength per contact vertex
// (FrictionLaw::given_strength: the joint behaves as cohesive, which has no
// dilatancy), then sets each strength to mu times the compression that
// round found. In that QP joints carry no tension, and what they cannot
// carry goes to virtual forces and torques on the blocks at the price of the
// kinetic energy of the motion they would start (plus a linear penalty of
// 1e-2, just enough to make zero virtual load exact: a larger one is a dead
// zone in which a block whose fall a steep face blocks gets no force from
// that face, so the joint never gains strength): a round is one step of
// frictional contact dynamics from rest
// (Gauss's least constraint), so its compressions are those the loads press
// into the joints, and among equilibria it picks the least sum of squared
// forces (contacts with equal springs). The first round has no strength at
// all (no prestress); compressions under 1 % of the lighter block's weight
// do not count (the solver's rounding, which friction could otherwise turn
// into self-made arching). The rounds first build the strengths up: each
// vertex keeps mu times the largest compression any round has pressed into
// it, until no strength grows or a round stands. A block that still moves
// presses different vertices of its joints from round to round (it turns
// about those without strength), so strengths that followed only the last
// round would never be where its sliding needs them, and a squeeze that
// friction must hold while it grows (a voussoir in a slot that widens
// outwards) would never build. From there plain rounds set each strength to
// mu times the last round's compression, damped where they turn back. The
// rounds end when no strength changes (a fixed point: friction is within mu
// times the very compression it rests on), or at a stable round whose
// friction is within mu times its own compressions.
//
// Verdict: stable when the rounds settled and the last QP's forces balance
// every block without virtual loads or excess friction (as the equilibrium
// method decides). It is certain in that model: such forces exist and arise
// from an unstressed state. "Unstable" is the fixed point the plain rounds
// reach from the built-up strengths, a local answer: an iteration from
// another starting point, or another spring law, could find another.
// Rounds that do not settle within max_rounds give status max_iterations
// and no verdict (stable false).
//
// Both methods agree where friction does not decide (mu infinite: no
// sliding; or frictionless joints).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/equilibrium.hpp"
#include "analysis/load_factor.hpp"

namespace ashlar {

// Throws InvalidArgument for bad settings, as analyze_equilibrium. The
// result's method is kinematic and `rounds` the equilibrium solves made;
// its forces, tension and mechanism are the last round's.
EquilibriumResult analyze_kinematic(const Structure& structure, const AnalysisSettings& settings);

// The load factor by the kinematic method: the largest lambda for which the
// structure with the body force lambda x weight x direction on every free
// block (or lambda x its point loads) still stands kinematically, found by
// bisection to `bracket_tolerance` (relative) below the equilibrium
// method's factor (load_factor), which bounds it: what stands kinematically
// stands by equilibrium too.
struct KinematicLoadFactorSettings {
  // What the factor multiplies (pattern, direction). Its problem is not
  // read: analysis.problem is both methods'.
  LoadFactorSettings load;
  // The kinematic analyses' settings (their method is ignored).
  AnalysisSettings analysis;
  // Relative width of the final bisection bracket, in (0, 1): each digit
  // costs about three kinematic analyses.
  double bracket_tolerance = 1e-3;
};

struct KinematicLoadFactor {
  // optimal; unbounded (stands under any multiple the equilibrium method
  // allows: an infinite factor); unstable (falls with no load: factor 0 is
  // not reached, NaN); or the equilibrium method's status when it has no
  // factor (infeasible, floating, stopped, ...); no_verdict when a
  // kinematic analysis did not settle, interrupted when one was stopped
  // (Ctrl-C, a sandbox deadline) (both NaN).
  MarginStatus status = MarginStatus::optimal;
  double factor = 0.0;
  // It stands with no load: a factor >= 0 was found, or it is unbounded.
  // False without a verdict (no_verdict, interrupted, a failed program).
  bool stable = false;
  double equilibrium_factor = 0.0;   // load_factor's, the upper bound
  int analyses = 0;                  // kinematic analyses made
  EquilibriumResult failure;         // the analysis just above the factor: its mechanism
  double seconds = 0.0;
};

struct KinematicFrictionDemandSettings {
  // The kinematic analyses' settings (their friction is what the search
  // finds, their method is ignored).
  AnalysisSettings analysis;
  // Relative width of the final bisection bracket, in (0, 1).
  double bracket_tolerance = 1e-3;
};

// The least friction coefficient under which the kinematic method finds the
// structure standing, by bisection to `bracket_tolerance` (relative) from
// the equilibrium method's demand (friction_demand), which it cannot be
// below. Status as friction_demand's, and unbounded when it stands only
// without sliding (friction +inf; a block clamped between walls),
// no_verdict when an analysis did not settle, interrupted when one was
// stopped (both NaN). `programs` counts kinematic analyses, `critical` the
// interfaces that move at `lower`. Both searches tell `progress` the
// digits of their bracket (BracketProgress, core/progress.hpp), and throw
// InvalidArgument for a bracket_tolerance outside (0, 1).
FrictionDemand kinematic_friction_demand(const Structure& structure, const KinematicFrictionDemandSettings& settings,
                                         const ProgressCount& progress = {});

KinematicLoadFactor kinematic_load_factor(const Structure& structure, const KinematicLoadFactorSettings& settings,
                                          const ProgressCount& progress = {});

}  // namespace ashlar
