#include "analysis/compare_methods.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "analysis/cra.hpp"
#include "analysis/equilibrium_analysis.hpp"
#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar {
namespace {

std::vector<MethodComparison::Borrowed> borrowed_friction(const Structure& structure, double friction,
                                                          const EquilibriumResult& e, const EquilibriumResult& k) {
  std::vector<MethodComparison::Borrowed> out;
  if (e.vertex_forces.size() != k.vertex_forces.size()) return out;  // floating or without answers
  std::vector<MethodComparison::Borrowed> per(e.interfaces.size());
  double weight = 0.0;
  for (int i = 0; i < structure.size(); ++i) {
    if (!structure.is_support(i)) weight += kGravity * structure.block(i).mass();
  }
  for (size_t v = 0; v < e.vertex_forces.size(); ++v) {
    MethodComparison::Borrowed& entry = per[e.vertex_interface[v]];
    entry.friction += e.vertex_forces[v].tail<2>().norm();
    entry.available += friction * k.vertex_forces[v](0);
  }
  for (size_t i = 0; i < per.size(); ++i) {
    per[i].interface = static_cast<int>(i);
    if (per[i].friction - per[i].available > 1e-6 * weight) out.push_back(per[i]);
  }
  std::sort(out.begin(), out.end(), [](const auto& x, const auto& y) {
    return x.friction - x.available > y.friction - y.available;
  });
  return out;
}

bool runs(OpinionWhen when, bool disagree) {
  return when == OpinionWhen::always || (when == OpinionWhen::on_disagreement && disagree);
}

// Runs a further opinion; one asked for only on disagreement that cannot
// run on this structure (cables, explicit interfaces) says why instead.
template <class Result>
std::optional<Result> opinion(OpinionWhen when, const std::function<Result()>& run, std::string& refused) {
  if (when == OpinionWhen::always) return run();
  try {
    return run();
  } catch (const InvalidArgument& e) {
    refused = e.what();
    return std::nullopt;
  }
}

std::string said(const EquilibriumResult& r) {
  const Verdict v = verdict_of(r);
  std::string text = kVerdictNames.name(v);
  if (v == Verdict::falls && r.status == SolverStatus::infeasible) {
    text += " (no compatible compression-only equilibrium)";
  } else if (v == Verdict::falls) {
    text += r.floating_blocks.empty() ? " (infeasibility " + message_number(r.infeasibility) + ")"
                                      : " (block " + std::to_string(r.floating_blocks[0] + 1) + " floats)";
  } else if (v == Verdict::no_verdict) {
    text += std::string(" (") + kSolverStatusNames.name(r.status) + ")";
  }
  return text;
}

std::string said(const SimulationResult& d, const Structure& structure) {
  if (d.status == SimulationStatus::interrupted) {
    return "no verdict (interrupted after " + message_number(d.time) + " s)";
  }
  const std::string moved = d.max_displacement_block < 0
                                ? "no block moved"
                                : structure.label(d.max_displacement_block) + " moved " +
                                      message_number(d.max_displacement) + " m";
  const Verdict v = verdict_of(d);
  const char* end = v == Verdict::falls         ? ", still moving"
                    : v == Verdict::settles      ? ", then came to rest"
                    : v == Verdict::no_verdict ? ", still moving: a longer run decides"
                                               : "";
  return std::string(kVerdictNames.name(v)) + " (from rest, " + moved + " in " + message_number(d.time) + " s" +
         end + ")";
}

}  // namespace

Verdict verdict_of(const SimulationResult& result) {
  if (result.status != SimulationStatus::completed) return Verdict::no_verdict;
  // Still moving at the end without having moved far: too short a run to tell.
  if (!result.moved) return result.settled ? Verdict::stands : Verdict::no_verdict;
  return result.settled ? Verdict::settles : Verdict::falls;
}

MethodComparison compare_methods(const Structure& structure, const AnalysisSettings& settings,
                                 const ComparisonSettings& comparison) {
  MethodComparison out;
  AnalysisSettings equilibrium = settings;
  equilibrium.method = AnalysisMethod::equilibrium;
  out.equilibrium = analyze_equilibrium(structure, equilibrium);
  out.kinematic = analyze_kinematic(structure, settings);
  out.borrowed = borrowed_friction(structure, settings.problem.friction, out.equilibrium, out.kinematic);
  const Verdict static_verdict = verdict_of(out.equilibrium);
  const Verdict kinematic_verdict = verdict_of(out.kinematic);
  // The static methods settle it when the equilibrium method proves a fall
  // or the kinematic method proves standing; otherwise they disagree (or
  // one gave no verdict).
  const bool decided = static_verdict == Verdict::falls || kinematic_verdict == Verdict::stands;
  const bool interrupted = out.equilibrium.status == SolverStatus::interrupted ||
                           out.kinematic.status == SolverStatus::interrupted;

  std::string dynamics_refused, cra_refused;
  if (!interrupted && runs(comparison.dynamics, !decided)) {
    SimulationOptions options = comparison.simulation;
    options.friction = settings.problem.friction;
    options.contact = settings.problem.contact;
    out.dynamic = opinion<SimulationResult>(
        comparison.dynamics, [&] { return simulate(structure, options); }, dynamics_refused);
  }
  if (!interrupted && runs(comparison.cra, !decided)) {
    AnalysisSettings cra = settings;
    cra.method = AnalysisMethod::cra;
    out.cra = opinion<EquilibriumResult>(
        comparison.cra, [&] { return analyze_cra(structure, cra); }, cra_refused);
  }

  // The verdict, and the evidence behind it.
  std::string evidence = "equilibrium method: " + said(out.equilibrium) + "; kinematic method: " + said(out.kinematic);
  if (out.dynamic) evidence += "; dynamics: " + said(*out.dynamic, structure);
  else if (!dynamics_refused.empty()) evidence += "; the dynamics cannot run: " + dynamics_refused;
  if (out.cra) evidence += "; CRA: " + said(*out.cra);
  else if (!cra_refused.empty()) evidence += "; CRA cannot run: " + cra_refused;
  Arbitration& a = out.arbitration;
  auto decide = [&](Verdict verdict, std::optional<DecidedBy> by, const std::string& why) {
    a.verdict = verdict;
    a.decided_by = by;
    a.reason = why + " (" + evidence + ")";
  };
  const Verdict dynamic_verdict = out.dynamic ? verdict_of(*out.dynamic) : Verdict::no_verdict;
  const Verdict cra_verdict = out.cra ? verdict_of(*out.cra) : Verdict::no_verdict;
  if (interrupted || (out.dynamic && out.dynamic->status == SimulationStatus::interrupted) ||
      (out.cra && out.cra->status == SolverStatus::interrupted)) {
    a.interrupted = true;
    decide(Verdict::no_verdict, std::nullopt, "interrupted");
  } else if (static_verdict == Verdict::falls) {
    decide(Verdict::falls, DecidedBy::equilibrium,
           out.equilibrium.floating_blocks.empty()
               ? "no compression-only equilibrium within the friction cones exists"
               : "a block touches nothing that leads to a support");
  } else if (kinematic_verdict == Verdict::stands) {
    decide(Verdict::stands, DecidedBy::both,
           "forces within the cones of the compressions the loads press in, from no prestress, balance every block");
  } else if (dynamic_verdict != Verdict::no_verdict) {
    decide(dynamic_verdict, DecidedBy::dynamics, "the static methods do not decide; the dynamics from rest does");
  } else if (cra_verdict != Verdict::no_verdict) {
    decide(cra_verdict, DecidedBy::cra, "the static methods do not decide and the dynamics gives no verdict; CRA does");
  } else {
    decide(Verdict::no_verdict, std::nullopt,
           out.dynamic || !dynamics_refused.empty() ? "the static methods do not decide, and neither the dynamics nor CRA gives a verdict"
                                                    : "the static methods do not decide, and no further opinion was asked for");
  }
  a.equilibrium = static_verdict;
  a.kinematic = kinematic_verdict;
  if (out.dynamic) {
    a.dynamics = dynamic_verdict;
    a.displacement = out.dynamic->max_displacement;
    a.displaced_block = out.dynamic->max_displacement_block;
  }
  if (out.cra) a.cra = cra_verdict;
  a.friction = settings.problem.friction;
  // The margin of a structure that stands.
  if (a.verdict == Verdict::stands && comparison.margin_tolerance > 0.0) {
    FrictionDemandSettings margin;
    margin.problem = settings.problem;
    margin.bracket_tolerance = comparison.margin_tolerance;
    out.margin = friction_demand(structure, margin);
    if (out.margin->status == MarginStatus::interrupted) {
      a.interrupted = true;
      decide(Verdict::no_verdict, std::nullopt, "interrupted");
    }
  }
  if (out.margin && out.margin->status == MarginStatus::optimal) {
    a.friction_demand = out.margin->friction;
    a.reason += "; friction demand by the equilibrium method " + message_number(out.margin->friction) +
                  " against mu " + message_number(settings.problem.friction);
  }
  return out;
}

}  // namespace ashlar
