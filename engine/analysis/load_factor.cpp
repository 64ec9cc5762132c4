#include "analysis/load_factor.hpp"

#include <ClpSimplex.hpp>
#include <ClpSolve.hpp>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "analysis/clp_barrier.hpp"
#include "analysis/equilibrium.hpp"
#include "analysis/equilibrium_analysis.hpp"
#include "analysis/equilibrium_program.hpp"
#include "analysis/interior_point.hpp"
#include "analysis/mechanism.hpp"
#include "core/clock.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"

namespace ashlar {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Clp solves a scaled copy; "optimal" with secondary status 2-4 means the
// unscaled solution breaks bounds or rows beyond the tolerance (by up to
// 4e-4 of the mean weight near a tipping point: a confident wrong factor).
// Solve again without scaling, from the basis found.
int unscaled_status(ClpSimplex& simplex) {
  if (simplex.status() == 0 && simplex.secondaryStatus() >= 2 && simplex.secondaryStatus() <= 4) {
    simplex.scaling(0);
    simplex.primal();
  }
  return simplex.status();
}

// Clp's status once `simplex` has solved (its iterations are counted by
// the program's IterationTally). The dual simplex called feasible programs
// infeasible on fine arches (128 and 200 voussoirs), and so may the
// primal: "infeasible" stands only when the dual simplex from a slack
// basis agrees.
int confirmed_status(ClpSimplex& simplex) {
  if (unscaled_status(simplex) != 1) return simplex.status();
  simplex.allSlackBasis(true);
  simplex.dual();
  return unscaled_status(simplex);
}

// A feasibility program (no objective) by the primal simplex.
int solve_checked(ClpSimplex& simplex) {
  simplex.primal();
  return confirmed_status(simplex);
}

// Clp's barrier with crossover to a vertex (an optimal basis, with its
// duals). From scratch it takes far fewer iterations than either simplex
// on 3D friction programs, whose vertices are highly degenerate.
int solve_by_barrier(ClpSimplex& simplex) {
  ClpSolve barrier;
  barrier.setSolveType(ClpSolve::useBarrier);
  barrier.setSpecialOption(2, 1);  // no interrupt handler: analyses may run side by side
  simplex.initialSolve(barrier);
  if (simplex.status() != 0 && simplex.status() != 1 && simplex.status() != 2) {
    simplex.primal();  // the barrier stopped short: the simplex from its point
  }
  return confirmed_status(simplex);
}

// The barrier iterations a load factor's program is given. Its optima
// took 12-44 (a 24 x 30 dome pushed sideways the most); on unbounded
// programs it wanders: 402 iterations and 12.5 s on the 16 x 18 dome
// pushed along (1, 0, -3), 1,608 and 27 s on a planar 431-block wall,
// where Clp's own barrier and crossover answered in 20.5 s and 3.6 s.
constexpr int kFactorBarrierIterations = 100;

// What Clp's barrier with CHOLMOD's normal equations (BarrierSolver) left
// in the model: a point to cross over from (it says optimal, and the
// unscaled answer breaks no bound or row; Clp's checkSolution, which also
// sums the dual infeasibility), an interrupted solve, or nothing usable. On
// an unbounded program it called a factor of 1e16 optimal with 2,393 rows
// broken, and the simplex from there took 27,360 pivots and 60 s on a 3D
// wall, where Clp's own barrier and crossover took 8.6 s. `tolerance`: the
// barrier's primal and dual tolerances, 0 for Clp's.
enum class BarrierPoint { usable, interrupted, unusable };
BarrierPoint barrier_point(ClpSimplex& simplex, double tolerance) {
  const double primal_tolerance = simplex.primalTolerance(), dual_tolerance = simplex.dualTolerance();
  if (tolerance > 0.0) {
    simplex.setPrimalTolerance(tolerance);
    simplex.setDualTolerance(tolerance);
  }
  BarrierSolver().solve(simplex, kFactorBarrierIterations);
  simplex.setPrimalTolerance(primal_tolerance);
  simplex.setDualTolerance(dual_tolerance);
  if (simplex.status() == kClpInterrupted) return BarrierPoint::interrupted;
  if (simplex.status() != 0) return BarrierPoint::unusable;
  simplex.checkSolution(0);  // which marks the program unsolved (-1) if any dual is infeasible
  if (simplex.numberPrimalInfeasibilities() > 0) return BarrierPoint::unusable;
  return BarrierPoint::usable;
}

// The barrier's tolerances when its own last iterate is the answer:
// Clp's default 1e-7 left the 1,008-voussoir vault's factor 1.2e-8 off and
// joints moving at about limit_interfaces' threshold (280 limit interfaces
// against the vertex's 218), and let a block bearing on a 1e-3 strip, whose
// program is infeasible, through as optimal. At 1e-9 the vault's factor is
// within 3e-11 of the vertex's, with the same 218 limits.
constexpr double kBarrierAloneTolerance = 1e-9;
// The dual infeasibility, summed over the columns, that the barrier's
// answer may keep (Clp's checkSolution at its default 1e-7 tolerance): the
// 16 x 18 dome leaves 5.9e-7 over 3 columns; pushed along (0.3, 1, 0) it
// leaves 3.5e-6 and goes on to the crossover.
constexpr double kBarrierAloneDualSlack = 1e-6;
// The factor's distance from 0 under which its sign, the stability
// verdict, is left to a vertex.
constexpr double kBarrierAloneClearOfZero = 1e-6;
// Bodies from which a 3D program's factor is left to the barrier alone.
// Below, the crossover costs little and its vertex is exact: the block on
// a table's factors (tests/regression/block_on_table.lua) came out of the
// barrier alone 1.8e-9 and 2.7e-9 from their closed forms, held to 1e-9.
constexpr int kBarrierAloneBodies = 100;

// The largest factor. Where the structure stands unloaded the program is
// feasible, as BarrierSolver needs: the barrier with CHOLMOD's normal
// equations (Clp's own Cholesky, which orders by row counts only, took
// 71-73 % of a 1,216-block wall's load factor, planar or 3D), then the
// simplex from its point (its values pass) to a vertex, whose duals are an
// extreme mechanism. On a 3D program of kBarrierAloneBodies or more the
// barrier's point is the optimum when its duals (the mechanism) are
// feasible to Clp's tolerance and the factor is clear of 0: the
// crossover's pivots were 80 % of the 1,008-voussoir vault's load factor.
// Where it does not stand unloaded, or the barrier leaves no usable point,
// Clp's own barrier and crossover (solve_by_barrier).
int solve_for_factor(ClpSimplex& simplex, const EquilibriumProblem& problem, int factor_column,
                     bool stands_unloaded) {
  if (!stands_unloaded) return solve_by_barrier(simplex);
  const bool alone = problem.block_rows == 6 && problem.body_count >= kBarrierAloneBodies;
  switch (barrier_point(simplex, alone ? kBarrierAloneTolerance : 0.0)) {
    case BarrierPoint::interrupted: return kClpInterrupted;
    case BarrierPoint::unusable: return solve_by_barrier(simplex);
    case BarrierPoint::usable: break;
  }
  if (alone && simplex.sumDualInfeasibilities() <= kBarrierAloneDualSlack &&
      std::abs(simplex.primalColumnSolution()[factor_column]) > kBarrierAloneClearOfZero) {
    simplex.setProblemStatus(0);
    return 0;
  }
  simplex.primal(1);  // the crossover
  return confirmed_status(simplex);
}

// The scaled right-hand side (6 rows, as applied_force_rhs) of the load that
// lambda multiplies, per block.
std::vector<Eigen::Matrix<double, 6, 1>> pattern_rhs(const Structure& structure,
                                                     const EquilibriumProblem& problem,
                                                     const LoadFactorSettings& settings) {
  std::vector<Eigen::Matrix<double, 6, 1>> rhs(structure.size(), Eigen::Matrix<double, 6, 1>::Zero());
  if (settings.pattern == LoadPattern::body_force) {
    const Vec3 direction = settings.direction.normalized();
    for (int j = 0; j < structure.size(); ++j) {
      const Block& block = structure.block(j);
      rhs[j] = applied_force_rhs(block.mass() * kGravity * direction, block.centroid(), &block.centroid(),
                                 problem.weight_unit, problem.length_unit);
    }
  } else {
    for (const PointLoad& load : structure.loads()) {
      const Vec3& centroid = structure.block(load.block).centroid();
      rhs[load.block] += applied_force_rhs(load.force, load.at, &centroid, problem.weight_unit,
                                           problem.length_unit);
    }
  }
  return rhs;
}

}  // namespace

Structure structure_at_factor(const Structure& structure, const LoadFactorSettings& settings, double factor) {
  if (!std::isfinite(factor)) {
    throw InvalidArgument("load factor: the structure at the factor needs a finite factor, got " +
                          std::to_string(factor));
  }
  Structure loaded = structure;
  if (settings.pattern == LoadPattern::body_force) {
    if (!(settings.direction.norm() > 0.0)) throw InvalidArgument("load factor: direction must not be zero");
    const Vec3 direction = settings.direction.normalized();
    for (int j = 0; j < structure.size(); ++j) {
      if (structure.is_support(j)) continue;
      const Block& block = structure.block(j);
      loaded.add_load({j, factor * block.mass() * kGravity * direction, block.centroid()});
    }
  } else {
    loaded.clear_loads();
    for (const PointLoad& load : structure.loads()) loaded.add_load({load.block, factor * load.force, load.at});
  }
  return loaded;
}

namespace {

// Iterations the live load's own verdict (live_load_stands_alone) is
// given. Over a sweep of 72 load factors (an arch, domes, a vault, a wall
// planar and 3D; six directions; mu = 0.7 and no sliding) the 20 unbounded
// ones were proven in 6-14 iterations; where the load needs tension the
// solve reached its optimum in 7-19 or stopped here. 12 left the 16 x 18
// dome pushed along (1, 0, -3) at mu = 0.7 to the program: 17 s.
constexpr int kRayIterations = 20;

// Whether the live load alone, with no dead load, is carried compression-
// only: the equilibrium analysis's interior point on the problem with the
// multiplied load as its only load, stopped at the first forces that
// balance it without tension (InteriorPointSettings::certify_below, the
// analysis's own stability proof). Then, on a structure standing unloaded,
// any multiple of it stands too and the factor is unbounded; Clp's barrier
// spent its 100 iterations and its own barrier and crossover after them on
// such programs (the 16 x 18 dome pushed down at mu = 0.7: 7.1 s). Only
// where the feasible set is a cone (no bounded cable or shear strength) and
// friction is Coulomb's; false when not proven in kRayIterations.
// The analysis's QP takes the live load as its right-hand side.
bool live_load_stands_alone(EquilibriumAnalysis& analysis, const Eigen::VectorXd& live_load,
                            const LoadFactorSettings& settings) {
  const EquilibriumProblem& problem = analysis.problem();
  if (settings.problem.friction_law != FrictionLaw::coulomb) return false;
  for (const ForceGroup& group : problem.groups) {
    if (group.bound != 0.0 && problem.rules_of(group).bound_coefficients.size()) return false;
  }
  int iterations = 0;
  return analysis.carries_alone(live_load, kRayIterations, iterations);
}

void check_settings(const Structure& structure, const LoadFactorSettings& settings) {
  if (settings.pattern == LoadPattern::body_force) {
    const Vec3& d = settings.direction;
    if (!d.allFinite() || d.norm() == 0.0) {
      throw InvalidArgument("direction: expected a non-zero finite vector");
    }
    if (structure.planar() && std::abs(d.y()) > 1e-12 * d.norm()) {
      throw InvalidArgument(
          "direction: has a y component, but the structure is planar (x-z plane); "
          "call s:set_planar(false) to analyse it in 3D");
    }
  } else if (structure.loads().empty()) {
    throw InvalidArgument("load = 'point_loads': the structure has no point loads (s:add_load)");
  }
}


}  // namespace

LoadFactor load_factor(const Structure& structure, const LoadFactorSettings& settings,
                       const ProgressCount& progress) {
  const auto start = Clock::now();
  check_settings(structure, settings);
  // One analysis for the verdict at rest and the live load's own (their
  // QPs differ in the right-hand side); its QP is the program's.
  AnalysisSettings unloaded;
  unloaded.problem = settings.problem;
  EquilibriumAnalysis analysis(structure, unloaded);
  const EquilibriumProblem& problem = analysis.problem();
  LoadFactor result;
  if (problem.has_floating_bodies()) {
    result.status = MarginStatus::floating;
    result.factor = kNaN;
    result.seconds = seconds_since(start);
    return result;
  }
  EquilibriumProgram program = equilibrium_program(problem, settings.problem);
  // The factor's column: A x - lambda e = rhs, e the multiplied load's
  // right-hand side. Point loads leave the constant side when multiplied.
  const std::vector<Eigen::Matrix<double, 6, 1>> multiplied = pattern_rhs(structure, problem, settings);
  const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
  const int factor_column = program.add_column(0.0, 0.0);
  Eigen::VectorXd live_load = Eigen::VectorXd::Zero(problem.row_count);  // scaled, as problem.rhs
  for (int j = 0; j < structure.size(); ++j) {
    const int first = problem.row_of_block[j];
    if (first < 0) continue;
    for (int r = 0; r < problem.block_rows; ++r) {
      const double entry = multiplied[j](rows[r]);
      if (entry == 0.0) continue;
      live_load(first + r) = entry;
      program.add_entry(first + r, factor_column, -entry);
      if (settings.pattern == LoadPattern::point_loads) {
        program.row_lower[first + r] -= entry;
        program.row_upper[first + r] -= entry;
      }
    }
  }
  IterationTally tally{0, progress};
  ClpSimplex simplex;
  load_program(simplex, program, &tally);
  // Whether it stands with no load: the equilibrium analysis's verdict (its
  // interior point answers in a fiftieth of the simplex's time: 0.04 s
  // against 2.3 s on a 305-block dome), or, where that verdict is at its
  // resolution (borderline), the simplex's exact feasibility.
  const EquilibriumResult at_rest = analysis.solve();
  if (at_rest.status == SolverStatus::interrupted) {  // no verdict: the programs need not start
    result.status = clp_failure(kClpInterrupted);
    result.factor = kNaN;
    result.seconds = seconds_since(start);
    return result;
  }
  result.stable = at_rest.borderline ? solve_checked(simplex) == 0 : at_rest.stable;
  if (result.stable && live_load_stands_alone(analysis, live_load, settings)) {
    result.status = MarginStatus::unbounded;
    result.factor = kInfinity;
    result.seconds = seconds_since(start);
    return result;
  }
  simplex.setColumnBounds(factor_column, -COIN_DBL_MAX, COIN_DBL_MAX);
  simplex.setObjectiveCoefficient(factor_column, -1.0);
  // The largest factor by the barrier (solve_for_factor), whose duals are
  // the mechanism: 33 iterations and 0.4 s on that dome, where the primal
  // simplex took 14,453 pivots and 4.4 s.
  solve_for_factor(simplex, problem, factor_column, result.stable);
  result.iterations = tally.iterations;
  switch (simplex.status()) {
    case 0:
      result.factor = simplex.primalColumnSolution()[factor_column];
      result.stable = result.stable && result.factor >= 0.0;  // exact: no multiple down to 0 stands
      result.mechanism = mechanism_of(structure, problem, simplex.dualRowSolution());
      result.limit = limit_interfaces(structure, *structure.interfaces(settings.problem.contact), result.mechanism);
      break;
    case 1:
      result.status = MarginStatus::infeasible;
      result.factor = kNaN;
      result.stable = false;
      break;
    case 2:
      result.status = MarginStatus::unbounded;
      result.factor = kInfinity;
      break;
    default:  // an interrupted search says so and carries no verdict
      result.status = clp_failure(simplex.status());
      result.factor = kNaN;
      if (simplex.status() == kClpInterrupted) result.stable = false;
  }
  result.seconds = seconds_since(start);
  return result;
}

namespace {

// The friction-borrowing program (FrictionPrograms below) at a finite
// coefficient as the equilibrium solver's problem, on 3D structures of
// contacts alone: each contact vertex's tension unknown acts on no block
// and becomes the friction it borrows, b >= 0, which widens every side of
// its friction pyramid by b (in tangential force), at cost 1; no
// regularisation, no virtual torques: a linear program in (c, b, f_u,
// f_v). Clp's simplex took 40,000 crossover pivots on the degenerate
// optimal face of a 1,008-voussoir vault's first program (35 s); the
// interior point needs no vertex.
//
// Its verdicts:
// - too small: by the balance multipliers y of the solver's last iterate,
//   however accurate, through weak duality. For any forces x in the cones
//   that balance the loads, what they borrow is q.x = rhs.y + sum_k g_k.x_k
//   with g_k = q_k - A_k^T y, so rhs.y bounds it from below when every g_k
//   is non-negative on vertex k's cone (on its extreme rays: c = 1 with f
//   at a corner of the pyramid of radius mu, and b = 1 with f at a corner
//   of the unit pyramid). Where a g_k is slightly negative on a ray, y
//   scaled down by s <= 1 mends the rays with b (their g's b part is the
//   cost 1), and a coefficient mu' <= mu, which narrows every cone, those
//   with c: then s rhs.y > 0 proves mu' too small. A vertex whose blocks
//   move together is taken as still (proven_too_small). On the
//   1,008-voussoir vault a program just below the demand stopped with
//   primal residuals of 1e-7 and a borrowed amount 1e-4 too small, yet
//   its multipliers proved the coefficient too small to the bit.
// - stands: the iterate's forces, each vertex's friction scaled into its
//   cone, balance every block to the analysis's stable_tolerance, its own
//   test of forces that stand.
// Anything else is left to the simplex.
class InteriorBorrowing {
public:
  static bool applies(const EquilibriumProblem& problem, const EquilibriumOptions& options) {
    return problem.block_rows == 6 && options.friction_law == FrictionLaw::coulomb && problem.contacts_only();
  }

  // problem: built with unbounded friction, its other options `options`.
  InteriorBorrowing(const EquilibriumProblem& problem, const EquilibriumOptions& options) : options_(options) {
    EquilibriumProblem program = problem;
    program.groups.resize(problem.contact_vertex_count);  // contact vertices come first
    for (ForceGroup& group : program.groups) group.on_b.col(1).setZero();
    options_.friction = 1.0;  // a placeholder of the rules' shape: solve() sets the coefficient
    program.rules[static_cast<int>(GroupKind::contact_vertex)] = rules();
    AnalysisSettings settings;
    settings.problem = options_;
    analysis_ = std::make_unique<EquilibriumAnalysis>(std::move(program), settings);
    set_corners();
  }

  struct Answer {
    SolverStatus status = SolverStatus::numerical_error;  // the solver's
    double borrowed = kNaN;      // scaled, by the last iterate (when it has one)
    double too_small = kNaN;     // a coefficient proven too small: the one asked, or a rounding below; else NaN
    bool stands = false;         // the iterate's forces, friction scaled into the cones, pass the analysis's test
    // (c, b, f_u, f_v) per group of the problem, zero past the contact
    // vertices; where it stands, with b = 0 and the friction in the cones.
    std::vector<Eigen::Vector4d> unknowns;
  };

  // The program at `friction`, warm from the last one's iterate; `groups`:
  // the problem's.
  Answer solve(double friction, size_t groups) {
    options_.friction = friction;
    analysis_->set_rules(GroupKind::contact_vertex, rules());
    Answer answer;
    const InteriorPointInfo info = analysis_->solve_qp(InteriorPointSettings{}, warm_);
    answer.status = info.status;
    iterations_ = info.iterations;
    warm_ = !has_no_answer(info.status);
    if (!warm_) return answer;
    const InteriorPointSolution& solution = analysis_->solution();
    answer.unknowns.assign(groups, Eigen::Vector4d::Zero());
    answer.borrowed = 0.0;
    for (int k = 0; k < analysis_->problem().contact_vertex_count; ++k) {
      answer.unknowns[k] = solution.x.segment<4>(4 * k);
      answer.borrowed += answer.unknowns[k](1);
    }
    answer.too_small = proven_too_small(friction, solution.y, solution.x);
    // The forces without what they borrow: each vertex's friction scaled
    // into its cone, what that takes off left to the balance.
    std::vector<Eigen::Vector4d> within = answer.unknowns;
    Eigen::VectorXd forces = solution.x;
    for (int k = 0; k < analysis_->problem().contact_vertex_count; ++k) {
      Eigen::Vector4d& x = within[k];
      const double needed = friction_needed(options_, x(0), x(2), x(3));
      if (needed > friction) x.tail<2>() *= x(0) > 0.0 ? friction / needed : 0.0;
      x(1) = 0.0;
      forces.segment<4>(4 * k) = x;
    }
    answer.stands = compression_only_imbalance(analysis_->problem(), forces) <= kStandsTolerance;
    if (answer.stands) answer.unknowns = std::move(within);
    return answer;
  }
  int iterations() const { return iterations_; }

private:
  GroupRules rules() const {
    const Eigen::Matrix<double, Eigen::Dynamic, 3> sides = friction_rows(options_);
    GroupRules contact;
    contact.rows = Eigen::Matrix<double, Eigen::Dynamic, 4>::Zero(2 + sides.rows(), 4);
    contact.rows(0, 0) = 1.0;  // c >= 0
    contact.rows(1, 1) = 1.0;  // b >= 0
    for (int j = 0; j < sides.rows(); ++j) {
      contact.rows.row(2 + j) << sides(j, 0), sides.row(j).tail<2>().norm(), sides(j, 1), sides(j, 2);
    }
    contact.linear << 0.0, 1.0, 0.0, 0.0;
    return contact;
  }

  // The corners (f_u, f_v) of the friction polygon at c = 1, b = 0 for a
  // unit coefficient, and at c = 0, b = 1 (friction_rows' sides with b's
  // column their tangential length): the pyramid's on the unit circle at
  // angles 2 pi i / m, and its unit polygon's at 1 / cos(pi / m); the box's
  // (+-1, +-1) both.
  void set_corners() {
    if (options_.friction_model == FrictionModel::box) {
      for (const double u : {-1.0, 1.0}) {
        for (const double v : {-1.0, 1.0}) friction_corners_.emplace_back(u, v);
      }
      borrowed_corners_ = friction_corners_;
      return;
    }
    const int m = options_.friction_sides;
    for (int i = 0; i < m; ++i) {
      const double angle = 2.0 * kPi * i / m;
      friction_corners_.emplace_back(std::cos(angle), std::sin(angle));
      borrowed_corners_.push_back(friction_corners_.back() / std::cos(kPi / m));
    }
  }

  // See the class's comment: the coefficient mu' (at most `friction`)
  // that the multipliers y prove too small, or NaN. x: the iterate's
  // unknowns, the size of the forces at vertices taken as still.
  double proven_too_small(double friction, const Eigen::VectorXd& y, const Eigen::VectorXd& x) const {
    const EquilibriumProblem& problem = analysis_->problem();
    double scale = 1.0, proven = friction, still_work = 0.0;
    for (int k = 0; k < problem.contact_vertex_count; ++k) {
      const ForceGroup& group = problem.groups[k];
      const Eigen::Vector4d reaction = problem.reaction(group, y);  // A_k^T y; its b entry 0
      // A vertex whose blocks move together, compressed and not sliding,
      // has g_k = 0 at the optimum, and in the iterate g_k at the dual
      // residual (1e-13 of the blocks' motion on an 8 x 4 dome, where a
      // proof through such a vertex's g_c / -least_friction fell to a
      // third of mu): taken as still, the work of its forces on that
      // residual, g_k . x_k, is charged to the bound instead.
      double motion = 0.0;
      for (const int row : {group.row_a, group.row_b}) {
        if (row >= 0) motion = std::max(motion, y.segment<6>(row).lpNorm<Eigen::Infinity>());
      }
      if (reaction.lpNorm<Eigen::Infinity>() <= kStill * motion) {
        still_work += std::abs(reaction.dot(x.segment<4>(4 * k)));
        continue;
      }
      const double g_c = -reaction(0);
      const Eigen::Vector2d g_f(-reaction(2), -reaction(3));
      double least_friction = kInfinity, least_borrowed = kInfinity;
      for (const Eigen::Vector2d& corner : friction_corners_) least_friction = std::min(least_friction, g_f.dot(corner));
      for (const Eigen::Vector2d& corner : borrowed_corners_) least_borrowed = std::min(least_borrowed, g_f.dot(corner));
      if (least_borrowed < 0.0) scale = std::min(scale, 1.0 / -least_borrowed);  // 1 + s least_borrowed >= 0
      if (least_friction < 0.0) {
        proven = std::min(proven, g_c / -least_friction);  // g_c + mu' least_friction >= 0
      } else if (g_c < 0.0) {
        return kNaN;
      }
    }
    // rhs.y's rounding: a few ulps of the sum of its terms' sizes.
    const double bound = scale * (problem.rhs.dot(y) - still_work);
    const double rounding = 64.0 * std::numeric_limits<double>::epsilon() * problem.rhs.cwiseAbs().dot(y.cwiseAbs());
    return proven > 0.0 && bound > rounding ? proven : kNaN;
  }

  // Forces stand when, their friction scaled into the cones, they balance
  // every block to this fraction of its load: the analysis's own test
  // (AnalysisSettings::stable_tolerance, compression_only_imbalance). Near
  // the demand, from above, the solver may stop short of its tolerance
  // (balance residuals of 1.5e-7 on the 16 x 18 dome, 2.8e-8 borrowed in
  // all on a 128-block vault).
  static constexpr double kStandsTolerance = AnalysisSettings{}.stable_tolerance;
  // Relative motion at a vertex, against its blocks' largest multiplier,
  // below which the vertex is taken as still: the solver's tolerance.
  static constexpr double kStill = 1e-10;

  EquilibriumOptions options_;
  std::unique_ptr<EquilibriumAnalysis> analysis_;
  std::vector<Eigen::Vector2d> friction_corners_, borrowed_corners_;
  bool warm_ = false;
  int iterations_ = 0;
};

// Programs of one problem at several friction coefficients; each starts
// from the previous basis of the same shape. At a finite coefficient the
// program does not ask whether an equilibrium fits in the friction cones
// (an infeasible program, whose verdict Clp struggles to reach: 19,617
// pivots and "numerical difficulties" on a 305-block dome) but how much
// friction beyond them it must borrow at least, per contact vertex along
// u and v, each unit at cost 1: always feasible when the structure stands
// without sliding, zero exactly when it stands with this coefficient, and
// near the demand about proportional to how far below it the coefficient
// is, which lets the search step by secants instead of halving.
class FrictionPrograms {
public:
  FrictionPrograms(const EquilibriumProblem& problem, EquilibriumOptions options, FrictionDemand& tally)
      : problem_(problem), options_(std::move(options)), tally_(tally) {
    if (InteriorBorrowing::applies(problem_, options_)) interior_ = std::make_unique<InteriorBorrowing>(problem_, options_);
  }

  // 0: stands, 1: does not (it must borrow friction; proven_short() says
  // at which coefficient, above `known_short`, the largest already known
  // too small), other: Clp's failure status. The friction borrowed
  // (scaled) goes to `borrowed`, the scaled unknowns of the equilibrium
  // found (borrowed friction included) to `unknowns`.
  int stands(double friction, std::vector<Eigen::Vector4d>* unknowns = nullptr, double* borrowed = nullptr,
             double known_short = 0.0) {
    // A program small enough to end without iterating never asks the
    // event handler: ask here, so that a stop requested is always heard.
    if (stop_requested()) return kClpInterrupted;
    options_.friction = friction;
    proven_short_ = friction;
    if (interior_ && friction > 0.0 && std::isfinite(friction)) {
      InteriorBorrowing::Answer answer = interior_->solve(friction, problem_.groups.size());
      tally_.iterations += interior_->iterations();
      ++tally_.programs;
      if (answer.status == SolverStatus::interrupted) return kClpInterrupted;
      if (answer.too_small > known_short) {  // false for NaN
        proven_short_ = answer.too_small;
        return verdict(false, answer.borrowed, std::move(answer.unknowns), unknowns, borrowed);
      }
      if (answer.stands) return verdict(true, answer.borrowed, std::move(answer.unknowns), unknowns, borrowed);
      // Undecided: the simplex decides.
    }
    EquilibriumProgram program = equilibrium_program(problem_, options_);
    const int first_borrowed = program.columns;
    // Without friction or without a bound on it, the program asks only
    // whether it stands: Clp decides those quickly (the frictionless one
    // in 3,468 pivots on that dome, against 26,449 borrowing).
    if (friction > 0.0 && std::isfinite(friction)) {
      for (int k = 0; k < problem_.contact_vertex_count; ++k) {
        for (const Eigen::Vector4d& along : {Eigen::Vector4d(0, 0, 1, 0), Eigen::Vector4d(0, 0, -1, 0),
                                             Eigen::Vector4d(0, 0, 0, 1), Eigen::Vector4d(0, 0, 0, -1)}) {
          program.add_group_column(problem_, k, along, 0.0, COIN_DBL_MAX);
        }
      }
    }
    IterationTally tally;
    ClpSimplex simplex;
    load_program(simplex, program, &tally);
    for (int column = first_borrowed; column < program.columns; ++column) {
      simplex.setObjectiveCoefficient(column, 1.0);
    }
    const bool borrows = first_borrowed < program.columns;
    const bool warm = basis_.size() == static_cast<size_t>(program.columns + program.rows);
    int status;
    if (borrows && !warm) {
      // From scratch the barrier and crossover (1.7 s on the 305-block
      // dome) beat the dual simplex from all slacks (2.9 s, 8,874 pivots)
      // and the primal (17,148 pivots). From a basis the primal does better.
      // (CHOLMOD's barrier and the simplex from its point, as the load
      // factor's, took 21 s and 27,405 iterations over the dome's five
      // programs, against 4.8 s and 7,865.)
      status = solve_by_barrier(simplex);
    } else {
      if (warm) simplex.copyinStatus(basis_.data());
      status = solve_checked(simplex);
    }
    tally_.iterations += tally.iterations;
    ++tally_.programs;
    if (status != 0) return status;
    basis_.assign(simplex.statusArray(), simplex.statusArray() + program.columns + program.rows);
    // Columns may sit a rounding below zero: only what is borrowed counts.
    double* columns = simplex.primalColumnSolution();
    double amount = 0.0;
    for (int column = first_borrowed; column < program.columns; ++column) amount += std::max(0.0, columns[column]);
    // What a program that stands borrows is rounding: its equilibrium is
    // the one in the cones (a vertex with no compression must not seem to
    // need infinite friction for a borrowed 1e-12).
    const bool stands = amount <= kBorrowedNothing * std::max(problem_.body_count, 1);
    if (stands) std::fill(columns + first_borrowed, columns + program.columns, 0.0);
    return verdict(stands, amount, program.group_unknowns(problem_, columns), unknowns, borrowed);
  }

  // The coefficient the last verdict 1 proved too small: the one asked, or
  // a rounding below it (InteriorBorrowing).
  double proven_short() const { return proven_short_; }
  // Whether the interior point solves the programs at finite coefficients.
  bool by_interior_point() const { return interior_ != nullptr; }

  // The coefficient an equilibrium needs, and the interfaces that need it.
  double needed(const std::vector<Eigen::Vector4d>& unknowns, std::vector<int>* critical = nullptr) const {
    std::vector<double> per_interface;
    double most = 0.0;
    for (size_t k = 0; k < problem_.groups.size(); ++k) {
      const ForceGroup& group = problem_.groups[k];
      if (group.kind != GroupKind::contact_vertex) continue;
      const Eigen::Vector4d& x = unknowns[k];
      // A vertex carrying nothing but rounding (cone columns a rounding
      // below zero) needs no friction, not an infinite amount.
      if (x.lpNorm<Eigen::Infinity>() <= kRounding) continue;
      const double need = friction_needed(options_, x(0), x(2), x(3));
      most = std::max(most, need);
      if (per_interface.size() <= static_cast<size_t>(group.source)) per_interface.resize(group.source + 1, 0.0);
      per_interface[group.source] = std::max(per_interface[group.source], need);
    }
    if (critical) {
      for (size_t k = 0; k < per_interface.size(); ++k) {
        if (most > 0.0 && per_interface[k] >= (1 - 1e-3) * most) critical->push_back(static_cast<int>(k));
      }
    }
    return most;
  }

private:
  // stands()'s answer for a program that stands or not, borrowing
  // `amount` with the unknowns `found`, which go to the caller's
  // `unknowns` and `borrowed`.
  static int verdict(bool stands, double amount, std::vector<Eigen::Vector4d> found,
                     std::vector<Eigen::Vector4d>* unknowns, double* borrowed) {
    if (borrowed) *borrowed = amount;
    if (unknowns) *unknowns = std::move(found);
    return stands ? 0 : 1;
  }

  // Friction borrowed per body (scaled: a mean body weight) below which a
  // program stands. Borrowing is about proportional to how far below the
  // demand the coefficient is (a block on an incline: 1 per unit of it),
  // so this is the relative accuracy it allows; Clp's rounding only ever
  // makes a coefficient seem too small, a rounding above the demand (the
  // safe side).
  static constexpr double kBorrowedNothing = 1e-10;
  // Scaled force at a vertex that is Clp's rounding (its tolerances are 1e-7).
  static constexpr double kRounding = 1e-9;

  const EquilibriumProblem& problem_;
  EquilibriumOptions options_;
  FrictionDemand& tally_;
  std::vector<unsigned char> basis_;
  std::unique_ptr<InteriorBorrowing> interior_;  // null where the simplex answers alone
  double proven_short_ = kNaN;
};

// Brackets the least friction coefficient with which a structure stands,
// [low, high], from verdicts at coefficients tried: too small, with the
// shortfall (the friction its program borrowed), or enough. Each step
// tries a secant estimate of the demand from the shortfalls of the latest
// two coefficients found too small, a quarter of the asked width above it
// (after one too small) or below it (after one that stood), so that a good
// estimate closes the bracket in two steps; a secant step that made too
// little progress (a quarter of the shortfall left, or after two secant
// steps that stood, half the bracket) hands the next one to bisection. One
// secant step that stood is not judged by the bracket: it moved the upper
// end, which was near the demand already, and the estimate's other side
// goes next. Judged by the bracket, an imperfect dome's friction demand
// alternated secant steps that stood with bisections from below: 13
// programs, now 9.
class SecantBracket {
public:
  // width: relative, as closed() asks.
  explicit SecantBracket(double width) : width_(width) {}

  double low = 0.0, high = kInfinity;

  bool closed() const { return high - low <= width_ * high; }

  // A coefficient found too small before the steps (no step judged).
  void known_short(double at, double shortfall) {
    low = at;
    short_of_.emplace_back(at, shortfall);
  }

  // The coefficient to try next, strictly inside a finite bracket.
  double next() {
    width_before_ = high - low;
    secant_ = false;
    if (!halve_ && short_of_.size() >= 2) {
      const auto [mu0, shortfall0] = short_of_[short_of_.size() - 2];
      const auto [mu1, shortfall1] = short_of_.back();
      if (shortfall0 > shortfall1) {
        const double estimate = mu1 + shortfall1 * (mu1 - mu0) / (shortfall0 - shortfall1);
        for (const double side : {aim_, -aim_}) {  // the other side when one is out of the bracket
          const double aimed = estimate + side * 0.25 * width_ * high;
          if (aimed > low && aimed < high) {
            secant_ = true;
            return aimed;
          }
        }
      }
    }
    return 0.5 * (low + high);
  }

  // The verdicts at next()'s coefficient: too small, with its shortfall;
  // or enough, the bracket's upper end now `upper` (at most the coefficient,
  // less where the equilibrium found needs less).
  void too_small(double at, double shortfall) {
    const double before = short_of_.empty() ? kInfinity : short_of_.back().second;
    known_short(at, shortfall);
    halve_ = secant_ && shortfall > 0.25 * before;
    secant_stood_ = false;
    aim_ = 1.0;
  }
  void enough(double upper) {
    high = upper;
    halve_ = secant_ && secant_stood_ && high - low > 0.5 * width_before_;
    secant_stood_ = secant_;
    aim_ = -1.0;
  }

private:
  double width_;
  std::vector<std::pair<double, double>> short_of_;  // (coefficient, shortfall), in the order found
  bool halve_ = true;          // bisect next: the first step, and after one without progress
  bool secant_ = false;        // next() gave a secant estimate
  bool secant_stood_ = false;  // the last step was a secant step that stood
  double aim_ = 1.0;           // the side of the estimate aimed at
  double width_before_ = 0.0;  // the bracket's width before the step
};

// Past this coefficient a structure that stands only without sliding is
// called unstable: it leans on contacts with (nearly) no compression.
constexpr double kLargestDemand = 1e6;

// The relative width to which the equilibrium analyses bracket the demand
// before the programs take over, when the simplex solves them. Three more
// analyses than at 1e-3 put the programs' first steps (the upper end's,
// warm from the lower's basis) closer to the demand, where the simplex
// takes fewer pivots and the secant closes sooner: the imperfect 16 x 18
// dome 9 programs -> 5 (CPU 3.0-3.1 s -> 2.8-2.9 s), the 1,008-voussoir
// vault's upper end 3,372 pivots -> 550 (CPU 62-64 s -> 36-41 s), on a
// shared machine. At 1e-5 the analyses cost more than the programs save
// (the dome 6 programs).
constexpr double kSimplexAnalysedWidth = 1e-4;
// The same when the interior point solves them (InteriorBorrowing): a
// program then costs about an analysis, warm or not, and the secant closes
// from further out. The imperfect 16 x 18 dome and the 1,008-voussoir
// vault at 1e-4, 1e-3, 1e-2, 1e-1, 0.3: the analyses 0.97, 0.62, 0.47,
// 0.37, 0.33 s and 5.1, 4.4, 3.5, 1.6, 1.4 s; the whole demand 1.37,
// 1.02, 0.96, 0.88, 1.07 s (5, 5, 7, 8, 13 programs) and 6.7, 6.3, 5.2,
// 3.7, 4.5 s (5, 5, 5, 7, 12 programs).
constexpr double kInteriorAnalysedWidth = 1e-1;

// The demand as the equilibrium analysis sees it: a bracket grown from 1 by
// doubling, then halved to a relative `width`, on its verdicts: one QP each,
// warm from the last, about a twentieth of a second on a 305-block dome,
// where a program far from the demand takes seconds. A verdict is all a
// step needs: an analysis that stands stops at its first compression-only
// equilibrium (verdict_only), and brings the upper end down to the
// friction that equilibrium needs, which is often well below the
// coefficient tried far from the demand (the imperfect 16 x 18 dome: 17
// analyses and 241 interior-point iterations to a bracket of the same
// width, against 18 and 398 solved to the optimum and halved). The upper end of the bracket,
// or infinity when it does not stand without sliding, when no coefficient
// up to kLargestDemand stands, or when an analysis gives no verdict. Only a
// guide: the programs decide.
double analysed_demand(const Structure& structure, const EquilibriumOptions& options, double width) {
  AnalysisSettings settings;
  settings.problem = options;
  settings.problem.friction = 1.0;
  settings.verdict_only = true;
  EquilibriumAnalysis analysis(structure, settings);
  bool warm = false;
  double needed = kInfinity;  // by the forces of the last analysis that stood
  auto stands = [&](double friction) {
    settings.problem.friction = friction;
    analysis.update(structure, settings);
    const EquilibriumResult r = analysis.solve(warm);
    warm = r.status == SolverStatus::converged || r.status == SolverStatus::inaccurate;
    if (has_no_answer(r.status)) return -1;
    if (!r.stable) return 0;
    needed = 0.0;
    for (const Eigen::Vector4d& forces : r.vertex_forces) {
      needed = std::max(needed, friction_needed(options, forces(0), forces(2), forces(3)));
    }
    needed = std::min(needed, friction);
    return 1;
  };
  if (stands(kInfinity) != 1) return kInfinity;
  double low = 0.0, high = 1.0;
  for (;; high *= 2.0) {
    const int verdict = stands(high);
    if (verdict < 0 || (verdict == 0 && high >= kLargestDemand)) return kInfinity;
    if (verdict == 1) break;
    low = high;
  }
  high = std::max(low, needed);
  bool frictionless_asked = false;
  while (high - low > width * high) {
    // Halving never brackets a demand of 0 to a relative width: a
    // running-bond wall, which needs no friction, took 1,077 analyses
    // down to 4.9e-324 (45 s for a 431-block wall). Below the width, ask.
    if (low == 0.0 && high < width && !frictionless_asked) {
      frictionless_asked = true;
      const int verdict = stands(0.0);
      if (verdict < 0) return kInfinity;
      if (verdict == 1) return 0.0;
    }
    const double middle = 0.5 * (low + high);
    const int verdict = stands(middle);
    if (verdict < 0) return kInfinity;
    if (verdict == 1) high = std::max(low, needed);
    else low = middle;
  }
  return high;
}

}  // namespace

FrictionDemand friction_demand(const Structure& structure, const FrictionDemandSettings& settings,
                               const ProgressCount& progress) {
  const double tolerance = settings.bracket_tolerance;
  if (!(tolerance > 0.0 && tolerance < 1.0)) {
    throw InvalidArgument("bracket_tolerance: expected a number in (0, 1), got " + std::to_string(tolerance));
  }
  const EquilibriumOptions& options = settings.problem;
  const auto start = Clock::now();
  const BracketProgress bracket(tolerance, progress);
  bracket.tell(0.0, kInfinity);
  EquilibriumOptions unbounded = options;
  unbounded.friction = kInfinity;
  const EquilibriumProblem problem = build_equilibrium_problem(structure, unbounded);
  FrictionDemand result;
  auto finish = [&](MarginStatus status, double friction) {
    result.status = status;
    result.friction = friction;
    result.seconds = seconds_since(start);
    return result;
  };
  if (problem.has_floating_bodies()) return finish(MarginStatus::floating, kInfinity);
  FrictionPrograms programs(problem, options, result);
  std::vector<Eigen::Vector4d> unknowns;
  int status = 0;
  // The programs' bracket, on the friction they borrow below the demand.
  SecantBracket demand(tolerance);
  bool high_stands = false;  // `unknowns` hold an equilibrium that stands with demand.high
  // Confirm the analyses' bracket by programs, just outside each end, the
  // lower end first. There the structure must borrow friction; where it
  // stands, the program's optimum (nothing borrowed) is massively
  // degenerate, and Clp's barrier and crossover took four times as long
  // to reach it cold (the 16 x 18 dome: 2.27 s above, 0.55 s below, and
  // the upper end from the lower's basis 0.11 s; its friction demand
  // 3.9 s -> 1.9 s).
  const double width = programs.by_interior_point() ? kInteriorAnalysedWidth : kSimplexAnalysedWidth;
  const double analysed = analysed_demand(structure, options, width);
  if (std::isfinite(analysed)) {
    // One end's program: it moves the lower end (too small) or the upper
    // (stands); false when Clp failed (status says how).
    auto confirm = [&](double friction) {
      double borrowed = 0.0;
      status = programs.stands(friction, &unknowns, &borrowed, demand.low);
      if (status == 1) {
        demand.known_short(programs.proven_short(), borrowed);
      } else if (status == 0) {
        demand.high = std::min(friction, programs.needed(unknowns));
        high_stands = true;
      }
      return status == 0 || status == 1;
    };
    const double below = analysed * (1.0 - 2.0 * width);
    if ((below > 0.0 && !confirm(below)) ||
        (!high_stands && !confirm(analysed * (1.0 + width)))) {
      return finish(clp_failure(status), kNaN);
    }
  }
  if (!high_stands) {
    // Nothing tried stands yet: whether it stands without sliding at all,
    // and what friction that equilibrium needs.
    status = programs.stands(kInfinity, &unknowns);
    if (status == 1) {
      result.lower = demand.low;
      return finish(MarginStatus::unstable, kInfinity);
    }
    if (status != 0) return finish(clp_failure(status), kNaN);
    demand.high = programs.needed(unknowns);
  }
  if (!high_stands && !std::isfinite(demand.high)) {
    // The frictionless-in-the-limit equilibrium leaned on a vertex with no
    // compression: grow a finite coefficient until one stands.
    double high = std::max(1.0, 2.0 * demand.low);
    double borrowed = 0.0;
    while ((status = programs.stands(high, &unknowns, &borrowed, demand.low)) == 1 && high < kLargestDemand) {
      demand.known_short(programs.proven_short(), borrowed);
      high *= 4;
    }
    if (status == 1) {
      result.lower = demand.low;
      return finish(MarginStatus::unstable, kInfinity);
    }
    if (status != 0) return finish(clp_failure(status), kNaN);
    demand.high = std::min(high, programs.needed(unknowns));
  } else if (!high_stands) {
    status = programs.stands(demand.high, &unknowns, nullptr, demand.low);
    if (status != 0) return finish(status == 1 ? MarginStatus::numerical_difficulties : clp_failure(status), kNaN);
  }
  if (high_stands && demand.high == 0.0) return finish(MarginStatus::optimal, 0.0);  // it stood without friction
  if (demand.low == 0.0) {
    // No program has fallen short yet (one that does proves every smaller
    // coefficient too small): whether it stands without friction.
    status = programs.stands(0.0);
    if (status == 0) return finish(MarginStatus::optimal, 0.0);
    if (status != 1) return finish(clp_failure(status), kNaN);
  }
  std::vector<Eigen::Vector4d> at_high = unknowns;
  bracket.tell(demand.low, demand.high);
  while (!demand.closed()) {
    const double next = demand.next();
    double borrowed = 0.0;
    status = programs.stands(next, &unknowns, &borrowed, demand.low);
    if (status == 0) {
      // The equilibrium found may need less than the coefficient tried.
      demand.enough(std::max(demand.low, std::min(next, programs.needed(unknowns))));
      at_high = unknowns;
    } else if (status == 1) {
      demand.too_small(programs.proven_short(), borrowed);
    } else if (status == kClpInterrupted) {
      result.lower = demand.low;  // the bracket so far: it stands with demand.high
      return finish(clp_failure(status), demand.high);
    } else {
      return finish(clp_failure(status), kNaN);
    }
    bracket.tell(demand.low, demand.high);
  }
  result.lower = demand.low;
  programs.needed(at_high, &result.critical);
  return finish(MarginStatus::optimal, demand.high);
}

}  // namespace ashlar
