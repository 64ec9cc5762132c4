#include "analysis/kinematic.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "analysis/equilibrium_analysis.hpp"
#include "analysis/load_factor.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/text.hpp"

namespace ashlar {
namespace {

// Damping of the rounds: the largest and smallest share of a round's
// change taken; halved when the change turned back, raised again while it
// keeps its direction.
constexpr double kFullStep = 1.0, kLeastStep = 1.0 / 256;
constexpr double kStepGrowth = 1.25;
// Compressions count from this fraction of the lighter free block's weight
// up: below, they are not forces the loads press into a joint but the
// solver's rounding. Where nothing presses, the QP's tiny regularisation
// leaves compressions up to 6e-4 of a block's weight (a flat arch of five
// voussoirs with vertical joints), and friction from them feeds the very
// moments that create them: a loop that grows by a third each round at
// mu = 0.9 and makes the arch stand on compression only prestress could
// start. 1e-3 let that seed through; at 1 % the friction of joints that
// carry less than 1 % of a block's weight is the method's resolution.
constexpr double kLeastCompression = 1e-2;

// A compression as the strengths count it: in full from `least` up, none
// below half of it, and linearly between (a threshold that switched would
// make the rounds dither at it).
double counted_compression(double compression, double least) {
  if (compression >= least) return compression;
  return std::max(0.0, 2.0 * compression - least);
}

// Per contact vertex, the least compression counted: kLeastCompression of
// the lighter free block it presses on, in scaled weight.
Eigen::VectorXd least_compressions(const Structure& structure, const EquilibriumProblem& problem) {
  Eigen::VectorXd least(problem.contact_vertex_count);
  auto weight = [&](int block) {
    return structure.is_support(block) ? std::numeric_limits<double>::infinity()
                                       : structure.block(block).mass() * kGravity / problem.weight_unit;
  };
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    const ForceGroup& g = problem.groups[k];
    least(k) = kLeastCompression * std::min(weight(g.block_a), weight(g.block_b));
  }
  return least;
}

// Whether the friction at every contact vertex of x (scaled) is within the
// pyramid of mu times the vertex's own compression, to `tolerance` (scaled
// force): the given-strength rows with mu c in place of the strength.
bool within_own_cones(const EquilibriumProblem& problem, const Eigen::VectorXd& x, const Eigen::VectorXd& least,
                      double mu, double tolerance) {
  const GroupRules& rules = problem.rules[static_cast<int>(GroupKind::contact_vertex)];
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    const double compression = counted_compression(x(4 * k), least(k));
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
    throw InvalidArgument("round_tolerance must be a finite number > 0, got " + shortest_number(settings.round_tolerance));
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
  // The rounds first build the strengths up: each vertex keeps mu times the
  // largest compression any round has pressed into it, until no strength
  // grows or a round stands; plain damped rounds (g = T(g)) then settle from
  // there. A block that still moves presses a different vertex of a joint
  // from round to round (its least-constraint motion turns about the
  // vertices that have no strength yet, and friction at the vertices that
  // have some moves its compression elsewhere), so a strength that follows
  // only the last compression is never where this round's sliding needs it.
  // The Armadillo vault's voussoir C-11-1 sits in a slot that diverges
  // towards the free edge: the course's thrust squeezes it only while
  // friction holds it (the squeeze also pushes it out), and with strengths
  // from the last round alone, damped besides, its joints lost their
  // strength vertex by vertex, the thrust went round it and it settled
  // falling alone at mu 0.84. Built up, its joints keep every vertex's
  // strength until the thrust squeezes it, and the plain rounds from there
  // keep it standing. The verdict is unchanged in kind: a fixed point of the
  // plain rounds, or a stable round whose friction is within its own
  // compressions' cones.
  bool building = true;
  double share = kFullStep;
  Eigen::VectorXd strength = Eigen::VectorXd::Zero(vertices), next(vertices), last_step = Eigen::VectorXd::Zero(vertices);
  const Eigen::VectorXd least = least_compressions(structure, analysis.problem());
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
    for (int k = 0; k < vertices; ++k) next(k) = mu * counted_compression(x(4 * k), least(k));
    // Scaled forces are in mean block weights: the tolerance is absolute.
    // Once no strength grows, or a round stands (nothing moves, so nothing
    // rocks from vertex to vertex), the plain rounds take over from this one.
    building = building && !result.stable && (next - strength).maxCoeff() > settings.round_tolerance;
    if (!building && (next - strength).lpNorm<Eigen::Infinity>() <= settings.round_tolerance) break;
    // A stable round whose friction at every vertex is within mu times the
    // compression that vertex has settles the verdict: those forces are an
    // equilibrium of the kind the fixed point is, without prestress (each
    // round's least-energy forces) and within Coulomb's cone of their own
    // compressions. Later rounds would only polish the strengths.
    if (result.stable && within_own_cones(analysis.problem(), x, least, mu, settings.round_tolerance)) break;
    if (round >= settings.max_rounds) {
      result.status = SolverStatus::max_iterations;
      result.stable = false;
      result.borderline = false;
      break;
    }
    if (building) {
      strength = strength.cwiseMax(next);
    } else {
      const Eigen::VectorXd step = next - strength;
      share = step.dot(last_step) < 0.0 ? std::max(kLeastStep, 0.5 * share) : std::min(kFullStep, kStepGrowth * share);
      last_step = step;
      strength += share * step;
    }
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
      virtual_loads += std::abs((x(4 * k) - x(4 * k + 1)) * g.on_b(g.component, 0));  // on a alone: -on_b
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

namespace {

// The structure with the load that lambda multiplies, times lambda.
Structure loaded(const Structure& structure, const LoadFactorSettings& load, double lambda) {
  Structure out = structure;
  if (load.pattern == LoadPattern::point_loads) {
    out.clear_loads();
    for (PointLoad p : structure.loads()) {
      p.force *= lambda;
      out.add_load(p);
    }
    return out;
  }
  const Vec3 direction = load.direction.normalized();
  for (int i = 0; i < structure.size(); ++i) {
    if (structure.is_support(i)) continue;
    const Block& block = structure.block(i);
    out.add_load({i, lambda * block.mass() * kGravity * direction, block.centroid()});
  }
  return out;
}

}  // namespace

KinematicLoadFactor kinematic_load_factor(const Structure& structure, const KinematicLoadFactorSettings& settings,
                                          const ProgressCount& progress) {
  const double tolerance = settings.bracket_tolerance;
  if (!(tolerance > 0.0 && tolerance < 1.0)) {
    throw InvalidArgument("bracket_tolerance: expected a number in (0, 1), got " + std::to_string(tolerance));
  }
  const LoadFactorSettings& load = settings.load;
  const AnalysisSettings& analysis = settings.analysis;
  const auto start = Clock::now();
  const BracketProgress bracket(tolerance, progress);
  bracket.tell(0.0, std::numeric_limits<double>::infinity());
  KinematicLoadFactor out;
  LoadFactorSettings bound = load;
  bound.problem = analysis.problem;
  const LoadFactor upper = load_factor(structure, bound);
  out.equilibrium_factor = upper.factor;
  auto finish = [&](MarginStatus status, double factor) {
    out.status = status;
    out.factor = factor;
    out.stable = (status == MarginStatus::optimal && factor >= 0.0) || status == MarginStatus::unbounded;
    out.seconds = seconds_since(start);
    return out;
  };
  if (upper.status != MarginStatus::optimal && upper.status != MarginStatus::unbounded) {
    return finish(upper.status, upper.factor);
  }
  // Each analysis's verdict; no verdict (not converged, or interrupted,
  // which then ends the search as such) ends the search.
  bool interrupted = false;
  auto verdict_at = [&](double lambda, EquilibriumResult* keep) {
    ++out.analyses;
    EquilibriumResult r = analyze_kinematic(loaded(structure, load, lambda), analysis);
    interrupted = r.status == SolverStatus::interrupted;
    const Verdict verdict = verdict_of(r);
    if (keep) *keep = std::move(r);
    return verdict;
  };
  const double kNaN = std::numeric_limits<double>::quiet_NaN();
  auto no_verdict = [&] { return finish(interrupted ? MarginStatus::interrupted : MarginStatus::no_verdict, kNaN); };
  EquilibriumResult at_zero;
  const Verdict zero = verdict_at(0.0, &at_zero);
  if (zero == Verdict::no_verdict) return no_verdict();
  if (zero == Verdict::falls) {
    out.failure = std::move(at_zero);
    return finish(MarginStatus::unstable, kNaN);
  }
  double low = 0.0, high = upper.factor;
  if (!std::isfinite(high)) {  // find a multiple that fails, doubling from the weight itself
    constexpr double kLargestFactor = 1e6;
    high = 1.0;
    for (;; high *= 2.0) {
      const Verdict verdict = verdict_at(high, &out.failure);
      if (verdict == Verdict::no_verdict) return no_verdict();
      if (verdict == Verdict::falls) break;
      low = high;
      if (high >= kLargestFactor) return finish(MarginStatus::unbounded, std::numeric_limits<double>::infinity());
    }
  } else {
    const Verdict verdict = verdict_at(high, &out.failure);
    if (verdict == Verdict::no_verdict) return no_verdict();
    if (verdict == Verdict::stands) {  // the upper bound itself stands
      bracket.tell(high, high);
      return finish(MarginStatus::optimal, high);
    }
  }
  while (high - low > tolerance * std::max(high, 1e-12)) {
    bracket.tell(low, high);
    const double middle = 0.5 * (low + high);
    EquilibriumResult r;
    const Verdict verdict = verdict_at(middle, &r);
    if (verdict == Verdict::no_verdict) return no_verdict();
    if (verdict == Verdict::stands) {
      low = middle;
    } else {
      high = middle;
      out.failure = std::move(r);
    }
  }
  bracket.tell(low, high);
  return finish(MarginStatus::optimal, low);
}

FrictionDemand kinematic_friction_demand(const Structure& structure, const KinematicFrictionDemandSettings& settings,
                                         const ProgressCount& progress) {
  const double tolerance = settings.bracket_tolerance;
  if (!(tolerance > 0.0 && tolerance < 1.0)) {
    throw InvalidArgument("bracket_tolerance: expected a number in (0, 1), got " + std::to_string(tolerance));
  }
  const auto start = Clock::now();
  const BracketProgress bracket(tolerance, progress);
  bracket.tell(0.0, std::numeric_limits<double>::infinity());
  FrictionDemandSettings equilibrium;
  equilibrium.problem = settings.analysis.problem;
  equilibrium.bracket_tolerance = tolerance;
  FrictionDemand out = friction_demand(structure, equilibrium);
  if (out.status != MarginStatus::optimal) return out;  // it falls even without sliding, or Clp failed
  out.programs = 0;
  out.iterations = 0;
  out.critical.clear();
  auto finish = [&](MarginStatus status, double friction) {
    out.status = status;
    out.friction = friction;
    out.seconds = seconds_since(start);
    return out;
  };
  // Each analysis's verdict; a fall keeps its moving interfaces as the
  // critical ones.
  bool interrupted = false;
  auto verdict_at = [&](double mu) {
    ++out.programs;
    AnalysisSettings at = settings.analysis;
    at.problem.friction = mu;
    const EquilibriumResult r = analyze_kinematic(structure, at);
    out.iterations += r.iterations;
    interrupted = r.status == SolverStatus::interrupted;
    const Verdict verdict = verdict_of(r);
    if (verdict == Verdict::falls) {
      out.critical.clear();
      for (const LimitInterface& joint : r.limit) out.critical.push_back(joint.interface);
    }
    return verdict;
  };
  auto no_verdict = [&] {
    return finish(interrupted ? MarginStatus::interrupted : MarginStatus::no_verdict,
                  std::numeric_limits<double>::quiet_NaN());
  };
  constexpr double kLargestFriction = 1e3;
  double low = out.lower, high = std::max(out.friction, 1e-3);
  for (Verdict verdict = verdict_at(high); verdict != Verdict::stands; verdict = verdict_at(high)) {
    if (verdict == Verdict::no_verdict) return no_verdict();
    low = high;
    if (high >= kLargestFriction) {
      out.lower = low;
      return finish(MarginStatus::unbounded, std::numeric_limits<double>::infinity());
    }
    high = std::min(kLargestFriction, 2.0 * high);
  }
  while (high - low > tolerance * high) {
    bracket.tell(low, high);
    const double middle = 0.5 * (low + high);
    const Verdict verdict = verdict_at(middle);
    if (verdict == Verdict::no_verdict) return no_verdict();
    (verdict == Verdict::stands ? high : low) = middle;
  }
  bracket.tell(low, high);
  out.lower = low;
  return finish(MarginStatus::optimal, high);
}

}  // namespace ashlar
