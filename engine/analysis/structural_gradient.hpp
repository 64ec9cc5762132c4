// The structural gradient (Shin 2014, "Analytic structural gradient"): how
// the equilibrium penalty changes as the vertices of the blocks and the end
// points of the cables move, with the topology (which faces touch, which
// constraints are active) held fixed.
#pragma once

#include <vector>

#include "analysis/equilibrium.hpp"
#include "core/types.hpp"
#include "structure/structure.hpp"

namespace ashlar {

struct StructuralGradient {
  EquilibriumResult analysis;  // the analysis whose optimum was differentiated
  // d(analysis.penalty)/d(position), 1/m (penalty is dimensionless):
  std::vector<std::vector<Vec3>> block_vertices;  // [block][vertex], in Block::vertices() order
  std::vector<Vec3> cable_from, cable_to;         // per cable end point
  bool valid = false;       // false when the penalty is infinite (floating bodies, solver failure)
  double seconds = 0.0;     // wall time of the gradient after the analysis
};

// STRUCTURAL_GRADIENT  Analyses `structure` and differentiates its penalty.
//
// By the envelope theorem the optimum's multipliers give the derivative
// with respect to every piece of problem data (equilibrium_sensitivity);
// this chains it with how that data moves with the geometry: contact
// polygons and their frames (accumulate_interface_gradient), block weights
// and centroids (mass_properties_gradient), cable directions, lengths and
// weights, and the problem's units of force (mean weight per body) and
// length (mean block size). No second factorisation: the cost is linear in
// the model's size on top of one analysis.
//
// Where two blocks' vertices coincide the contact follows block a's vertex;
// the gradient is exact for moves that keep coincident vertices together
// (the optimiser's welded variables) and one-sided for moves that part them.
StructuralGradient structural_gradient(const Structure& structure,
                                       const AnalysisSettings& settings,
                                       const EquilibriumResult* warm_start = nullptr);

class EquilibriumAnalysis;
// The same on an analysis object (after its setup or update() with
// `structure`, the structure it was given): solved again, warm from its last
// solution when `warm_start`, reusing its symbolic factorisation.
StructuralGradient structural_gradient(EquilibriumAnalysis& analysis, const Structure& structure,
                                       bool warm_start = false);

}  // namespace ashlar
