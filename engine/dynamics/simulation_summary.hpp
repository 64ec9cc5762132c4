// A simulation's run as an engineer reports it: peak and residual
// displacement, drift, when the structure first moved and when it
// collapsed, and which blocks fell. Read from the recorded frames of a
// SimulationResult (simulation.hpp), so times are those of the frames:
// record every step (record_every = 1) for the step's resolution.
//
// Conventions: z is up (the default gravity); a block's displacement at a
// frame is the largest displacement of any of its vertices from where it
// started (as SimulationResult::displacement); its centroid's displacement
// is the motion of its centroid. Displacements are relative to the ground.
#pragma once

#include <optional>
#include <vector>

#include "dynamics/simulation.hpp"

namespace ashlar {

struct SummaryOptions {
  // A block has moved when a vertex of it has gone further than this
  // fraction of its bounding-box diagonal (as SimulationOptions).
  double moved_fraction = 1e-3;
  // A block has fallen when its centroid is lower than where it started by
  // more than this fraction of its smallest bounding-box extent (a block
  // that rocks about an edge raises its centroid; one that topples or
  // drops lowers it), > 0.
  double fall_fraction = 0.5;
  // Or when its centroid, which started at or above this height (m), has
  // gone below it; none: no level.
  std::optional<double> fall_level;
};

struct SimulationSummary {
  // Per block (0 for supports), m: the largest vertex displacement over the
  // run (every step), and at the last frame.
  std::vector<double> peak_displacement, residual_displacement;
  double peak = 0.0, residual = 0.0;          // their largest over the blocks (m)
  int peak_block = -1, residual_block = -1;   // 0-based; -1 when nothing moved
  // The first frame's time (s) at which some block had moved; none if none did.
  std::optional<double> first_movement;
  // The blocks that fell (0-based, in the order they fell, ties by index)
  // and the first frame's time (s) at which each had fallen.
  std::vector<int> fallen;
  std::vector<double> fall_times;
  // The first fall (s): the time of collapse; none when no block fell.
  std::optional<double> collapse_time;
};

// Throws InvalidArgument for options out of range or a result whose frames
// do not match the structure.
SimulationSummary summarize(const Structure& structure, const SimulationResult& result, const SummaryOptions& options);

// Block i's displacement (m, its vertices' largest) at every recorded frame.
std::vector<double> displacement_history(const Structure& structure, const SimulationResult& result, int block);

// Drift of a block or a course of blocks: the horizontal displacement of
// their centroids' mean from where it started, over its height above the
// base (the lowest vertex of any free block at the start), per frame.
struct Drift {
  double height = 0.0;          // m, the centroids' mean height above the base
  std::vector<double> values;   // per recorded frame, dimensionless
  double peak = 0.0;            // the largest over the frames
  double residual = 0.0;        // at the last frame
};

// Throws InvalidArgument when `blocks` is empty, names a support or a block
// out of range, or the centroids' mean is not above the base.
Drift drift(const Structure& structure, const SimulationResult& result, const std::vector<int>& blocks);

}  // namespace ashlar
