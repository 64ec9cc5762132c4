#include "analysis/kinematic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "analysis/equilibrium_analysis.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"

namespace ashlar {
namespace {

// Damping of the rounds: the largest and smallest share of a round's
// change taken; halved when the change turned back, raised again while it
// keeps its direction.
constexpr double kFullStep = 1.0, kLeastStep = 1.0 / 256;
constexpr double kStepGrowth = 1.25;
// Compressions are counted from this (scaled: a fraction of the mean block
// weight) up: below, they are the solver's rounding, not forces the loads
// press into a joint. Where
// nothing presses, the QP's tiny regularisation leaves compressions of
// about 3e-4 (a flat arch of five voussoirs), and friction from them would
// feed the very moments that create them, a loop that only prestress could
// start.
constexpr double kLeastCompression = 1e-3;

// Whether the friction at every contact vertex of x (scaled) is within the
// pyramid of mu times the vertex's own compression, to `tolerance` (scaled
// force): the given-strength rows with mu c in place of the strength.
bool within_own_cones(const EquilibriumProblem& problem, const Eigen::VectorXd& x, double mu, double tolerance) {
  const GroupRules& rules = problem.rules[static_cast<int>(GroupKind::contact_vertex)];
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    const double compression = std::max(0.0, x(4 * k) - kLeastCompression);
    for (Eigen::Index row = 2; row < rules.rows.rows(); ++row) {
      const double reach = rules.bound_coefficients(row) * mu * compression;
      if (rules.rows(row, 2) * x(4 * k + 2) + rules.rows(row, 3) * x(4 * k + 3) + reach < -tolerance) return false;
    }
  }
  return true;
}

}  // namespace

EquilibriumResult analyze_kinematic(const Structure& structure, const AnalysisSettings& settings) {
  const auto start = Clock::now();
  if (settings.max_rounds < 1) {
    throw InvalidArgument("max_rounds must be an integer >= 1, got " + std::to_string(settings.max_rounds));
  }
  if (!(settings.round_tolerance > 0.0) || !std::isfinite(settings.round_tolerance)) {
    throw InvalidArgument("round_tolerance must be a finite number > 0");
  }
  AnalysisSettings strength_settings = settings;
  strength_settings.problem.friction_law = FrictionLaw::given_strength;
  strength_settings.verdict_only = false;  // each round needs its optimum's compressions
  EquilibriumAnalysis analysis(structure, strength_settings);
  const double mu = settings.problem.friction;
  const int vertices = analysis.problem().contact_vertex_count;
  // The strengths g solve g = T(g): mu times the compressions of the QP with
  // strengths g. Plain iteration diverges where friction and normal force
  // trade against each other steeply (a wedge with faces 15 degrees from
  // vertical and mu = 0.3: T's slope is -mu cot 15 = -1.1), so each round
  // takes a share of the change, halved whenever the change turned back
  // (for a slope -s the rounds contract once the share is below 2 / (1 + s)).
  // Extrapolating schemes (Anderson mixing) were tried: they amplify the
  // solver's noise in compressions that should be zero (a flat arch with
  // vertical joints) and never settle.
  double share = kFullStep;
  Eigen::VectorXd strength = Eigen::VectorXd::Zero(vertices), next(vertices), last_step = Eigen::VectorXd::Zero(vertices);
  EquilibriumResult result;
  int iterations = 0, factorizations = 0;
  AnalysisTimings timings;
  for (int round = 1;; ++round) {
    result = analysis.solve(round > 1);
    iterations += result.iterations;
    factorizations += result.factorizations;
    timings.setup += result.timings.setup;
    timings.assembly += result.timings.assembly;
    timings.factorization += result.timings.factorization;
    timings.solve += result.timings.solve;
    result.rounds = round;
    // Without friction rows (mu infinite) there is nothing to settle;
    // without an answer or with floating blocks, nothing to go on.
    if (!std::isfinite(mu) || vertices == 0 || has_no_answer(result.status) || !result.floating_blocks.empty()) break;
    const Eigen::VectorXd& x = analysis.solution().x;
    // Soft: a threshold that switched would make the rounds dither there.
    for (int k = 0; k < vertices; ++k) next(k) = mu * std::max(0.0, x(4 * k) - kLeastCompression);
    // Scaled forces are in mean block weights: the tolerance is absolute.
    const double change = (next - strength).lpNorm<Eigen::Infinity>();
    if (change <= settings.round_tolerance) break;
    // A stable round whose friction at every vertex is within mu times the
    // compression that vertex has settles the verdict: those forces are an
    // equilibrium of the kind the fixed point is, without prestress (each
    // round's least-energy forces) and within Coulomb's cone of their own
    // compressions. Later rounds would only polish the strengths.
    if (result.stable && within_own_cones(analysis.problem(), x, mu, settings.round_tolerance)) break;
    if (round >= settings.max_rounds) {
      result.status = SolverStatus::max_iterations;
      result.stable = false;
      result.borderline = false;
      break;
    }
    const Eigen::VectorXd step = next - strength;
    share = step.dot(last_step) < 0.0 ? std::max(kLeastStep, 0.5 * share) : std::min(kFullStep, kStepGrowth * share);
    last_step = step;
    strength += share * step;
    analysis.set_shear_strengths(std::vector<double>(strength.data(), strength.data() + vertices));
  }  // The infeasibility the equilibrium method measures in tension is here
  // the virtual loads that the joints could not carry, over the weight.
  if (std::isfinite(result.infeasibility) && !result.stable) {
    const EquilibriumProblem& problem = analysis.problem();
    const Eigen::VectorXd& x = analysis.solution().x;
    double virtual_loads = 0.0;
    for (size_t k = 0; k < problem.groups.size(); ++k) {
      const ForceGroup& g = problem.groups[k];
      if (g.kind != GroupKind::slack) continue;
      virtual_loads += std::abs((x(4 * k) - x(4 * k + 1)) * g.on_a(g.component, 0));
    }
    result.infeasibility = virtual_loads / std::max(problem.body_count, 1);
  }
  result.method = AnalysisMethod::kinematic;
  result.iterations = iterations;
  result.factorizations = factorizations;
  result.timings = timings;
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace ashlar
