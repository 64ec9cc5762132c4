// Load capacity (Shin 2014, figures 5 and 6): for every block, the smallest
// and largest multiple of its own weight with which the structure still has
// a compression-only equilibrium that respects friction, every other block
// keeping its weight.
//
// The thesis searches by trial; here each bound is one linear program in
// the contact forces and the multiplier (feasibility of the equilibrium
// equations, friction pyramids, no tension). All programs share one
// constraint matrix and differ in one column's bounds and objective.
// - Least multiple: on 3D structures first the analysis's own verdict with
//   the block weightless (the equilibrium solver, warm from the as-built
//   forces, stopped at the first compression-only equilibrium: 3-4
//   iterations); a certified verdict is the least multiple 0. Otherwise,
//   and on planar structures, COIN-OR Clp's primal simplex from the
//   as-built optimal basis (a few dozen pivots).
// - Largest multiple: on planar structures the simplex continues from the
//   least's basis within a small pivot budget (enough on arches). Past it,
//   and on every 3D structure, it is solved under a cap: on 3D structures
//   with 0 < mu < infinity and no cables by the equilibrium solver
//   (interior_point.hpp) as a linear program, warm from the as-built
//   forces; elsewhere, or where that does not converge, by Clp's barrier
//   (no crossover; its normal equations on CHOLMOD, analysed once per
//   worker: clp_barrier.hpp). When the cap binds, a ray test decides
//   whether the maximum is unbounded: whether block j's weight alone can be
//   carried compression-only (a program that changes only in one fixed
//   column from block to block, so the dual simplex warm-starts it).
// Blocks are shared among worker threads, each with its own copy of the
// programs and solvers. The as-built program, whose optimal basis starts
// the simplex, is solved on a thread of its own meanwhile, and only the
// blocks that need it wait for it; on 3D structures whose as-built
// analysis certifies that they stand, only when a block needs it.
#pragma once

#include <vector>

#include "analysis/equilibrium.hpp"
#include "analysis/margin_status.hpp"
#include "core/progress.hpp"

namespace ashlar {

struct LoadCapacitySettings {
  AnalysisSettings analysis;  // friction, contacts, and the equilibrium solver's settings
  // Worker threads, 0 for one per hardware thread; the bounds do not depend on it.
  int threads = 0;
  // Solve one block per orbit of the problem's symmetries (false: every
  // block, for checking them).
  bool use_symmetry = true;
  // The blocks whose bounds are wanted (0-based), or every block when
  // empty: on a model without symmetry the cost is per block asked.
  std::vector<int> blocks{};
};

struct LoadCapacity {
  // Per block, multiples of its own weight (dimensionless, >= 0): the
  // structure stands for every multiple in [min, max] (a feasible set is an
  // interval). max is +infinity when no weight is too much (e.g. a block
  // resting on a support). Both NaN for supports, floating blocks, blocks
  // without weight, blocks whose program is infeasible at every multiple
  // (the rest cannot stand whatever this block weighs), and blocks not
  // asked (LoadCapacitySettings::blocks).
  std::vector<double> min, max;
  // The structure stands as it is (every multiple 1): the as-built
  // analysis's certified verdict (3D, Coulomb friction), else the
  // as-built program's feasibility.
  bool stable = false;
  // optimal, or the failure of the first block (in block order) whose
  // programs failed (stopped on the iteration limit, numerical_difficulties,
  // unexpected); that block's bounds are NaN, the others stand.
  // interrupted (Ctrl-C or a sandbox deadline): the blocks not done are
  // NaN, and stable is false (no verdict).
  MarginStatus status = MarginStatus::optimal;
  // The problem's symmetries used (analysis/problem_symmetry.hpp; 1: none,
  // or not searched): one block of each orbit is solved and its bounds
  // are its orbit's.
  int symmetries = 1;
  int programs = 0;            // linear programs and equilibrium solves
  int simplex_iterations = 0;  // simplex pivots, barrier and interior-point iterations over all of them
  double seconds = 0.0;
};

// Throws InvalidArgument for bad analysis options (as analyze_equilibrium)
// and for blocks asked out of range or twice.
// progress: blocks solved (core/progress.hpp; none when empty).
LoadCapacity load_capacity(const Structure& structure, const LoadCapacitySettings& settings,
                           const ProgressCount& progress = {});

}  // namespace ashlar
