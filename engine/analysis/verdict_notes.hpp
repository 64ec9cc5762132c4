// What a verdict turns on, told with the result: the joints an unstable
// structure just misses, and warnings on a stable verdict that rests on
// friction at its limit. Cheap passes over one result: no second method runs.
#pragma once

#include "analysis/equilibrium.hpp"

namespace ashlar {

// The largest gap, as a fraction of the structure's size, reported as the
// contact a floating or failing block misses.
constexpr double kNearMiss = 0.01;

// How many failing blocks an unstable result names.
constexpr int kFailingBlocksShown = 10;

// Fills result.failing_blocks and failing_gaps (an unstable verdict with an
// answer and no floating block: its blocks that need the most tension and,
// within 1 % of the structure's size, the contact each misses) and
// result.warnings (a stable verdict of the equilibrium method whose forces
// use all the friction mu allows at some interfaces carrying over 1e-3 of
// the mean block weight, their vertices' forces summed: friction
// the method may borrow from normal force no load presses in, which the
// kinematic method and ashlar.compare_methods check). `result` must be an
// analysis of `structure` with `settings`.
void annotate_verdict(const Structure& structure, const AnalysisSettings& settings, EquilibriumResult& result);

}  // namespace ashlar
