// Where the methods disagree, and which verdict to believe.
//
// The two static methods bracket the truth of the rigid-block model with
// Coulomb joints that slide without dilatancy:
//   - the equilibrium method's "unstable" (converged) is certain: no
//     compression-only equilibrium within the friction cones exists, so
//     nothing holds the structure up;
//   - the kinematic method's "stable" is certain too: forces within the
//     cones of compressions the loads press in from no prestress exist.
// Between them (equilibrium stands, kinematic falls or gives no verdict) the
// static methods cannot decide: the kinematic answer is the fixed point its
// rounds reach from no prestress, a local answer. There the arbiter is the
// physics itself: rigid-block dynamics from rest under the same friction
// and contacts (dynamics/simulation.hpp), with the coupled rigid-block
// analysis (cra.hpp), when asked for, as a further opinion that decides
// only when the dynamics does not run or gives no verdict.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "analysis/kinematic.hpp"
#include "analysis/load_factor.hpp"
#include "core/enum_names.hpp"
#include "dynamics/simulation.hpp"

namespace ashlar {

// When a further opinion (the dynamics, CRA) runs.
enum class OpinionWhen { never, on_disagreement, always };

struct ComparisonSettings {
  // The dynamics from rest: when it runs, and how (its friction and contact
  // options are replaced by the analysis settings'). By default a quarter
  // of a second: a block whose fall starts at 0.1 % of g (of its
  // mechanism's acceleration) moves 0.3 mm, past moved_fraction of a 0.3 m
  // block, within it.
  OpinionWhen dynamics = OpinionWhen::on_disagreement;
  SimulationOptions simulation = [] {
    SimulationOptions options;
    options.duration = 0.25;
    return options;
  }();
  // CRA (method cra, with the analysis settings' cra settings): asked for
  // only, since on hundreds of blocks it takes minutes and its exact
  // program may not converge (cra.hpp).
  OpinionWhen cra = OpinionWhen::never;
  // The margin: the least friction coefficient under which the equilibrium
  // method finds the structure standing (friction_demand), to this relative
  // tolerance; 0: not computed.
  double margin_tolerance = 1e-2;
};

// Which opinion decided the arbiter's verdict: the equilibrium method (a
// fall it proves), both static methods (when they agree on standing), the
// dynamics, or CRA.
enum class DecidedBy { equilibrium, both, dynamics, cra };
inline constexpr EnumNames<DecidedBy, 4> kDecidedByNames{{{{DecidedBy::equilibrium, "equilibrium"},
                                                           {DecidedBy::both, "both"},
                                                           {DecidedBy::dynamics, "dynamics"},
                                                           {DecidedBy::cra, "cra"}}}};

// The arbiter's answer: one verdict, which opinion decided it (none
// without a verdict), and why with the evidence (one sentence); each
// opinion's own verdict; the dynamics' largest displacement and the
// equilibrium method's friction demand when they ran (NaN otherwise).
struct Arbitration {
  Verdict verdict = Verdict::no_verdict;
  bool interrupted = false;  // an opinion was stopped (Ctrl-C, a deadline): no verdict
  std::optional<DecidedBy> decided_by;
  std::string reason;
  Verdict equilibrium = Verdict::no_verdict, kinematic = Verdict::no_verdict;
  std::optional<Verdict> dynamics, cra;   // when they ran
  double displacement = std::numeric_limits<double>::quiet_NaN();  // m
  int displaced_block = -1;                                        // 0-based, -1 when nothing moved
  double friction = 0.0;                                           // the comparison's mu
  double friction_demand = std::numeric_limits<double>::quiet_NaN();
};

struct MethodComparison {
  EquilibriumResult equilibrium, kinematic;
  std::optional<EquilibriumResult> cra;      // when it ran
  std::optional<SimulationResult> dynamic;   // when it ran
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
  // The equilibrium method's friction demand (when margin_tolerance > 0):
  // mu / demand.friction is how far friction can fall before even that
  // method finds no way to stand (the kinematic demand can be higher).
  std::optional<FrictionDemand> margin;

  Arbitration arbitration;
};

// What the dynamics says: stands (nothing moved, at rest at the end),
// settles, falls (moved and still moving at the end), no verdict
// (interrupted, or still moving without having moved: too short a run).
Verdict verdict_of(const SimulationResult& result);

// Both static methods (settings.method is ignored), the further opinions
// `comparison` asks for, and the arbiter's verdict. Throws InvalidArgument
// for bad settings, as analyze_equilibrium and simulate.
MethodComparison compare_methods(const Structure& structure, const AnalysisSettings& settings,
                                 const ComparisonSettings& comparison = {});

}  // namespace ashlar
