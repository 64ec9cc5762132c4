#include "analysis/structural_gradient.hpp"

#include <cmath>

#include "analysis/equilibrium_analysis.hpp"
#include "analysis/equilibrium_sensitivity.hpp"
#include "core/clock.hpp"
#include "geometry/block.hpp"
#include "structure/interface_gradient.hpp"

namespace ashlar {

namespace {

// Adds d(block_size)/d(vertex) times `scale`: size^2 = 4/n sum |p - mean|^2,
// whose derivative with respect to p_k is 8/n (p_k - mean).
void add_size_gradient(const Block& block, double scale, std::vector<Vec3>& gradient) {
  const std::vector<Vec3>& vertices = block.vertices();
  const double n = static_cast<double>(vertices.size());
  Vec3 mean = Vec3::Zero();
  for (const Vec3& p : vertices) mean += p;
  mean /= n;
  const double size = block_size(block);
  for (size_t k = 0; k < vertices.size(); ++k) {
    gradient[k] += scale * 4.0 * (vertices[k] - mean) / (n * size);
  }
}

}  // namespace

StructuralGradient structural_gradient(const Structure& structure,
                                       const AnalysisSettings& settings,
                                       const EquilibriumResult* warm_start) {
  EquilibriumAnalysis analysis(structure, settings);
  if (warm_start) analysis.set_starting_point(warm_start->solution);
  return structural_gradient(analysis, structure, warm_start != nullptr);
}

StructuralGradient structural_gradient(EquilibriumAnalysis& analysis, const Structure& structure,
                                       bool warm_start) {
  structure.require_detected_interfaces("gradient");
  StructuralGradient out;
  out.analysis = analysis.solve(warm_start);
  const EquilibriumProblem& problem = analysis.problem();
  const AnalysisSettings& settings = analysis.settings();
  const auto start = Clock::now();
  const int n = structure.size();
  const std::vector<Cable>& cables = structure.cables();
  out.block_vertices.resize(n);
  for (int i = 0; i < n; ++i) out.block_vertices[i].assign(structure.block(i).vertices().size(), Vec3::Zero());
  out.cable_from.assign(cables.size(), Vec3::Zero());
  out.cable_to.assign(cables.size(), Vec3::Zero());
  out.valid = std::isfinite(out.analysis.penalty);
  if (!out.valid) return out;

  const EquilibriumSensitivity sensitivity =
      equilibrium_sensitivity(structure, problem, analysis.solution());

  // Contact polygons and frames.
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces(settings.problem.contact);
  const std::vector<Interface>& interfaces = *interfaces_list;
  std::vector<InterfaceAdjoint> adjoints(interfaces.size());
  std::vector<int> next_vertex(interfaces.size(), 0);
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    const int f = problem.groups[k].source;
    InterfaceAdjoint& adjoint = adjoints[f];
    if (adjoint.vertices.empty()) adjoint.vertices.assign(interfaces[f].vertices.size(), Vec3::Zero());
    adjoint.vertices[next_vertex[f]++] = sensitivity.vertex_position[k];
    adjoint.normal += sensitivity.vertex_frame[k].col(0);
    adjoint.u += sensitivity.vertex_frame[k].col(1);
    adjoint.v += sensitivity.vertex_frame[k].col(2);
  }
  accumulate_interface_gradient(structure, settings.problem.contact, adjoints, out.block_vertices);

  // Weights and centroids, and the units they set: weight_unit is the
  // analysed bodies' weight per body, length_unit their mean block size.
  const double bodies = problem.body_count;
  const double d_weight_unit = sensitivity.weight_unit / bodies;
  int analysed_blocks = 0;
  for (int i = 0; i < n; ++i) analysed_blocks += problem.row_of_block[i] >= 0;
  for (int i = 0; i < n; ++i) {
    if (problem.row_of_block[i] < 0) continue;
    const Block& block = structure.block(i);
    const MassPropertiesGradient mass = mass_properties_gradient(block.vertices(), block.faces());
    const double weight_per_volume = block.density() * kGravity;
    std::vector<Vec3>& gradient = out.block_vertices[i];
    for (size_t k = 0; k < gradient.size(); ++k) {
      gradient[k] += (sensitivity.block_weight[i] + d_weight_unit) * weight_per_volume * mass.volume[k] +
                     mass.centroid[k].transpose() * sensitivity.block_centroid[i];
    }
    add_size_gradient(block, sensitivity.length_unit / analysed_blocks, gradient);
  }
  // Half a cable's weight counts in weight_unit for each analysed end.
  std::vector<int> analysed_ends(cables.size(), 0);
  for (const ForceGroup& group : problem.groups) {
    if (group.kind == GroupKind::cable || group.kind == GroupKind::bounded_cable) {
      analysed_ends[group.source] = (group.row_a >= 0) + (group.row_b >= 0);
    }
  }
  for (size_t c = 0; c < cables.size(); ++c) {
    const Vec3 along = (cables[c].to.point - cables[c].from.point).normalized();
    Vec3 d_to = 0.5 * analysed_ends[c] * cables[c].mass_per_length * kGravity * d_weight_unit * along;
    if (analysed_blocks == 0) d_to += sensitivity.length_unit / cables.size() * along;
    out.cable_to[c] = sensitivity.cable_to[c] + d_to;
    out.cable_from[c] = sensitivity.cable_from[c] - d_to;
  }

  // penalty = P / bodies.
  for (std::vector<Vec3>& gradient : out.block_vertices) {
    for (Vec3& g : gradient) g /= bodies;
  }
  for (Vec3& g : out.cable_from) g /= bodies;
  for (Vec3& g : out.cable_to) g /= bodies;
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace ashlar
