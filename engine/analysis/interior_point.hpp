// Primal-dual interior-point solver (Mehrotra predictor-corrector) for the
// equilibrium QP of equilibrium_problem.hpp.
//
// The Hessian is diagonal and every inequality row involves the unknowns of
// one contact vertex, so eliminating the unknowns vertex by vertex (4 x 4
// systems) leaves normal equations A Phi^-1 A^T dy = r of size 6 x (free
// blocks) (3 x for planar problems), sparse with the contact graph's
// pattern. That matrix is analysed once (EquilibriumSolver's constructor)
// and factorised once per iteration; predictor and corrector share the
// factorisation. Where the iterate tells the optimum's active set (every
// row's slack and multiplier far apart) the solve tries to finish on it:
// one Newton step with those rows held as equalities and the others
// dropped lands on the optimum to rounding (interior_point.cpp's
// ActiveSetPolish; the 10,051-block walls 18-19 -> 11 iterations).
//
// Its pieces: the normal matrix and its pattern (normal_matrix.hpp,
// normal_pattern.hpp), a group's eliminated block (phi_factor.hpp), twin
// vertices solved as one group (twin_groups.hpp), the Newton system with
// iterative refinement (newton_system.hpp), residuals (iterate_residuals.hpp),
// starting point and step lengths (step_policy.hpp) and the best iterate
// kept when the tolerance is out of reach (best_iterate.hpp). Shapes and
// units: interior_point_iterate.hpp.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "analysis/equilibrium_problem.hpp"
#include "analysis/interior_point_iterate.hpp"
#include "analysis/normal_matrix.hpp"
#include "analysis/phi_factor.hpp"
#include "analysis/twin_groups.hpp"
#include "core/enum_names.hpp"
#include "core/parallel_loop.hpp"

namespace ashlar {

struct InteriorPointSettings {
  int max_iterations = 100;   // Newton iterations before giving up
  double tolerance = 1e-10;   // on scaled residuals, and on the total duality gap relative to objective_floor + |objective|
  // The least objective the duality gap is measured against: 1 (scaled
  // units), or less for problems whose optimum is far smaller and whose
  // answer is the optimum's detail, not its value (important weights).
  double objective_floor = 1.0;
  double step_fraction = 0.99;  // of the step to the boundary taken each iteration
  // When the iterations stop short of `tolerance` (rounding, or the
  // iteration limit), the best iterate is still returned, with status
  // inaccurate, if its residuals and gap are within this.
  double inaccurate_tolerance = 1e-5;
  // When > 0, the solve stops (status certified) at the first iterate whose
  // forces, tension dropped, balance every body to this tolerance
  // (compression_only_imbalance): stability is proven, the optimum is not
  // needed. 0: always solve to the optimum.
  double certify_below = 0.0;
  // Solve twin contact vertices (twin_groups.hpp) as one group each; false solves
  // every vertex on its own (the same optimum, for checking the merge).
  bool merge_twins = true;
};

enum class SolverStatus {
  converged,
  inaccurate,       // stopped short of the tolerance; the best iterate meets inaccurate_tolerance
  max_iterations,   // stopped at max_iterations, or after 20 iterations without progress
  numerical_error,  // a factorisation or step failed (e.g. loss of positive definiteness)
  interrupted,      // Ctrl-C or a sandboxed script's deadline (ashlar::stop_requested)
  certified,        // stopped at forces that prove stability (InteriorPointSettings::certify_below)
  infeasible,       // the constraints have no solution (IPOPT, method cra: no compatible compression-only equilibrium)
};
inline constexpr EnumNames<SolverStatus, 7> kSolverStatusNames{{{{SolverStatus::converged, "converged"},
                                                                 {SolverStatus::inaccurate, "inaccurate"},
                                                                 {SolverStatus::max_iterations, "max_iterations"},
                                                                 {SolverStatus::numerical_error, "numerical_error"},
                                                                 {SolverStatus::interrupted, "interrupted"},
                                                                 {SolverStatus::certified, "certified"},
                                                                 {SolverStatus::infeasible, "infeasible"}}}};

// "converged", "inaccurate", "max_iterations", "numerical_error", "interrupted",
// "certified" or "infeasible".
const char* status_name(SolverStatus status);

// Whether the solve ended without an equilibrium one may use.
inline bool has_no_answer(SolverStatus status) {
  return status == SolverStatus::numerical_error || status == SolverStatus::interrupted;
}

struct InteriorPointInfo {
  SolverStatus status = SolverStatus::numerical_error;
  int iterations = 0;
  int factorizations = 0;
  int groups = 0;                   // force groups solved: the problem's, fewer where twins merged
  double objective = 0.0;           // scaled, as in the QPS export
  double primal_residual = 0.0;     // max |A x - b|, scaled
  double dual_residual = 0.0;       // max |H x + q - A^T y - G^T z|
  double complementarity = 0.0;     // mean w_i z_i (the total is the duality gap)
  double assembly_seconds = 0.0;    // residuals, vertex eliminations, normal-matrix values
  double factorization_seconds = 0.0;
  double solve_seconds = 0.0;       // triangular solves and step updates
};

// The cores one solver may use: all of them (one analysis at a time), or
// one, for solvers that run side by side on worker threads (load capacity's
// and important weights' blocks). There splitting each factorisation over
// two cores (core/sparse_cholesky.hpp) only made the workers' threads wait
// for each other: the 16 x 24 dome's 2,310-row normal matrix, its load
// capacity on 2 cores 16.0-16.5 s -> 15.1-15.5 s in alternating runs, its
// important weights 10.5 s -> 10.1 s.
enum class SolverCores { all, one };

class EquilibriumSolver {
public:
  // Builds and analyses the normal-equation pattern of `problem`.
  explicit EquilibriumSolver(const EquilibriumProblem& problem, SolverCores cores = SolverCores::all);
  ~EquilibriumSolver();

  // Whether `problem` has the pattern this solver analysed: the same
  // balance rows, and every force group acting on the same bodies' rows.
  bool fits(const EquilibriumProblem& problem) const;
  // Makes the solver fit `problem` without a new analysis when its groups
  // add only to blocks of the analysed pattern (a group moved to another
  // body, or to two bodies already in contact): true then, in time linear
  // in the groups; false, and the solver unchanged, otherwise.
  bool refit(const EquilibriumProblem& problem);

  // Solves `problem` (same contacts as at construction: fits(problem)). When `warm_start`
  // is set and `solution` has matching sizes it is the starting point.
  InteriorPointInfo solve(const EquilibriumProblem& problem, const InteriorPointSettings& settings,
                          InteriorPointSolution& solution, bool warm_start = false);

  // The response of the optimum to a change of the balance rows' right-hand
  // side with its active set held (Shin 2014 eq. 7): in interior-point
  // form, the barrier terms z/w of the optimum stand for the active
  // constraints (huge) and the inactive ones (vanishing), so
  //     dx = Phi^-1 A^T (A Phi^-1 A^T)^-1 db
  // with Phi the per-group matrices of the last Newton system. Factorises
  // once (false when that fails or `solution` does not fit `problem`); then
  // any number of directions cost a pair of triangular solves each.
  // `merge` as InteriorPointSettings::merge_twins.
  bool prepare_response(const EquilibriumProblem& problem, const InteriorPointSolution& solution,
                        bool merge = true);
  // (A Phi^-1 A^T)^-1 db, row_count long, scaled; db scaled as problem.rhs.
  Eigen::VectorXd multiplier_response(const Eigen::VectorXd& delta_rhs) const;
  // dx of group `group` (scaled, 4) from multiplier_response's answer.
  Eigen::Vector4d group_response(const EquilibriumProblem& problem, int group,
                                 const Eigen::VectorXd& multipliers) const;

private:
  // The twin classes of `problem` (none unless `merge`), and the normal
  // matrix working on them when they changed.
  void find_twins(const EquilibriumProblem& problem, bool merge);
  // solve() of the groups the solver works on, `problem` merged or not.
  InteriorPointInfo solve_groups(const EquilibriumProblem& problem, const InteriorPointSettings& settings,
                                 InteriorPointSolution& solution, bool warm_start);
  // solve_groups() for D = block rows per body: the Mehrotra
  // predictor-corrector iterations.
  template <int D>
  InteriorPointInfo solve_rows(const EquilibriumProblem& problem, const InteriorPointSettings& settings,
                               InteriorPointSolution& solution, bool warm_start);

  ParallelLoop loop_;  // passes over the groups, on one thread per core
  NormalMatrix normal_;
  TwinGroups twins_;
  std::vector<PhiFactor> response_phi_;  // factor R of Phi per group at prepare_response
  bool response_ready_ = false;
};

}  // namespace ashlar
