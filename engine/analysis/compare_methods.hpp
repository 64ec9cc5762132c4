// Where the methods disagree, and which verdict to believe.
#pragma once

#include <optional>
#include <vector>

#include "analysis/kinematic.hpp"
#include "dynamics/simulation.hpp"

namespace ashlar {

// Both methods on one structure (settings.method is ignored), and where
// they differ; with `dynamics`, also the simulation from rest (its friction
// and contact options replaced by the settings'): the dynamic verdict,
// moved or stayed.
struct MethodComparison {
  EquilibriumResult equilibrium, kinematic;
  // Interfaces whose friction in the equilibrium method's forces exceeds mu
  // times the compression the kinematic method finds there: friction that
  // rests on normal force no load presses in (N), by how much it exceeds,
  // largest first. Interfaces within 1e-6 of the total weight are left out.
  struct Borrowed {
    int interface = -1;              // index into structure.interfaces(contact)
    double friction = 0.0;           // sum over its vertices of |friction|, equilibrium method
    double available = 0.0;          // mu x the sum of its compressions, kinematic method
  };
  std::vector<Borrowed> borrowed;
  std::optional<SimulationResult> dynamic;  // when asked for
};
MethodComparison compare_methods(const Structure& structure, const AnalysisSettings& settings,
                                 const SimulationOptions* dynamics = nullptr);

}  // namespace ashlar
