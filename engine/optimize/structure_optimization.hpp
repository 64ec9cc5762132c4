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
#include "analysis/equilibrium_analysis.hpp"
#include "analysis/load_factor.hpp"
#include "analysis/structural_gradient.hpp"
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

// ----------------------------------------------------------------------------
// Optimisation to a margin: the least material whose margin reaches a target.

// What must reach the target.
enum class MarginKind {
  stable,            // the equilibrium analysis's verdict
  load_factor,       // ashlar.load_factor's factor >= the value, and stable unloaded
  geometric_factor,  // still stable with one parameter divided by the value
};
inline constexpr EnumNames<MarginKind, 3> kMarginKindNames{{{{MarginKind::stable, "stable"},
                                                            {MarginKind::load_factor, "load_factor"},
                                                            {MarginKind::geometric_factor, "geometric_factor"}}}};

struct MarginTarget {
  MarginKind kind = MarginKind::stable;
  // load_factor: the factor (>= 0); geometric_factor: the factor (> 0).
  double value = 0.0;
  // load_factor: the pattern and direction; its `problem` is replaced by the
  // analysis settings' problem.
  LoadFactorSettings load;
  // geometric_factor: the parameter divided by the value (the thickness of
  // an arch: Heyman's geometric factor is the thickness over the least that
  // stands).
  int parameter = 0;
};

// The material minimised (free blocks only: supports are ground).
enum class Material {
  volume,  // m^3
  weight,  // N: mass x 9.81
};
inline constexpr EnumNames<Material, 2> kMaterialNames{{{{Material::volume, "volume"}, {Material::weight, "weight"}}}};

// The free blocks' volume or weight.
double material_of(const Structure& s, Material material);

// Whether a design stands, as a margin check (optimizer.hpp): the analysis
// penalty is the violation. A verdict-only analysis when no gradient is
// wanted, else the structural gradient, whose derivatives `to_variables`
// maps to the optimiser's variables (not called where there is no
// equilibrium at all: short of the target, with no gradient).
class StabilityCheck {
public:
  explicit StabilityCheck(const AnalysisSettings& analysis);
  MarginCheck operator()(const Structure& s, bool gradient,
                         const std::function<Eigen::VectorXd(const StructuralGradient&)>& to_variables);

private:
  AnalysisSequence analyses_, verdicts_;
};

// Minimises the material of generate(p) over lower <= p <= upper among the
// parameters whose margin reaches `target` (optimize_parameters_to_target):
// the material's gradient by central differences of the generator (no
// analysis); the margin's violation where it falls short is the analysis
// penalty (stable, geometric_factor) with its structural gradient chained
// through the generator, or the target less the load factor, its gradient
// by central differences of load factors (step 1e-5 x max(1, |p|)). The
// verdicts of the bisection's probes are the analysis's with verdict_only.
// Throws InvalidArgument for a bad target (a negative load factor, a
// geometric factor <= 0, a parameter out of range) and as optimize_generated.
GeneratedOptimization optimize_generated_to_target(const StructureGenerator& generate,
                                                   const std::vector<std::string>& names,
                                                   const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                                   const Eigen::VectorXd& start, const AnalysisSettings& analysis,
                                                   const MarginTarget& target, Material material,
                                                   const OptimizeSettings& settings);

// Fabrication conditions of a shape optimised to a target.
struct ShapeFabrication {
  // Curves of positions in order (e.g. an arch's intrados, one position per
  // joint): smooth_weight x the sum over each curve of the squared second
  // differences |x[k-1] - 2 x[k] + x[k+1]|^2 (m^2) is added to the objective
  // (smooth_weight in the objective's units per m^2). 0: none.
  double smooth_weight = 0.0;
  std::vector<std::vector<PositionRef>> smooth_curves;
  // Every contact between blocks at least this wide (m; least_joint_width):
  // a narrower design is rejected. 0: none.
  double min_thickness = 0.0;
};

// The sum over the curves of the squared second differences (m^2).
double second_differences(const DesignPoint& design, const std::vector<std::vector<PositionRef>>& curves);

// The least width of the contacts of s (m): contact_width of each contact
// polygon, its least caliper width (a rectangular joint's shorter side: an
// arch's thickness at the joint when the arch is deeper than thick).
// Infinite when there is no contact.
double least_joint_width(const Structure& s, const ContactOptions& contact);

// Minimises the material (plus the smoothing penalty) over the vertices of
// `s` within `constraints` among the designs that stand, by
// optimize_parameters_to_target in the design space's reduced variables
// through one chart centred at the start (a design that cannot be made
// planar, or that the design space or min_thickness rejects, counts as not
// standing). The margin's normal is the analysis penalty's structural
// gradient. Throws as optimize_structure, and InvalidArgument for a curve
// position out of range or a start narrower than min_thickness.
StructureOptimization optimize_structure_to_target(const Structure& s, const DesignConstraints& constraints,
                                                   const AnalysisSettings& analysis, Material material,
                                                   const ShapeFabrication& fabrication,
                                                   const OptimizeSettings& settings);

}  // namespace ashlar
