#include "optimize/structure_optimization.hpp"

#include <algorithm>
#include <cmath>

#include "analysis/equilibrium_analysis.hpp"
#include "analysis/load_factor.hpp"
#include "analysis/structural_gradient.hpp"
#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar {

namespace {

// The structural gradient of `s`, which must have an equilibrium.
StructuralGradient gradient_of(AnalysisSequence& analyses, const Structure& s, const EvaluationReport& report) {
  const StructuralGradient g = structural_gradient(analyses.set_up(s), s);
  if (!g.valid) {
    throw Error("the structure has no equilibrium at all (" + std::string(status_name(g.analysis.status)) + ")");
  }
  if (report) report(g.analysis.penalty, g.analysis.infeasibility);
  return g;
}

// The derivative of every position with respect to one parameter, by central
// differences of the generator: the dot product with the structural
// gradient is the parameter's derivative.
double parameter_derivative(const Structure& base, const Structure& plus, const Structure& minus,
                            const StructuralGradient& g, double step, const std::string& name) {
  if (plus.size() != base.size() || minus.size() != base.size() ||
      plus.cables().size() != base.cables().size() || minus.cables().size() != base.cables().size()) {
    throw InvalidArgument("parameter '" + name +
                          "' changes the number of blocks or cables; only parameters that move "
                          "vertices can be optimised");
  }
  double sum = 0.0;
  for (int i = 0; i < base.size(); ++i) {
    const std::vector<Vec3>& p = plus.block(i).vertices();
    const std::vector<Vec3>& m = minus.block(i).vertices();
    if (p.size() != g.block_vertices[i].size() || m.size() != p.size()) {
      throw InvalidArgument("parameter '" + name + "' changes the vertex count of block " + std::to_string(i + 1));
    }
    for (size_t k = 0; k < p.size(); ++k) sum += g.block_vertices[i][k].dot(p[k] - m[k]);
  }
  for (size_t c = 0; c < base.cables().size(); ++c) {
    sum += g.cable_from[c].dot(plus.cables()[c].from.point - minus.cables()[c].from.point);
    sum += g.cable_to[c].dot(plus.cables()[c].to.point - minus.cables()[c].to.point);
  }
  return sum / (2.0 * step);
}

// The penalty's derivative with respect to each parameter at `values`,
// whose structure `base` has the structural gradient g.
Eigen::VectorXd parameter_gradient(const StructureGenerator& generate, const std::vector<std::string>& names,
                                   const Eigen::VectorXd& values, const Structure& base, const StructuralGradient& g) {
  Eigen::VectorXd gradient(values.size());
  for (Eigen::Index j = 0; j < values.size(); ++j) {
    const double step = 1e-6 * std::max(1.0, std::abs(values(j)));
    Eigen::VectorXd plus = values, minus = values;
    plus(j) += step;
    minus(j) -= step;
    gradient(j) = parameter_derivative(base, *generate(plus), *generate(minus), g, step, names[j]);
  }
  return gradient;
}

// Central differences of f at x, each step relative * max(1, |x_j|).
Eigen::VectorXd central_differences(const std::function<double(const Eigen::VectorXd&)>& f, const Eigen::VectorXd& x,
                                    double relative) {
  Eigen::VectorXd derivative(x.size());
  for (Eigen::Index j = 0; j < x.size(); ++j) {
    const double step = relative * std::max(1.0, std::abs(x(j)));
    Eigen::VectorXd plus = x, minus = x;
    plus(j) += step;
    minus(j) -= step;
    derivative(j) = (f(plus) - f(minus)) / (2 * step);
  }
  return derivative;
}

}  // namespace

DesignPoint design_of(const Structure& s) {
  DesignPoint design;
  for (int i = 0; i < s.size(); ++i) design.block_vertices.push_back(s.block(i).vertices());
  for (const Cable& cable : s.cables()) {
    design.points.push_back(cable.from.point);
    design.points.push_back(cable.to.point);
  }
  return design;
}

std::shared_ptr<Structure> with_design(const Structure& s, const DesignPoint& design) {
  auto out = std::make_shared<Structure>();
  for (int i = 0; i < s.size(); ++i) {
    const Block& block = s.block(i);
    out->add(std::make_shared<const Block>(design.block_vertices[i], block.faces(), block.density(), block.name(),
                                           block.planarity()),
             s.is_support(i), s.name(i));
  }
  out->set_planar(s.planar());
  for (const PointLoad& load : s.loads()) out->add_load(load);
  for (size_t c = 0; c < s.cables().size(); ++c) {
    Cable cable = s.cables()[c];
    cable.from.point = design.points[2 * c];
    cable.to.point = design.points[2 * c + 1];
    out->add_cable(cable);
  }
  return out;
}

void hold_faces_on_fixed_blocks(const Structure& s, DesignConstraints& constraints) {
  std::vector<bool> fixed(s.size(), false);
  for (int block : constraints.fixed_blocks) fixed[block] = true;
  const double tolerance = 1e-6 * s.bounds().diagonal();
  const std::shared_ptr<const std::vector<Interface>> interfaces = s.interfaces();
  for (const Interface& contact : *interfaces) {
    if (fixed[contact.a] == fixed[contact.b]) continue;
    const int free_block = fixed[contact.a] ? contact.b : contact.a;
    const std::vector<Vec3>& vertices = s.block(free_block).vertices();
    for (size_t k = 0; k < vertices.size(); ++k) {
      if (std::abs(contact.normal.dot(vertices[k] - contact.center)) <= tolerance) {
        constraints.fixed.push_back(PositionRef::vertex(free_block, static_cast<int>(k)));
      }
    }
  }
}

StructureOptimization optimize_structure(const Structure& s, const DesignConstraints& constraints,
                                         const AnalysisSettings& analysis, const OptimizeSettings& settings,
                                         const EvaluationReport& report) {
  s.require_detected_interfaces("optimize");
  std::vector<std::vector<FaceLoop>> faces;
  for (int i = 0; i < s.size(); ++i) faces.push_back(s.block(i).faces());
  const DesignSpace space(std::move(faces), design_of(s), constraints);
  AnalysisSequence analyses(analysis, false);
  std::shared_ptr<Structure> current;  // alive while its analysis is
  const DesignObjective objective = [&](const DesignPoint& design) {
    current = with_design(s, design);
    const StructuralGradient g = gradient_of(analyses, *current, report);
    DesignEvaluation evaluation;
    evaluation.value = g.analysis.penalty;
    evaluation.stable = g.analysis.stable;
    evaluation.gradient.block_vertices = g.block_vertices;
    for (size_t c = 0; c < g.cable_from.size(); ++c) {
      evaluation.gradient.points.push_back(g.cable_from[c]);
      evaluation.gradient.points.push_back(g.cable_to[c]);
    }
    return evaluation;
  };
  StructureOptimization out;
  out.result = optimize_design(space, objective, settings);
  out.structure = with_design(s, out.result.design);
  return out;
}

GeneratedOptimization optimize_generated(const StructureGenerator& generate, const std::vector<std::string>& names,
                                         const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                         const Eigen::VectorXd& start, const AnalysisSettings& analysis,
                                         const OptimizeSettings& settings, const EvaluationReport& report) {
  AnalysisSequence analyses(analysis, false);
  std::shared_ptr<Structure> base;  // alive while its analysis is
  const ParameterObjective objective = [&](const Eigen::VectorXd& values) {
    base = generate(values);
    const StructuralGradient g = gradient_of(analyses, *base, report);
    ParameterEvaluation evaluation;
    evaluation.value = g.analysis.penalty;
    evaluation.stable = g.analysis.stable;
    evaluation.gradient = parameter_gradient(generate, names, values, *base, g);
    return evaluation;
  };
  GeneratedOptimization out;
  out.result = optimize_parameters(lower, upper, start, objective, settings);
  out.structure = generate(out.result.parameters);
  return out;
}

double material_of(const Structure& s, Material material) {
  double sum = 0.0;
  for (int i = 0; i < s.size(); ++i) {
    if (s.is_support(i)) continue;
    sum += material == Material::weight ? s.block(i).mass() * kGravity : s.block(i).volume();
  }
  return sum;
}

StabilityCheck::StabilityCheck(const AnalysisSettings& analysis)
    : analyses_(analysis, false), verdicts_([&] {
        AnalysisSettings verdict = analysis;
        verdict.verdict_only = true;
        return verdict;
      }(), false) {}

MarginCheck StabilityCheck::operator()(const Structure& s, bool gradient,
                                       const std::function<Eigen::VectorXd(const StructuralGradient&)>& to_variables) {
  MarginCheck m;
  if (!gradient) {
    const EquilibriumResult r = verdicts_.analyze(s);
    m.feasible = r.stable;
    m.violation = r.stable ? 0.0 : r.penalty;
    return m;
  }
  const StructuralGradient g = structural_gradient(analyses_.set_up(s), s);
  m.feasible = g.analysis.stable;
  m.violation = g.analysis.stable ? 0.0 : g.analysis.penalty;
  if (g.valid) m.violation_gradient = to_variables(g);
  return m;
}

GeneratedOptimization optimize_generated_to_target(const StructureGenerator& generate,
                                                   const std::vector<std::string>& names,
                                                   const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                                                   const Eigen::VectorXd& start, const AnalysisSettings& analysis,
                                                   const MarginTarget& target, Material material,
                                                   const OptimizeSettings& settings) {
  const Eigen::Index n = start.size();
  if (target.kind == MarginKind::load_factor && !(std::isfinite(target.value) && target.value >= 0.0)) {
    throw InvalidArgument("target.load_factor: must be a finite number >= 0, got " +
                          message_number(target.value, kGivenValueDigits));
  }
  if (target.kind == MarginKind::geometric_factor) {
    if (!(std::isfinite(target.value) && target.value > 0.0)) {
      throw InvalidArgument("target.geometric_factor: must be a finite number > 0, got " +
                            message_number(target.value, kGivenValueDigits));
    }
    if (target.parameter < 0 || target.parameter >= n) {
      throw InvalidArgument("target.parameter: " + std::to_string(target.parameter + 1) +
                            " is out of range (there are " + std::to_string(n) + " parameters)");
    }
  }
  // The material, its gradient by central differences of the generator.
  const ParameterObjective objective = [&](const Eigen::VectorXd& values) {
    ParameterEvaluation e;
    e.value = material_of(*generate(values), material);
    e.gradient = central_differences([&](const Eigen::VectorXd& v) { return material_of(*generate(v), material); },
                                     values, 1e-6);
    return e;
  };
  StabilityCheck stability(analysis);
  std::shared_ptr<Structure> base;  // alive while its analysis is
  const auto stands = [&](const Eigen::VectorXd& values, bool gradient) {
    base = generate(values);
    return stability(*base, gradient, [&](const StructuralGradient& g) {
      return parameter_gradient(generate, names, values, *base, g);
    });
  };
  LoadFactorSettings load = target.load;
  load.problem = analysis.problem;
  // The load factor of generate(values); throws when Clp fails.
  const auto factor_at = [&](const Eigen::VectorXd& values) {
    const LoadFactor f = load_factor(*generate(values), load);
    if (f.status != MarginStatus::optimal && f.status != MarginStatus::unbounded &&
        f.status != MarginStatus::infeasible) {
      throw Error(std::string("the load factor failed: ") + kMarginStatusNames.name(f.status));
    }
    return f;
  };
  MarginFunction margin;
  switch (target.kind) {
    case MarginKind::stable:
      margin = stands;
      break;
    case MarginKind::geometric_factor:
      margin = [&](const Eigen::VectorXd& values, bool gradient) {
        Eigen::VectorXd scaled = values;
        scaled(target.parameter) /= target.value;
        MarginCheck m = stands(scaled, gradient);
        if (m.violation_gradient.size()) m.violation_gradient(target.parameter) /= target.value;
        return m;
      };
      break;
    case MarginKind::load_factor:
      margin = [&](const Eigen::VectorXd& values, bool gradient) {
        const LoadFactor f = factor_at(values);
        if (!f.stable) {
          // It falls unloaded: the target plus the penalty, continuous with
          // the target less a factor of 0 where it starts to stand.
          MarginCheck m = stands(values, gradient);
          m.feasible = false;
          m.violation += target.value;
          return m;
        }
        MarginCheck m;
        m.margin = f.factor;
        m.feasible = f.factor >= target.value;
        m.violation = m.feasible ? 0.0 : target.value - f.factor;
        if (gradient) {
          // An unbounded factor on one side leaves that derivative unknown: 0.
          m.violation_gradient =
              -central_differences([&](const Eigen::VectorXd& v) { return factor_at(v).factor; }, values, 1e-5)
                   .unaryExpr([](double d) { return std::isfinite(d) ? d : -0.0; });
        }
        return m;
      };
      break;
  }
  GeneratedOptimization out;
  out.result = optimize_parameters_to_target(lower, upper, start, objective, margin, settings);
  out.structure = generate(out.result.parameters);
  return out;
}

}  // namespace ashlar
