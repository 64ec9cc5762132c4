// Optimising structures, as ashlar.optimize does: the design of a structure
// (its blocks' vertices and cable end points), the default hold on faces
// that rest on fixed blocks, and the two objectives over an equilibrium
// analysis's penalty with its structural gradient: the vertices themselves
// (optimize_structure), or the parameters of a generator of structures
// (optimize_generated, its gradient by the chain rule through central
// differences of the generator).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "analysis/equilibrium.hpp"
#include "optimize/design_space.hpp"
#include "optimize/optimizer.hpp"
#include "structure/structure.hpp"

namespace ashlar {

// The design of `s`: its blocks' vertices, then both end points of every
// cable as free points (from, to).
DesignPoint design_of(const Structure& s);

// `s` with the positions of `design`: same names, supports, loads, cables.
std::shared_ptr<Structure> with_design(const Structure& s, const DesignPoint& design);

// ashlar.optimize's default: a free block's face resting on a fixed block
// (a voussoir's springing on its abutment) stays where it is, its vertices
// added to constraints.fixed (within 1e-6 of the structure's size of the
// contact plane), so the bearing a designer drew is kept. Without it the
// design space keeps them in the fixed face's plane, and the bearing may
// move or change size.
void hold_faces_on_fixed_blocks(const Structure& s, DesignConstraints& constraints);

// Told after every analysis of an objective: the penalty and the
// infeasibility it found.
using EvaluationReport = std::function<void(double penalty, double infeasibility)>;

struct StructureOptimization {
  OptimizeResult result;
  std::shared_ptr<Structure> structure;  // s at the result's design
};

// Minimises the analysis's penalty over the vertices of `s` (which must use
// detected interfaces) within `constraints`. One analysis object serves
// every step (the steps move vertices, not contacts). Throws Error when an
// analysis has no equilibrium at all, InvalidArgument for bad constraints.
StructureOptimization optimize_structure(const Structure& s, const DesignConstraints& constraints,
                                         const AnalysisSettings& analysis, const OptimizeSettings& settings,
                                         const EvaluationReport& report = {});

// A structure for parameter values (in the order of the names given with
// it); it must keep its blocks, cables and vertex counts as they change.
using StructureGenerator = std::function<std::shared_ptr<Structure>(const Eigen::VectorXd& values)>;

struct GeneratedOptimization {
  ParameterResult result;
  std::shared_ptr<Structure> structure;  // the generator's at the result's parameters
};

// Minimises the analysis's penalty over parameters in [lower, upper] from
// `start`. The gradient is the structural gradient dotted with each
// position's derivative, by central differences of the generator (step
// 1e-6 relative; no analysis involved). `names` name the parameters in
// errors. Throws InvalidArgument when a parameter changes the number of
// blocks, cables or vertices.
GeneratedOptimization optimize_generated(const StructureGenerator& generate, const std::vector<std::string>& names,
                                         const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                         const Eigen::VectorXd& start, const AnalysisSettings& analysis,
                                         const OptimizeSettings& settings, const EvaluationReport& report = {});

}  // namespace ashlar
