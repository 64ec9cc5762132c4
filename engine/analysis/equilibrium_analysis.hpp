// One equilibrium analysis of a structure, as an object: it owns the QP
// (EquilibriumProblem), the solver with its symbolic factorisation of the
// normal matrix's pattern, and the last solution, split as
//   setup  (constructor: check settings, build the QP, or take one built
//           and changed by the caller, and analyse the pattern),
//   update (new loads, friction or geometry: rebuild the QP, keep the
//           symbolic analysis when the contact pattern is unchanged;
//           or, cheaper, change only what a sequence of related programs
//           changes: the right-hand side (set_rhs, update_loads), a
//           group's bound or effect (set_group)),
//   solve  (any number of times; warm from the last solution on request).
// Parametric searches, gradients, weight sensitivity, force flow, load
// factors, load capacity, necessary weights and the optimiser re-solve one
// object instead of building the QP and analysing the pattern again. The
// cores setting lets workers that share blocks each own one analysis on
// one core (SolverCores).
#pragma once

#include <memory>

#include "analysis/equilibrium.hpp"
#include "analysis/equilibrium_problem.hpp"
#include "analysis/interior_point.hpp"

namespace ashlar {

// The forces of the scaled unknowns x (4 per group of `problem`, as the
// solver's) into `result`: interfaces (parallel to the problem's, the
// structure's under its contact options), vertex forces and
// positions, block tension, cable forces and virtual torques, in N and m.
// Returns the penalised unknowns' linear cost (scaled), the infeasibility
// before division by the body count. Every method that ends in forces of
// this QP's groups reports them through this one function.
double fill_result_forces(const Structure& structure, const EquilibriumProblem& problem, const Eigen::VectorXd& x,
                          EquilibriumResult& result);

class EquilibriumAnalysis {
public:
  // Throws InvalidArgument for bad settings or a structure the analysis
  // refuses (as analyze_equilibrium). `structure` must outlive the object,
  // or the next update(). `cores`: the solver's, for every solver this
  // object sets up (after update() too).
  EquilibriumAnalysis(const Structure& structure, const AnalysisSettings& settings,
                      SolverCores cores = SolverCores::all);
  // The QP `problem`, built by build_equilibrium_problem (perhaps of
  // settings.problem) and changed by the caller (groups added, rules
  // replaced), solved with settings.solver; settings.stable_tolerance is
  // carries_alone's. Such an object has no structure: solve_qp(), not
  // solve(), until an update() gives it one. Throws InvalidArgument for
  // bad settings.
  EquilibriumAnalysis(EquilibriumProblem problem, const AnalysisSettings& settings,
                      SolverCores cores = SolverCores::all);
  ~EquilibriumAnalysis();
  EquilibriumAnalysis(const EquilibriumAnalysis&) = delete;
  EquilibriumAnalysis& operator=(const EquilibriumAnalysis&) = delete;

  // The QP of `structure` under `settings`. The symbolic factorisation is
  // kept when every force group acts on the same bodies' rows as before
  // (same contacts; loads, friction and vertex positions may change), else
  // redone. The last solution stays, as a warm start for solve(true).
  void update(const Structure& structure, const AnalysisSettings& settings);

  // New loads, nothing else: `rhs` becomes the balance rows' right-hand
  // side (scaled: forces over problem().weight_unit, moments about each
  // block's centroid over weight_unit * length_unit; problem().row_count
  // long, rows as problem().row_of_block). The QP's groups, rules, units,
  // the symbolic analysis and the last solution stay: O(rows). A block of
  // weight W (N) multiplied by m adds (m - 1) W / weight_unit to its
  // vertical row (row_of_block + problem().vertical_row()); a point load's
  // rows are applied_force_rhs's. Throws std::invalid_argument for another
  // length.
  void set_rhs(Eigen::VectorXd rhs);
  // set_rhs(load_rhs(structure, problem())): the loads of `structure`, a
  // structure with the analysed one's blocks, supports, contacts and
  // cables, loaded otherwise (point loads, block weights, cable weights),
  // in this QP's units. With only point loads changed the QP is, to the
  // bit, the one update(structure, settings()) builds, at a fraction of the
  // cost; changed weights keep the old units (a fresh build's are the new
  // mean body weight): the same equilibria, tension priced in the old
  // units. Then `structure` is the one solve() reports on (it must
  // outlive the object or the next update). Throws InvalidArgument as
  // load_rhs.
  void update_loads(const Structure& structure);
  // Group `k` of the QP becomes `group`, of the same kind (its bound, its
  // effect on the balance rows, or its bodies changed: a column's bounds
  // and entries). When its bodies' rows change the solver is refitted
  // (EquilibriumSolver::refit, linear in the groups), or the pattern
  // analysed again when the new rows are not in it. Throws
  // std::invalid_argument for a group out of range or of another kind.
  void set_group(int k, const ForceGroup& group);
  // The rules of every group of `kind` become `rules`, with as many
  // inequality rows (a friction coefficient changed in a program built
  // from the problem): the pattern, the symbolic analysis and the last
  // solution stay. Throws std::invalid_argument for another row count.
  void set_rules(GroupKind kind, GroupRules rules);
  // FrictionLaw::given_strength: the shear strength (scaled) of every
  // contact vertex, in group order (problem().contact_vertex_count of
  // them). The QP's pattern, and so the symbolic analysis, stays.
  void set_shear_strengths(const std::vector<double>& strengths);

  // Starts the next solve(true) from `solution` (e.g. a Result of the same
  // structure); ignored by the solver when its sizes do not fit.
  void set_starting_point(InteriorPointSolution solution) { solution_ = std::move(solution); }
  // Solves the current QP: cold, or from the last solution when warm_start.
  // The result's `solution` stays empty: the object keeps it (solution(),
  // take_solution()). Throws std::logic_error on an object without a
  // structure (built from a problem).
  EquilibriumResult solve(bool warm_start = false);
  // Solves the current QP under `solver` (its own iteration limit, tolerance
  // or certify_below) and keeps the solution, without the result's forces
  // and verdict: the solver's report only. Cold, or warm from the last
  // solution (or set_starting_point's) when warm_start.
  InteriorPointInfo solve_qp(const InteriorPointSettings& solver, bool warm_start = false);
  // Whether `load` alone (scaled, as set_rhs takes it), nothing else
  // loaded, is carried compression-only: the QP with `load` as its
  // right-hand side (it stays so), from a cold start, stopped at the first
  // forces that balance it without tension to settings().stable_tolerance
  // (certified); false when not proven within `max_iterations` (the
  // iterations taken go to `iterations`). On a structure that stands,
  // where the feasible forces form a cone (no bounded cable or shear
  // strength), every multiple of such a load stands too: the ray along
  // which a load factor or a block's load capacity is unbounded.
  bool carries_alone(Eigen::VectorXd load, int max_iterations, int& iterations);

  const EquilibriumProblem& problem() const { return problem_; }
  const AnalysisSettings& settings() const { return settings_; }
  SolverCores cores() const { return cores_; }
  // The last solution (scaled; see InteriorPointSolution).
  const InteriorPointSolution& solution() const { return solution_; }
  // How often the normal matrix's pattern was analysed: 1, plus one for
  // each update() or set_group() that changed the contact pattern beyond
  // a refit.
  int symbolic_analyses() const { return symbolic_analyses_; }

  // The response of the last optimum to changed loads (Shin 2014 eq. 7):
  // see EquilibriumSolver::prepare_response. Reuses this object's
  // factorisation pattern; false when the last solve gave no answer.
  bool prepare_response();
  const EquilibriumSolver& solver() const { return *solver_; }

  // Move the QP or the last solution out, for a result that outlives the
  // object (it then needs an update() before solving again).
  EquilibriumProblem take_problem() { return std::move(problem_); }
  InteriorPointSolution take_solution() { return std::move(solution_); }

private:
  // A solver for problem_ unless the current one fits it.
  void fit_solver();

  const Structure* structure_ = nullptr;
  AnalysisSettings settings_;
  SolverCores cores_ = SolverCores::all;
  EquilibriumProblem problem_;
  std::unique_ptr<EquilibriumSolver> solver_;
  InteriorPointSolution solution_;
  // See EquilibriumResult::floating_gaps; found by the first solve() that
  // reports them (floating_gaps_found_).
  std::vector<MissedContact> floating_gaps_;
  bool floating_gaps_found_ = false;
  SolverStatus last_status_ = SolverStatus::numerical_error;
  double setup_seconds_ = 0.0;  // of the last constructor or update()
  int symbolic_analyses_ = 0;
};

// Analyses of a sequence of structures that differ in their dimensions
// (a parametric search's models, an optimiser's steps): one
// EquilibriumAnalysis serves them all, its symbolic factorisation kept
// while the contacts are, and with warm starts each solve begins at the
// last optimum: 3-28 % fewer interior-point iterations per search on
// arches, vaults, a dome and a flying buttress. A structure with another
// number of blocks is not offered the last optimum (the solver itself also
// starts cold when the unknowns' sizes differ), nor is a failed solve.
class AnalysisSequence {
public:
  AnalysisSequence(AnalysisSettings settings, bool warm_start)
      : settings_(std::move(settings)), warm_start_(warm_start) {}

  // The analysis object set up for `structure` (which must outlive its use).
  EquilibriumAnalysis& set_up(const Structure& structure);
  // set_up, then solve: from the last optimum when warm starts are on and
  // one of a structure with as many blocks exists.
  EquilibriumResult analyze(const Structure& structure);

private:
  AnalysisSettings settings_;
  bool warm_start_;
  std::unique_ptr<EquilibriumAnalysis> analysis_;
  bool has_optimum_ = false;  // the last solve ended with an optimum to start from
  int optimum_blocks_ = -1;   // of a structure with this many blocks
};

}  // namespace ashlar
