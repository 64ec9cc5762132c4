// optimize_structure_to_target: the least material over a structure's
// vertices among the designs that stand (see structure_optimization.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "analysis/equilibrium_analysis.hpp"
#include "analysis/structural_gradient.hpp"
#include "core/error.hpp"
#include "core/text.hpp"
#include "optimize/planar_chart.hpp"
#include "optimize/structure_optimization.hpp"
#include "structure/contact_detection.hpp"

namespace ashlar {
namespace {

const Vec3& position(const DesignPoint& design, const PositionRef& ref) {
  return ref.block == PositionRef::kFreePoint ? design.points[ref.index] : design.block_vertices[ref.block][ref.index];
}

Vec3& position(DesignPoint& design, const PositionRef& ref) {
  return ref.block == PositionRef::kFreePoint ? design.points[ref.index] : design.block_vertices[ref.block][ref.index];
}

DesignPoint zero_like(const DesignPoint& design) {
  DesignPoint zero = design;
  for (auto& vertices : zero.block_vertices) std::fill(vertices.begin(), vertices.end(), Vec3::Zero());
  std::fill(zero.points.begin(), zero.points.end(), Vec3::Zero());
  return zero;
}

}  // namespace

double second_differences(const DesignPoint& design, const std::vector<std::vector<PositionRef>>& curves) {
  double sum = 0.0;
  for (const auto& curve : curves) {
    for (size_t k = 1; k + 1 < curve.size(); ++k) {
      sum += (position(design, curve[k - 1]) - 2.0 * position(design, curve[k]) + position(design, curve[k + 1]))
                 .squaredNorm();
    }
  }
  return sum;
}

double least_joint_width(const Structure& s, const ContactOptions& contact) {
  double least = std::numeric_limits<double>::infinity();
  for (const Interface& joint : *s.interfaces(contact)) {
    Loop2 outer;
    for (const Vec3& p : joint.vertices) outer.emplace_back(joint.u.dot(p - joint.center), joint.v.dot(p - joint.center));
    least = std::min(least, contact_width(outer, joint.area));
  }
  return least;
}

StructureOptimization optimize_structure_to_target(const Structure& s, const DesignConstraints& constraints,
                                                   const AnalysisSettings& analysis, Material material,
                                                   const ShapeFabrication& fabrication,
                                                   const OptimizeSettings& settings) {
  s.require_detected_interfaces("optimize");
  if (!(std::isfinite(fabrication.smooth_weight) && fabrication.smooth_weight >= 0.0)) {
    throw InvalidArgument("smooth.weight: must be a finite number >= 0, got " +
                          message_number(fabrication.smooth_weight, kGivenValueDigits));
  }
  if (!(std::isfinite(fabrication.min_thickness) && fabrication.min_thickness >= 0.0)) {
    throw InvalidArgument("min_thickness: must be a finite number >= 0 (m), got " +
                          message_number(fabrication.min_thickness, kGivenValueDigits));
  }
  const DesignPoint start = design_of(s);
  for (const auto& curve : fabrication.smooth_curves) {
    for (const PositionRef& ref : curve) {
      const bool valid = ref.block == PositionRef::kFreePoint
                             ? ref.index >= 0 && ref.index < static_cast<int>(start.points.size())
                             : ref.block >= 0 && ref.block < s.size() && ref.index >= 0 &&
                                   ref.index < static_cast<int>(start.block_vertices[ref.block].size());
      if (!valid) throw InvalidArgument("smooth: a curve position is out of range");
    }
  }
  const double narrowest = least_joint_width(s, analysis.problem.contact);
  if (narrowest < fabrication.min_thickness) {
    throw InvalidArgument("min_thickness: the structure's narrowest joint is " +
                          message_number(narrowest, kGivenValueDigits) + " m, below min_thickness " +
                          message_number(fabrication.min_thickness, kGivenValueDigits) + " m");
  }
  std::vector<std::vector<FaceLoop>> faces;
  for (int i = 0; i < s.size(); ++i) faces.push_back(s.block(i).faces());
  const DesignSpace space(faces, start, constraints);
  const PlanarChart chart(space, space.start());
  // The admissible design at z (planar, within the constraints and
  // min_thickness), or a GeometryError: it then counts as not standing.
  std::shared_ptr<Structure> current;  // alive while its analysis is
  const auto design_at = [&](const Eigen::VectorXd& z) {
    const std::optional<Eigen::VectorXd> planar = chart.project(z);
    if (!planar) throw GeometryError("the step is too long to keep the faces planar");
    const std::string rejection = space.rejection(*planar);
    if (!rejection.empty()) throw GeometryError(rejection);
    return *planar;
  };
  const ParameterObjective objective = [&](const Eigen::VectorXd& z) {
    const Eigen::VectorXd y = design_at(z);
    const DesignPoint design = space.design(y);
    DesignPoint gradient = zero_like(design);
    ParameterEvaluation e;
    for (int i = 0; i < s.size(); ++i) {
      if (s.is_support(i)) continue;
      const double factor = material == Material::weight ? s.block(i).density() * kGravity : 1.0;
      e.value += factor * mass_properties(design.block_vertices[i], faces[i]).volume;
      const MassPropertiesGradient d = mass_properties_gradient(design.block_vertices[i], faces[i]);
      for (size_t k = 0; k < d.volume.size(); ++k) gradient.block_vertices[i][k] += factor * d.volume[k];
    }
    const double w = fabrication.smooth_weight;
    if (w > 0.0) {
      e.value += w * second_differences(design, fabrication.smooth_curves);
      for (const auto& curve : fabrication.smooth_curves) {
        for (size_t k = 1; k + 1 < curve.size(); ++k) {
          const Vec3 d = position(design, curve[k - 1]) - 2.0 * position(design, curve[k]) +
                         position(design, curve[k + 1]);
          position(gradient, curve[k - 1]) += 2.0 * w * d;
          position(gradient, curve[k]) -= 4.0 * w * d;
          position(gradient, curve[k + 1]) += 2.0 * w * d;
        }
      }
    }
    e.gradient = chart.pull_back(y, space.reduce(gradient));
    return e;
  };
  StabilityCheck stability(analysis);
  const MarginFunction stands = [&](const Eigen::VectorXd& z, bool gradient) {
    const Eigen::VectorXd y = design_at(z);
    current = with_design(s, space.design(y));
    if (fabrication.min_thickness > 0.0 &&
        least_joint_width(*current, analysis.problem.contact) < fabrication.min_thickness) {
      throw GeometryError("a joint is narrower than min_thickness");
    }
    return stability(*current, gradient, [&](const StructuralGradient& g) {
      DesignPoint d;
      d.block_vertices = g.block_vertices;
      for (size_t c = 0; c < g.cable_from.size(); ++c) {
        d.points.push_back(g.cable_from[c]);
        d.points.push_back(g.cable_to[c]);
      }
      return chart.pull_back(y, space.reduce(d));
    });
  };
  const ParameterResult found = optimize_parameters_to_target(space.lower_bounds(), space.upper_bounds(),
                                                              space.start(), objective, stands, settings);
  StructureOptimization out;
  OptimizeResult& result = out.result;
  result.design = space.design(design_at(found.parameters));
  result.status = found.status;
  result.stable = found.stable;
  result.history = found.history;
  result.evaluations = found.evaluations;
  result.message = found.message;
  out.structure = with_design(s, result.design);
  return out;
}

}  // namespace ashlar
