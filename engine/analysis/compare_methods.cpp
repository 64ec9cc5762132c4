#include "analysis/compare_methods.hpp"

#include <algorithm>

#include "analysis/equilibrium_analysis.hpp"

namespace ashlar {

MethodComparison compare_methods(const Structure& structure, const AnalysisSettings& settings,
                                 const SimulationOptions* dynamics) {
  MethodComparison out;
  AnalysisSettings equilibrium = settings;
  equilibrium.method = AnalysisMethod::equilibrium;
  out.equilibrium = analyze_equilibrium(structure, equilibrium);
  out.kinematic = analyze_kinematic(structure, settings);
  if (dynamics) {
    SimulationOptions options = *dynamics;
    options.friction = settings.problem.friction;
    options.contact = settings.problem.contact;
    out.dynamic = simulate(structure, options);
  }
  const EquilibriumResult& e = out.equilibrium;
  const EquilibriumResult& k = out.kinematic;
  if (e.vertex_forces.size() != k.vertex_forces.size()) return out;  // floating or without answers
  std::vector<MethodComparison::Borrowed> per(e.interfaces.size());
  double weight = 0.0;
  for (int i = 0; i < structure.size(); ++i) {
    if (!structure.is_support(i)) weight += kGravity * structure.block(i).mass();
  }
  for (size_t v = 0; v < e.vertex_forces.size(); ++v) {
    MethodComparison::Borrowed& entry = per[e.vertex_interface[v]];
    entry.friction += e.vertex_forces[v].tail<2>().norm();
    entry.available += settings.problem.friction * k.vertex_forces[v](0);
  }
  for (size_t i = 0; i < per.size(); ++i) {
    per[i].interface = static_cast<int>(i);
    if (per[i].friction - per[i].available > 1e-6 * weight) out.borrowed.push_back(per[i]);
  }
  std::sort(out.borrowed.begin(), out.borrowed.end(), [](const auto& x, const auto& y) {
    return x.friction - x.available > y.friction - y.available;
  });
  return out;
}

}  // namespace ashlar
