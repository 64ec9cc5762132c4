// Load capacity (Shin 2014, figures 5 and 6): for every block, the smallest
// and largest multiple of its own weight with which the structure still has
// a compression-only equilibrium that respects friction, every other block
// keeping its weight.
//
// The thesis searches by trial; here each bound is one linear program in
// the contact forces and the multiplier (feasibility of the equilibrium
// equations, friction pyramids, no tension), solved by the simplex method
// (COIN-OR Clp). All 2n programs share one constraint matrix and differ in
// one column's bounds and objective, so each starts from the previous
// optimal basis and takes a few pivots.
#pragma once

#include <string>
#include <vector>

#include "analysis/equilibrium.hpp"

namespace ashlar {

struct LoadCapacity {
  // Per block, multiples of its own weight (dimensionless, >= 0): the
  // structure stands for every multiple in [min, max] (a feasible set is an
  // interval). max is +infinity when no weight is too much (e.g. a block
  // resting on a support). Both NaN for supports, floating blocks, blocks
  // without weight, and blocks whose program is infeasible at every
  // multiple (the rest cannot stand whatever this block weighs).
  std::vector<double> min, max;
  // The structure stands as it is (every multiple 1).
  bool stable = false;
  // "optimal", or the first program's failure ("stopped" on the iteration
  // limit, "numerical difficulties"); the bounds of blocks solved before
  // a failure stay, the rest are NaN.
  std::string status = "optimal";
  int programs = 0;            // linear programs solved
  int simplex_iterations = 0;  // pivots over all of them
  double seconds = 0.0;
};

// Throws InvalidArgument for bad analysis options (as analyze_equilibrium).
LoadCapacity load_capacity(const Structure& structure, const AnalysisSettings& settings);

}  // namespace ashlar
