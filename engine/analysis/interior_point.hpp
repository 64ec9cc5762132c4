// Primal-dual interior-point solver (Mehrotra predictor-corrector) for the
// equilibrium QP of equilibrium_problem.hpp.
//
// The Hessian is diagonal and every inequality row involves the unknowns of
// one contact vertex, so eliminating the unknowns vertex by vertex (4 x 4
// systems) leaves normal equations A Phi^-1 A^T dy = r of size 6 x (free
// blocks) (3 x for planar problems), sparse with the contact graph's pattern. That matrix is analysed
// once (EquilibriumSolver's constructor) and factorised once per iteration;
// predictor and corrector share the factorisation.
//
// Twins: contact vertices with the same rules, bodies, bound and effect on
// the balance rows (a planar problem's vertex pairs on either face of the
// wall, which differ only in y) have one optimum, the same forces at each
// (the objective is strictly convex in them and symmetric). The solver
// takes m such twins as one group with effect m A, objective m (1/2 x^T H x
// + q^T x) and the same inequalities, whose multipliers are m times each
// twin's, and hands every twin the group's x, w and z / m: the same QP,
// with half the per-group work on a planar wall.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "analysis/equilibrium_problem.hpp"
#include "core/parallel_loop.hpp"

namespace ashlar {

class SparseCholesky;

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
  // Solve twin contact vertices (see above) as one group each; false solves
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

// Primal x (4 per force group, scaled), equality multipliers y, inequality
// slacks w and multipliers z (the group's rule rows per group, in order).
struct InteriorPointSolution {
  Eigen::VectorXd x, y, w, z;
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

  // A group's factor R of Phi = R^T R (4 x 4 upper triangular), its 10
  // entries packed by rows, diagonal stored inverted: 80 bytes a group
  // instead of a full matrix's 128 (100 MB less on a 100,052-block vault).
  // (Public for the solver's helper functions; not used outside it.)
  struct PhiFactor {
    double packed[10];
    double& operator()(int i, int j) { return packed[i * (7 - i) / 2 + j]; }
    double operator()(int i, int j) const { return packed[i * (7 - i) / 2 + j]; }
  };

private:
  // Fills the normal matrix A Phi^-1 A^T for barrier scaling z/w (slacks w
  // and multipliers z, one per inequality row, rows of group k from
  // first_row[k]) and each group's factor R of Phi = R^T R (upper
  // triangular). D = block_rows_ (3 or 6) at compile time; assemble()
  // picks it.
  template <int D>
  void assemble_normal_matrix(const EquilibriumProblem& problem, const std::vector<int>& first_row,
                              const Eigen::VectorXd& w, const Eigen::VectorXd& z,
                              std::vector<PhiFactor>& phi_factors);
  void assemble(const EquilibriumProblem& problem, const std::vector<int>& first_row,
                const Eigen::VectorXd& w, const Eigen::VectorXd& z,
                std::vector<PhiFactor>& phi_factors);
  // Splits the normal matrix's block columns among loop_'s parts
  // (part_first_column_, part_groups_) so that each adds about as many
  // blocks.
  void partition_columns(int blocks);
  // solve() for D = block_rows_ balance rows per body.
  template <int D>
  InteriorPointInfo solve_rows(const EquilibriumProblem& problem, const InteriorPointSettings& settings,
                               InteriorPointSolution& solution, bool warm_start);
  bool factorize_shifted();

  // The twin classes of `problem` (see the file comment; none unless
  // `merge`): twins_ and, when they changed, the slots and parts of the
  // groups the solver works on.
  void find_twins(const EquilibriumProblem& problem, bool merge);
  // `problem` with each twin class as one group (find_twins first).
  EquilibriumProblem merge_twins(const EquilibriumProblem& problem) const;
  // Where each merged group's inequality rows start (and the total), from
  // the problem's (EquilibriumProblem::inequality_starts).
  std::vector<int> merged_first_rows(const std::vector<int>& full_first_row) const;
  // The number of twins group k of the groups worked on stands for.
  double twin_count(int k) const { return twins_.count.empty() ? 1.0 : twins_.count[k]; }
  // One of the problem's solutions in the merged groups' unknowns, and back.
  void merge_solution(const InteriorPointSolution& full, const std::vector<int>& full_first_row,
                      InteriorPointSolution& merged) const;
  void split_solution(const InteriorPointSolution& merged, const std::vector<int>& full_first_row,
                      InteriorPointSolution& full) const;
  // solve() of the groups the solver works on, `problem` merged or not.
  InteriorPointInfo solve_groups(const EquilibriumProblem& problem, const InteriorPointSettings& settings,
                                 InteriorPointSolution& solution, bool warm_start);

  struct VertexSlots {
    int row_a = -1, row_b = -1;     // the group's bodies' first balance rows
    int aa = -1, bb = -1, ab = -1;  // pattern slots of the 6 x 6 blocks, -1 if absent
    bool ab_transposed = false;     // block (a, b) stored as (b, a) in the upper triangle
  };
  // The slots of `problem`'s groups in the analysed pattern; false if some
  // group adds to a block the pattern lacks.
  bool find_slots(const EquilibriumProblem& problem, std::vector<VertexSlots>& slots) const;
  std::vector<std::vector<int>> block_pattern_;  // per block column J, its block rows I <= J, sorted
  std::vector<VertexSlots> pattern_slots_;  // per group of the problem analysed (fits())
  // The groups the solver works on: the problem's, or its twin classes.
  struct Twins {
    std::vector<int> merged_of;     // problem group -> merged group; empty: no twins
    std::vector<int> first_member;  // merged group -> its first problem group
    std::vector<double> count;      // merged group -> its number of twins (m)
  } twins_;
  std::vector<VertexSlots> merged_slots_;  // per merged group, when twins merge
  const std::vector<VertexSlots>& worked_slots() const {
    return twins_.merged_of.empty() ? pattern_slots_ : merged_slots_;
  }
  ParallelLoop loop_;  // passes over the groups, on one thread per core
  // The assembly's parts: part p adds into block columns
  // [part_first_column_[p], part_first_column_[p + 1]), for the groups
  // part_groups_[p] (empty lists for a single part: every group).
  std::vector<int> part_first_column_;
  std::vector<std::vector<int>> part_groups_;
  std::vector<int> column_starts_;
  std::unique_ptr<SparseCholesky> cholesky_;
  int size_ = 0;
  int block_rows_ = 6;
  std::vector<PhiFactor> response_phi_;  // factor R of Phi per group at prepare_response
  bool response_ready_ = false;
};

// Whether `load` alone (scaled, as problem.rhs), nothing else loaded, is
// carried compression-only by `problem`'s force groups: `solver` (analysed
// for `problem`) on `problem` with `load` as its right-hand side, from a
// cold start, stopped at the first forces that balance it without tension
// to `stable_tolerance` (InteriorPointSettings::certify_below, the
// analysis's stability proof); false when not proven within
// `max_iterations` (the iterations taken go to `iterations`). On a
// structure that stands, where the feasible forces form a cone (no
// bounded cable or shear strength), every multiple of such a load stands
// too: the ray along which a load factor or a block's load capacity is
// unbounded.
bool carries_alone(EquilibriumSolver& solver, EquilibriumProblem problem, const Eigen::VectorXd& load,
                   double stable_tolerance, int max_iterations, int& iterations);

}  // namespace ashlar
