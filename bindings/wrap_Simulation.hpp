// Lua type "ashlar.Simulation": the outcome of ashlar.simulate (rigid-block
// dynamics). Its fields (moved, max_displacement, settled, steps, ...) are
// read on access; sim:trajectory(i), sim:export(path, opts), sim:summary(opts),
// sim:drift(blocks) and sim:chart(opts) are methods. Lua type
// "ashlar.GroundMotion": a recorded accelerogram (ashlar.ground_motion),
// callable as a ground_acceleration function.
#pragma once

#include <lua.hpp>

#include <cstddef>
#include <memory>
#include <string>

#include "dynamics/simulation.hpp"
#include "luax.hpp"
#include "study/study_progress.hpp"

namespace ashlar::lua {

// The option names of ashlar.simulate that a nested table (compare_methods'
// `dynamics`) also takes: all but friction and the contact options, which
// come from the comparison's.
#define ASHLAR_SIMULATION_OPTIONS                                                                          \
  "duration", "step", "theta", "restitution", "ground_acceleration", "ground_rotation", "ground_pivot",    \
      "gravity", "progress", "record_every", "search_distance", "moved_fraction", "settle_speed",         \
      "max_sweeps", "tolerance", "threads"

// The progress line of one run on stderr (redrawn in place on a terminal,
// a line every 10 s otherwise): updated as the run steps, closed with how
// it ended by finish(), or as stopped by an error when destroyed unfinished.
class SimulationProgress {
public:
  SimulationProgress(const std::string& label, std::size_t steps);
  ~SimulationProgress();
  SimulationProgress(const SimulationProgress&) = delete;
  SimulationProgress& operator=(const SimulationProgress&) = delete;

  void update(std::size_t done);
  void finish(const SimulationResult& result);

private:
  study::StudyProgress line_;
  std::size_t done_ = 0;
  bool finished_ = false;
};

// Simulation options from an option table that allows ASHLAR_SIMULATION_OPTIONS
// (friction and contact are left to the caller). A ground_acceleration or
// ground_rotation function is pushed on the stack (each must stay there
// while the simulation runs); with progress = true, `progress` gets the line that the run's
// progress callback draws, for the caller to finish.
SimulationOptions simulation_options(const OptionTable& options, const Structure& structure,
                                     std::shared_ptr<SimulationProgress>& progress);

// A new Simulation of `structure` (copied: the Lua structure may change
// afterwards) holding `result` of a run with that moved_fraction.
void luax_pushSimulation(lua_State* L, const Structure& structure, SimulationResult result,
                         double moved_fraction = SimulationOptions{}.moved_fraction);

void register_Simulation(lua_State* L);
// ashlar.simulate: set into the table on top of the stack.
void set_simulation_functions(lua_State* L);

}  // namespace ashlar::lua
