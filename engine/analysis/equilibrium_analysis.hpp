// One equilibrium analysis of a structure, as an object: it owns the QP
// (EquilibriumProblem), the solver with its symbolic factorisation of the
// normal matrix's pattern, and the last solution, split as
//   setup  (constructor: check settings, build the QP, analyse the pattern),
//   update (new loads, friction or geometry: rebuild the QP, keep the
//           symbolic analysis when the contact pattern is unchanged),
//   solve  (any number of times; warm from the last solution on request).
// Parametric searches, gradients, weight sensitivity, force flow and the
// optimiser re-solve one object instead of analysing the pattern again.
#pragma once

#include <memory>

#include "analysis/equilibrium.hpp"
#include "analysis/equilibrium_problem.hpp"
#include "analysis/interior_point.hpp"

namespace ashlar {

// The forces of the scaled unknowns x (4 per group of `problem`, as the
// solver's) into `result`: interfaces (parallel to `interfaces`, the
// structure's under the problem's contact options), vertex forces and
// positions, block tension, cable forces and virtual torques, in N and m.
// Returns the penalised unknowns' linear cost (scaled), the infeasibility
// before division by the body count. Every method that ends in forces of
// this QP's groups reports them through this one function.
double fill_result_forces(const Structure& structure, const std::vector<Interface>& interfaces,
                          const EquilibriumProblem& problem, const Eigen::VectorXd& x, EquilibriumResult& result);

class EquilibriumAnalysis {
public:
  // Throws InvalidArgument for bad settings or a structure the analysis
  // refuses (as analyze_equilibrium). `structure` must outlive the object,
  // or the next update().
  EquilibriumAnalysis(const Structure& structure, const AnalysisSettings& settings);
  ~EquilibriumAnalysis();
  EquilibriumAnalysis(const EquilibriumAnalysis&) = delete;
  EquilibriumAnalysis& operator=(const EquilibriumAnalysis&) = delete;

  // The QP of `structure` under `settings`. The symbolic factorisation is
  // kept when every force group acts on the same bodies' rows as before
  // (same contacts; loads, friction and vertex positions may change), else
  // redone. The last solution stays, as a warm start for solve(true).
  void update(const Structure& structure, const AnalysisSettings& settings);
  // Starts the next solve(true) from `solution` (e.g. a Result of the same
  // structure); ignored by the solver when its sizes do not fit.
  void set_starting_point(const InteriorPointSolution& solution) { solution_ = solution; }
  // FrictionLaw::given_strength: the shear strength (scaled) of every
  // contact vertex, in group order (problem().contact_vertex_count of
  // them). The QP's pattern, and so the symbolic analysis, stays.
  void set_shear_strengths(const std::vector<double>& strengths);
  // Solves the current QP: cold, or from the last solution when warm_start.
  // The result's `solution` stays empty: the object keeps it (solution(),
  // take_solution()).
  EquilibriumResult solve(bool warm_start = false);

  const EquilibriumProblem& problem() const { return problem_; }
  const AnalysisSettings& settings() const { return settings_; }
  // The last solution (scaled; see InteriorPointSolution).
  const InteriorPointSolution& solution() const { return solution_; }
  // How often the normal matrix's pattern was analysed: 1, plus one for
  // each update() that changed the contact pattern.
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
  const Structure* structure_;
  AnalysisSettings settings_;
  EquilibriumProblem problem_;
  std::unique_ptr<EquilibriumSolver> solver_;
  InteriorPointSolution solution_;
  std::vector<MissedContact> floating_gaps_;  // see EquilibriumResult::floating_gaps
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
