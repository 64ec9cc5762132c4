#include "analysis/load_capacity.hpp"

#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <future>
#include <limits>
#include <memory>
#include <mutex>

#include "analysis/clp_barrier.hpp"
#include "analysis/equilibrium_analysis.hpp"
#include "analysis/equilibrium_program.hpp"
#include "analysis/interior_point.hpp"
#include "analysis/problem_symmetry.hpp"
#include "core/clock.hpp"
#include "core/interrupt.hpp"
#include "core/parallel_loop.hpp"

namespace ashlar {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The equilibrium program with one more column per analysed block: the
// multiple of its weight, fixed at 1 (multiplier_column[j], -1 if none).
EquilibriumProgram capacity_program(const Structure& structure, const EquilibriumProblem& problem,
                                    const EquilibriumOptions& options,
                                    std::vector<int>& multiplier_column) {
  EquilibriumProgram program = equilibrium_program(problem, options);
  const int vertical = problem.vertical_row();
  multiplier_column.assign(structure.size(), -1);
  for (int j = 0; j < structure.size(); ++j) {
    const int row = problem.row_of_block[j];
    const double weight = structure.block(j).mass() * kGravity / problem.weight_unit;
    if (row < 0 || !(weight > 0.0)) continue;
    const int column = program.add_column(1.0, 1.0);
    multiplier_column[j] = column;
    program.add_entry(row + vertical, column, -weight);
    program.row_lower[row + vertical] -= weight;
    program.row_upper[row + vertical] -= weight;
  }
  return program;
}

// On 3D structures, both questions go first to the equilibrium solver
// (interior_point.hpp), which eliminates each contact vertex's unknowns and
// factors the contact graph's normal matrix, about half the cost of Clp's
// barrier iteration on the same program:
// - whether the block could be weightless (least multiple 0): the
//   analysis's own verdict with the block's weight removed, warm from the
//   as-built forces, stopped at the first iterate whose compression-only
//   forces balance every block (InteriorPointSettings::certify_below): 3-4
//   iterations on a dome, where the least multiple by the simplex took
//   ~70 pivots and a refactorised basis;
// - the largest multiple under a cap: the capacity program as the
//   solver's problem with no regularisation (a linear program in the
//   contact vertices' (c, f_u, f_v), their friction rows and one group
//   more, the multiple t of the block's weight, t in [0, cap], objective
//   -t), warm from the as-built forces with t = 1. Tension is a decoupled
//   1/2 s^2 (zero throughout) and the virtual torques are gone: the
//   capacity program's feasible set. Only where the friction rows bound the
//   forces in every direction, with nothing but contacts: 0 < mu <
//   infinity, no cables.
// Where it does not converge, or the weightless block is not certified,
// the simplex and Clp's barrier answer as before.
class InteriorCapacity {
public:
  static bool certifies(const EquilibriumProblem& problem, const EquilibriumOptions& options) {
    return problem.block_rows == 6 && options.friction_law == FrictionLaw::coulomb;
  }
  static bool maximises(const EquilibriumProblem& problem, const EquilibriumOptions& options) {
    return certifies(problem, options) && problem.contacts_only() && options.friction > 0.0 &&
           std::isfinite(options.friction);
  }

  // analysis: of the problem (its right-hand side is changed per block),
  // on the worker's cores. as_built: the analysis's optimum of the
  // problem, shared by the workers.
  InteriorCapacity(std::unique_ptr<EquilibriumAnalysis> analysis, const InteriorPointSolution& as_built,
                   const AnalysisSettings& settings, bool maximise)
      : analysis_(std::move(analysis)), rhs_(analysis_->problem().rhs), as_built_(as_built),
        settings_(settings.solver), analysis_settings_(settings) {
    settings_.certify_below = settings.stable_tolerance;
    if (maximise) build_program();
  }

  bool maximises() const { return multiple_group_ >= 0; }

  // Whether the structure stands with the weight (scaled) of the block
  // whose first balance row is `row` removed.
  bool stands_weightless(int row, double weight, int& iterations) {
    Eigen::VectorXd rhs = rhs_;
    rhs(row + analysis_->problem().vertical_row()) -= weight;
    analysis_->set_rhs(std::move(rhs));
    analysis_->set_starting_point(as_built_);
    const InteriorPointInfo info = analysis_->solve_qp(settings_, /*warm_start=*/true);
    iterations = info.iterations;
    return info.status == SolverStatus::certified;
  }

  // Whether that weight alone, nothing else loaded, is carried
  // compression-only (EquilibriumAnalysis::carries_alone): then no
  // multiple of it is too much.
  bool carries_weight_alone(int row, double weight, int& iterations) {
    const EquilibriumProblem& problem = analysis_->problem();
    Eigen::VectorXd load = Eigen::VectorXd::Zero(problem.row_count);
    load(row + problem.vertical_row()) = weight;
    return analysis_->carries_alone(std::move(load), kAloneIterations, iterations);
  }

  // The largest multiple of that weight under `cap`; NaN when the solver
  // did not converge.
  double largest(int row, double weight, double cap, int& iterations) {
    const int vertical = analysis_->problem().vertical_row();
    const int multiple = multiple_group_;
    ForceGroup group = maximum_ ? maximum_->problem().groups[multiple] : program_.groups[multiple];
    group.row_a = row;
    group.set_alone_on_a(vertical, 0, -weight);
    group.bound = cap;
    Eigen::VectorXd rhs = rhs_;
    rhs(row + vertical) -= weight;
    if (!maximum_) {
      // Analysed with the multiple's group on the first block asked.
      program_.groups[multiple] = group;
      program_.rhs = std::move(rhs);
      maximum_ = std::make_unique<EquilibriumAnalysis>(std::move(program_), analysis_settings_,
                                                       analysis_->cores());
    } else {
      // The multiple's group moved to this block's diagonal: the pattern holds (a refit).
      maximum_->set_group(multiple, group);
      maximum_->set_rhs(std::move(rhs));
    }
    // The as-built forces, tension dropped, carrying t = 1: feasible, and
    // 27 iterations on a dome's blocks where the cold start took 34.
    InteriorPointSolution start;
    start.x = Eigen::VectorXd::Zero(4 * (multiple + 1));
    start.x.head(4 * multiple) = as_built_.x.head(4 * multiple);
    for (int k = 0; k < multiple; ++k) start.x(4 * k + 1) = 0.0;
    start.x(4 * multiple) = 1.0;
    const int inequalities = program_inequalities_;
    start.y = Eigen::VectorXd::Zero(maximum_->problem().row_count);
    start.w = Eigen::VectorXd::Ones(inequalities);  // recomputed from x by the solver
    start.z = Eigen::VectorXd::Constant(inequalities, kStartMultiplier);
    maximum_->set_starting_point(std::move(start));
    InteriorPointSettings settings;
    settings.merge_twins = false;  // a dome's vertices have no twins; the solver's setting is for the analysis
    // The gap relative to the objective bounds the maximum's error: 1e-8
    // keeps it two orders inside the 1e-6 the bounds are held to, and
    // saves an iteration in 20 against the analysis's 1e-10 (the 16 x 18
    // dome's maxima within 7.3e-9 of the simplex-era references).
    settings.tolerance = 1e-8;
    const InteriorPointInfo info = maximum_->solve_qp(settings, /*warm_start=*/true);
    iterations = info.iterations;
    return info.status == SolverStatus::converged ? maximum_->solution().x(4 * multiple) : kNaN;
  }

private:
  // The multipliers' start: 0.1 took fewer iterations on a dome than 1 or 0.01.
  static constexpr double kStartMultiplier = 0.1;
  // Iterations carries_weight_alone is given. The unbounded blocks were
  // proven in 8-12 (the 16 x 18 dome's 64) and 10-17 (a 498-block vault's
  // 124); a block whose finite maximum lies beyond the first cap spends
  // them all before the ray test.
  static constexpr int kAloneIterations = 30;

  void build_program() {
    program_ = analysis_->problem();
    std::vector<ForceGroup>& groups = program_.groups;
    groups.erase(std::remove_if(groups.begin(), groups.end(),
                                [](const ForceGroup& group) { return group.kind != GroupKind::contact_vertex; }),
                 groups.end());
    for (ForceGroup& group : groups) group.on_b.col(1).setZero();  // tension acts on no block
    // The friction rows alone: with 0 < mu < infinity they imply c >= 0
    // (the pyramid's sides, or the box's, sum to a positive multiple of
    // c), so that row, and s >= 0, go. A fifth fewer rows for the solver's
    // passes over the vertices, and four rows, not five, meeting in three
    // unknowns at each cone's apex: the imperfect 16 x 18 dome's every
    // block 8,377 -> 7,964 iterations, 11.4 s -> 10.3 s on 2 cores; the
    // 1,008-voussoir vault's middle course 1,107 -> 1,111 iterations,
    // 10.5 s -> 9.4 s. The bounds within 8.3e-9 and 2.3e-9 (relative) of
    // the program with the row.
    GroupRules& contact = program_.rules[static_cast<int>(GroupKind::contact_vertex)];
    contact.rows = contact.rows.bottomRows(contact.rows.rows() - 2).eval();
    contact.bound_coefficients.resize(0);
    contact.hessian << 0.0, 1.0, 0.0, 0.0;
    contact.linear.setZero();
    GroupRules& multiple = program_.rules[static_cast<int>(GroupKind::weight)];
    multiple.rows = Eigen::Matrix<double, Eigen::Dynamic, 4>::Zero(2, 4);
    multiple.rows(0, 0) = 1.0;   // t >= 0
    multiple.rows(1, 0) = -1.0;  // -t >= -cap (the group's bound)
    multiple.bound_coefficients = Eigen::Vector2d(0.0, 1.0);
    multiple.hessian << 0.0, 1.0, 1.0, 1.0;  // its other unknowns: decoupled, zero
    multiple.linear << -1.0, 0.0, 0.0, 0.0;
    ForceGroup group;
    group.kind = GroupKind::weight;
    groups.push_back(group);
    program_.contact_vertex_count = static_cast<int>(groups.size()) - 1;
    multiple_group_ = program_.contact_vertex_count;
    program_inequalities_ = program_.inequality_starts().back();
  }

  std::unique_ptr<EquilibriumAnalysis> analysis_;  // its right-hand side changed per block
  Eigen::VectorXd rhs_;  // the analysis's as built, which the capacity program shares
  const InteriorPointSolution& as_built_;
  InteriorPointSettings settings_;
  AnalysisSettings analysis_settings_;
  // The largest multiple's QP, until its analysis is set up by the first
  // largest() (no groups when not used), and that analysis.
  EquilibriumProblem program_;
  std::unique_ptr<EquilibriumAnalysis> maximum_;
  int multiple_group_ = -1;  // the multiple's group in the program
  int program_inequalities_ = 0;
};

// Simplex pivots allowed for a planar largest multiple before the barrier takes over.
constexpr int kSimplexBudget = 50;
// The first cap on a largest multiple under the barrier, raised a
// hundredfold while a finite maximum lies beyond it, up to the last.
constexpr double kFirstCap = 1e4;
constexpr double kLastCap = 1e12;
// Relative distance from the cap within which the barrier's maximum counts
// as the cap (its optimum is accurate to about 1e-9 relative).
constexpr double kAtCap = 1e-6;

// Clp's status of a program that failed; "infeasible" once the least
// multiple was found feasible can only be a numerical failure.
int failure_status(int status) { return status == 1 ? 4 : status; }

// The as-built optimum, where every multiple is 1: each block's least
// multiple starts from it, as one block's extreme basis (a ray, when
// unbounded) is a poor start for the next block's.
struct Basis {
  std::vector<unsigned char> status;
  std::vector<double> columns, rows;

  explicit Basis(ClpSimplex& simplex)
      : status(simplex.statusArray(), simplex.statusArray() + simplex.numberColumns() + simplex.numberRows()),
        columns(simplex.primalColumnSolution(), simplex.primalColumnSolution() + simplex.numberColumns()),
        rows(simplex.primalRowSolution(), simplex.primalRowSolution() + simplex.numberRows()) {}

  void restore(ClpSimplex& simplex) const {
    simplex.copyinStatus(status.data());
    std::copy(columns.begin(), columns.end(), simplex.primalColumnSolution());
    std::copy(rows.begin(), rows.end(), simplex.primalRowSolution());
  }
};

// The as-built program, solved once by the dual simplex (about half the
// primal's pivots on domes), from scratch, in place: on planar structures
// on a thread of its own while the workers begin, as every block's least
// multiple starts from its basis; on 3D structures, where the equilibrium
// solver certifies most blocks weightless and no block then needs the
// basis, only when a block does (by the first worker that asks; the others
// wait) or when the as-built analysis does not certify that the structure
// stands. Its 4,432 pivots on the 16 x 18 dome took 1.0 s, a tenth of the
// whole run, and on the same dome with every vertex moved by up to 0.1 %
// (no symmetry) about 6,000 pivots that no block needed, on a third thread
// beside two workers on two cores.
class AsBuiltProgram {
public:
  // `capacity`: the program, solved in place; the workers' copies of it
  // must be made before the first solve().
  explicit AsBuiltProgram(ClpSimplex& capacity) : program_(capacity) {}
  AsBuiltProgram(const AsBuiltProgram&) = delete;
  AsBuiltProgram& operator=(const AsBuiltProgram&) = delete;

  // Solves the program unless done: one thread solves it, the others
  // wait; an error goes to the thread that solved, and the next caller
  // tries again.
  void solve() {
    std::call_once(solved_once_, [this] {
      program_.dual();
      status_ = program_.status();
      pivots_ = program_.numberIterations();
      if (status_ == 0) basis_ = std::make_unique<Basis>(program_);
      solved_ = true;
    });
  }
  // The optimal basis, or null when the program has none (infeasible: the
  // structure does not stand as built; or failed). Solves it first.
  const Basis* basis() {
    solve();
    return basis_.get();
  }
  // `copy` becomes the solved program, as the simplex left it (its
  // factorisation and scaling: from an unsolved copy with the same basis
  // restored, a 16-course vault's least multiples took 22 % more pivots).
  // Solves it first; one copy at a time, the model only read.
  void copy_solved(ClpSimplex& copy) {
    solve();
    const std::lock_guard<std::mutex> lock(copying_);
    copy = program_;
  }
  // Whether it was solved (after the workers are done).
  bool solved() const { return solved_; }
  // Clp's status and pivots, once solved.
  int status() const { return status_; }
  int pivots() const { return pivots_; }

private:
  ClpSimplex& program_;
  std::once_flag solved_once_;
  std::atomic<bool> solved_{false};
  int status_ = -1, pivots_ = 0;
  std::unique_ptr<Basis> basis_;
  std::mutex copying_;
};

// The recession directions of the feasible set: forces d with A d = -g_j
// (block j's weight alone, carried without tension or any other load). The
// largest multiple of block j is unbounded exactly when such a d exists.
// The cost (total compression) only gives the dual simplex a bounded
// program to warm-start from the previous block's.
ClpSimplex recession_program(const CoinPackedMatrix& matrix, const EquilibriumProgram& program) {
  std::vector<double> lower(program.columns), upper(program.columns), cost(program.columns);
  for (int c = 0; c < program.columns; ++c) {
    // A bounded column (a capped cable, a fixed multiple) cannot grow along a ray.
    lower[c] = program.column_lower[c] <= -COIN_DBL_MAX ? -COIN_DBL_MAX : 0.0;
    upper[c] = program.column_upper[c] >= COIN_DBL_MAX ? COIN_DBL_MAX : 0.0;
    cost[c] = lower[c] == 0.0 && upper[c] > 0.0 ? 1.0 : 0.0;
  }
  const std::vector<double> zero(program.rows, 0.0);
  ClpSimplex rays;
  rays.setLogLevel(0);
  rays.loadProblem(matrix, lower.data(), upper.data(), cost.data(), zero.data(), zero.data());
  stop_on_request(rays);
  return rays;
}

struct BlockBounds {
  double min = kNaN, max = kNaN;
  int failure = 0;  // Clp's status when a program failed
  int programs = 0, pivots = 0;
  bool solved = false;  // false: skipped, the computation was interrupted first
};

// One worker's programs, on its own copies of the models (a Clp model is
// not shared between threads).
class BlockPrograms {
public:
  // planar: whether the largest multiple tries the simplex first.
  // interior: the equilibrium solver's questions (InteriorCapacity), or null.
  BlockPrograms(const ClpSimplex& capacity, const ClpSimplex& rays, AsBuiltProgram& as_built, bool planar,
                std::unique_ptr<InteriorCapacity> interior)
      : initial_capacity_(capacity), initial_rays_(rays), capacity_(capacity), rays_(rays),
        interior_(std::move(interior)), as_built_(as_built), planar_(planar) {}

  // Back to the state of construction before a chunk of blocks: the Clp
  // models as copied (no simplex basis of an earlier block, no previous ray
  // to warm-start from) and no guess that the next block is unbounded.
  // The equilibrium solver's questions start from the as-built forces, or
  // cold, every time, and keep nothing of earlier blocks to restore.
  void restart() {
    if (!used_) return;
    capacity_ = initial_capacity_;
    rays_ = initial_rays_;
    solved_copy_ = false;
    ray_column_ = -1;
    last_unbounded_ = false;
    used_ = false;
  }

  // The bounds of the multiple in `column` (fixed at 1 between calls) of
  // `weight` (scaled) on the block whose first balance row is `row`.
  BlockBounds solve(int column, int row, double weight) {
    used_ = true;
    BlockBounds bounds;
    bounds.solved = true;
    int iterations = 0;
    const bool weightless = interior_ && interior_->stands_weightless(row, weight, iterations);
    if (interior_) count(bounds, iterations);
    if (weightless) {
      bounds.min = 0.0;
      bounds.max = largest(column, row, weight, bounds);
    } else {
      // Least: from the as-built basis, where the multiple 1 is feasible,
      // by the primal simplex (a few dozen pivots).
      if (!solved_copy_) {  // the first block here to need the simplex
        as_built_.copy_solved(capacity_);
        solved_copy_ = true;
      }
      capacity_.setColumnBounds(column, 0.0, COIN_DBL_MAX);
      capacity_.setObjectiveCoefficient(column, 1.0);
      if (const Basis* basis = as_built_.basis()) basis->restore(capacity_);
      capacity_.primal();
      count(bounds, capacity_.numberIterations());
      if (capacity_.status() == 0) {
        bounds.min = capacity_.primalColumnSolution()[column];
        bounds.max = largest(column, row, weight, bounds);
      } else if (capacity_.status() != 1) {  // 1: no multiple lets the rest stand
        bounds.failure = capacity_.status();
      }
    }
    if (bounds.failure != 0 || std::isnan(bounds.max)) bounds.min = bounds.max = kNaN;
    capacity_.setObjectiveCoefficient(column, 0.0);
    capacity_.setColumnBounds(column, 1.0, 1.0);
    return bounds;
  }

private:
  // Largest, on a planar structure first by the primal simplex from the
  // least's optimum, with a small pivot budget: on arches it ends in a few
  // pivots, at the optimum or on a ray. Past the budget, and on every 3D
  // structure, under a cap by the equilibrium solver (InteriorCapacity) or
  // Clp's barrier, then the ray test when the cap binds: from the as-built
  // basis the simplex takes 10^4 pivots on a friction dome, whose blocks
  // carry hundreds of times their weight, and the budget ran out on 285 of
  // the 289 blocks of a 16 x 18 dome (the other 4 the ray test finds); the
  // interior-point methods take 20-70 iterations. row and weight (scaled):
  // the block's first balance row and its weight, as solve() takes them.
  double largest(int column, int row, double weight, BlockBounds& bounds) {
    capacity_.setObjectiveCoefficient(column, -1.0);
    if (planar_) {
      const int unlimited = capacity_.maximumIterations();
      capacity_.setMaximumIterations(kSimplexBudget);
      capacity_.primal();
      capacity_.setMaximumIterations(unlimited);
      count(bounds, capacity_.numberIterations());
      if (capacity_.status() == 0) return capacity_.primalColumnSolution()[column];
      if (capacity_.status() == 2) return std::numeric_limits<double>::infinity();
      if (capacity_.status() != 3) {  // 3: the budget ran out
        bounds.failure = failure_status(capacity_.status());
        return kNaN;
      }
    }
    // Unbounded blocks come in runs (a dome's lowest courses, a vault's
    // springings): after one, the proof that the weight alone is carried
    // goes first and saves the capped program, 11-21 iterations on the
    // 16 x 18 dome's unbounded blocks against 8-12 for the proof. A wrong
    // guess, once per run, costs the proof's 30. Iterations in all: an
    // imperfect 16 x 18 dome 9,560 -> 8,655, the 1,008-voussoir vault
    // 21,176 -> 19,735; the bounds the same.
    const bool maximises = interior_ && interior_->maximises();
    bool alone_tried = false;
    if (maximises && last_unbounded_) {
      alone_tried = true;
      if (carried_alone(row, weight, bounds)) return std::numeric_limits<double>::infinity();
    }
    for (double cap = kFirstCap; cap <= kLastCap; cap *= 100) {
      if (cap < bounds.min) continue;  // the capped program must be feasible (clp_barrier.hpp)
      double multiple = kNaN;
      if (maximises) {
        int iterations = 0;
        multiple = interior_->largest(row, weight, cap, iterations);
        count(bounds, iterations);
      }
      if (std::isnan(multiple)) {
        multiple = barrier_largest(column, cap, bounds);
        if (bounds.failure != 0) return kNaN;
      }
      // An interior optimum at the cap lies within the solvers' tolerance
      // of it, not on it: a maximum that close goes to the ray test. The
      // equilibrium solver's proof that the weight alone is carried comes
      // first: Clp's dual simplex on the recession program took 28 s of a
      // 498-block vault's 107 s on one core (its load capacity on 2 cores
      // 99.6 s -> 64.8 s, the bounds the same to the bit).
      if (multiple < cap * (1 - kAtCap)) return multiple;
      if (maximises && cap == kFirstCap && !alone_tried && carried_alone(row, weight, bounds)) {
        return std::numeric_limits<double>::infinity();
      }
      if (has_ray(column, bounds)) return std::numeric_limits<double>::infinity();
      if (bounds.failure != 0) return kNaN;
    }
    bounds.failure = 4;
    return kNaN;
  }

  // The equilibrium solver's proof that the block's weight alone is
  // carried (InteriorCapacity::carries_weight_alone), remembered for the
  // next block.
  bool carried_alone(int row, double weight, BlockBounds& bounds) {
    int iterations = 0;
    last_unbounded_ = interior_->carries_weight_alone(row, weight, iterations);
    count(bounds, iterations);
    return last_unbounded_;
  }

  // The largest multiple under `cap` by Clp's barrier.
  double barrier_largest(int column, double cap, BlockBounds& bounds) {
    capacity_.setColumnBounds(column, 0.0, cap);
    // Only the optimum's value is wanted, not a vertex: no crossover, and
    // no presolve (a program that changes in one column's bounds gains
    // nothing from it); the two were a third of the CPU time on a
    // 161-block dome. The barrier's optimum agrees with the vertex's to
    // 6e-10 relative there.
    barrier_.solve(capacity_);
    count(bounds, capacity_.numberIterations());
    if (capacity_.status() != 0) {
      bounds.failure = failure_status(capacity_.status());
      return kNaN;
    }
    return capacity_.primalColumnSolution()[column];
  }

  bool has_ray(int column, BlockBounds& bounds) {
    if (ray_column_ >= 0) rays_.setColumnBounds(ray_column_, 0.0, 0.0);
    rays_.setColumnBounds(column, 1.0, 1.0);
    ray_column_ = column;
    rays_.dual();  // the previous block's optimum stays dual feasible
    count(bounds, rays_.numberIterations());
    if (rays_.status() > 1) bounds.failure = rays_.status();
    return rays_.status() == 0;
  }

  static void count(BlockBounds& bounds, int iterations) {
    ++bounds.programs;
    bounds.pivots += iterations;
  }

  const ClpSimplex initial_capacity_;  // as built, unsolved: the capacity program's copy at a restart
  const ClpSimplex& initial_rays_;
  ClpSimplex capacity_, rays_;
  std::unique_ptr<InteriorCapacity> interior_;
  BarrierSolver barrier_;  // its normal equations analysed once for all blocks
  AsBuiltProgram& as_built_;
  bool solved_copy_ = false;  // capacity_ copied from the solved as-built program
  bool planar_;
  int ray_column_ = -1;
  bool last_unbounded_ = false;  // whether this worker's last block was proven unbounded by the solver
  bool used_ = false;            // a block solved since construction or the last restart
};

// Blocks per chunk: a chunk's blocks (consecutive in block order) are
// solved by one worker, each warm from the one before (the simplex bases,
// the previous ray, the guess that a run of unbounded blocks goes on), and
// every chunk starts afresh (BlockPrograms::restart). A block's bounds then
// depend on its chunk alone, not on the thread that took it or on what that
// thread solved before: the same, to the bit, in every run and for any
// number of threads. When workers took blocks one at a time and each went
// on warm from its own last, the 16 x 18 dome's bounds changed between
// 2-thread runs (a block's largest multiple 20546.2 in one run and
// unbounded in another; the planar arches' in the last digits). A dome's
// course has 16-32 blocks: a chunk of 16 holds most of a run of unbounded
// ones. Fewer than 32 blocks solved (a few blocks asked, a symmetric
// model's orbits) are split in two halves, of at least 4, so that two
// workers share them: in chunks of 16 the 16 blocks of a course asked ran
// on one core. The chunks depend on the number of blocks solved, never on
// the threads.
size_t chunk_blocks(size_t solved) {
  constexpr size_t kChunkBlocks = 16, kLeastChunk = 4;
  return std::min(kChunkBlocks, std::max(kLeastChunk, (solved + 1) / 2));
}

}  // namespace

LoadCapacity load_capacity(const Structure& structure, const LoadCapacitySettings& capacity_settings,
                           const ProgressCount& progress) {
  const auto start = Clock::now();
  const AnalysisSettings& settings = capacity_settings.analysis;
  const int threads = capacity_settings.threads;
  const bool use_symmetry = capacity_settings.use_symmetry;
  check_analysis_settings(settings);  // planar or 3D, as the analyses of 3D structures do
  const std::vector<char> asked = asked_blocks(structure, capacity_settings.blocks, "load capacity");
  const EquilibriumProblem problem = build_equilibrium_problem(structure, settings.problem);
  // A block's bounds are optimal values: its images under the problem's
  // symmetries have the same, and only one block of each orbit is solved.
  const ProblemSymmetry symmetry = find_problem_symmetry(structure, problem, use_symmetry);
  std::vector<int> multiplier_column;
  const EquilibriumProgram program = capacity_program(structure, problem, settings.problem, multiplier_column);

  LoadCapacity result;
  result.min.assign(structure.size(), kNaN);
  result.max.assign(structure.size(), kNaN);
  ClpSimplex capacity;
  load_program(capacity, program);
  const CoinPackedMatrix matrix = *capacity.matrix();
  const ClpSimplex rays = recession_program(matrix, program);

  // The blocks solved: one per orbit with a block asked, in block order.
  std::vector<int> blocks;
  std::vector<int> slot(structure.size(), -1);  // per block solved, its index in `blocks`
  for (int j = 0; j < structure.size(); ++j) {
    if (multiplier_column[j] >= 0 && asked[j]) slot[symmetry.representative[j]] = 0;
  }
  for (int j = 0; j < structure.size(); ++j) {
    if (slot[j] < 0) continue;
    slot[j] = static_cast<int>(blocks.size());
    blocks.push_back(j);
  }
  std::vector<int> solved_as(structure.size(), -1);  // per block asked, its orbit's index in `blocks`
  for (int j = 0; j < structure.size(); ++j) {
    if (multiplier_column[j] >= 0 && asked[j]) solved_as[j] = slot[symmetry.representative[j]];
  }
  std::vector<BlockBounds> bounds(blocks.size());
  // The copies are made here, one thread reading the models at a time.
  std::vector<BlockPrograms> programs;
  const size_t chunk_size = chunk_blocks(blocks.size());
  const size_t chunks = (blocks.size() + chunk_size - 1) / chunk_size;
  const int workers = worker_count(threads, static_cast<int>(chunks));
  programs.reserve(workers);
  // The as-built forces for the equilibrium solver's warm starts; none
  // when it finds no optimum (the simplex and the barrier answer alone).
  // The as-built analysis runs on every core; a lone worker goes on with it.
  InteriorPointSolution as_built_forces;
  std::unique_ptr<EquilibriumAnalysis> as_built_analysis;
  bool interior = InteriorCapacity::certifies(problem, settings.problem);
  int as_built_iterations = 0;
  if (interior) {
    as_built_analysis = std::make_unique<EquilibriumAnalysis>(problem, settings, SolverCores::all);
    const InteriorPointInfo info = as_built_analysis->solve_qp(settings.solver);
    interior = !has_no_answer(info.status);
    as_built_iterations = info.iterations;
    as_built_forces = as_built_analysis->take_solution();
  }
  // Whether the as-built forces prove that the structure stands (the
  // analysis's own verdict: compression-only, to stable_tolerance); then
  // the simplex's as-built program is solved only for a block that needs
  // its basis.
  const bool certified_as_built = interior && !problem.has_floating_bodies() &&
                                  compression_only_imbalance(problem, as_built_forces.x) <= settings.stable_tolerance;
  const bool maximise = interior && InteriorCapacity::maximises(problem, settings.problem);
  // No block is begun once a stop is asked for (Ctrl-C, the caller's
  // sandbox deadline, a worker's error). Progress is told on the calling
  // thread.
  AsBuiltProgram as_built(capacity);  // solved once the copies are made
  const SolverCores solver_cores = workers > 1 ? SolverCores::one : SolverCores::all;
  for (int w = 0; w < workers; ++w) {
    std::unique_ptr<InteriorCapacity> interior_capacity;
    if (interior) {
      std::unique_ptr<EquilibriumAnalysis> analysis =
          workers == 1 ? std::move(as_built_analysis)
                       : std::make_unique<EquilibriumAnalysis>(problem, settings, solver_cores);
      interior_capacity = std::make_unique<InteriorCapacity>(std::move(analysis), as_built_forces, settings, maximise);
    }
    programs.emplace_back(capacity, rays, as_built, problem.block_rows == 3, std::move(interior_capacity));
  }
  as_built_analysis.reset();
  std::atomic<size_t> next{0};  // the next chunk to take
  std::atomic<int> done{0};
  const int total = static_cast<int>(blocks.size());
  auto work = [&](BlockPrograms& mine, bool tells) {
    for (size_t chunk = next++; chunk < chunks && !stop_requested(); chunk = next++) {
      mine.restart();
      const size_t end = std::min(blocks.size(), (chunk + 1) * chunk_size);
      for (size_t k = chunk * chunk_size; k < end && !stop_requested(); ++k) {
        const int j = blocks[k];
        bounds[k] = mine.solve(multiplier_column[j], problem.row_of_block[j],
                               structure.block(j).mass() * kGravity / problem.weight_unit);
        const int now = ++done;
        if (tells && progress) progress(now, total);
      }
    }
  };
  if (progress) progress(0, total);
  // Worker 0 on this thread; the as-built program on a part of its own
  // unless the as-built forces are certified.
  const int parts = certified_as_built ? workers : workers + 1;
  ParallelLoop(parts, 1).run_parts(parts, [&](int part) {
    if (part == workers) as_built.solve();
    else work(programs[part], part == 0);
  });
  if (progress) progress(done, total);

  // The as-built program counts once: the simplex's when it was solved,
  // else the equilibrium solver's certified analysis.
  result.programs = 1;
  result.symmetries = static_cast<int>(symmetry.block_maps.size());
  if (certified_as_built && !as_built.solved()) {
    result.simplex_iterations = as_built_iterations;
    result.stable = true;
  } else {
    as_built.solve();  // when no block needed it, nor was it begun
    result.simplex_iterations = as_built.pivots();
    result.stable = as_built.status() == 0 && !problem.has_floating_bodies();
  }
  if (as_built.solved() && as_built.status() > 2) {  // no bounds without the as-built program
    result.status = clp_failure(as_built.status());
    result.seconds = seconds_since(start);
    return result;
  }

  bool interrupted = false;
  for (int j = 0; j < structure.size(); ++j) {
    if (solved_as[j] < 0) continue;
    result.min[j] = bounds[solved_as[j]].min;
    result.max[j] = bounds[solved_as[j]].max;
  }
  for (size_t k = 0; k < blocks.size(); ++k) {
    result.programs += bounds[k].programs;
    result.simplex_iterations += bounds[k].pivots;
    if (bounds[k].failure != 0 && result.status == MarginStatus::optimal) result.status = clp_failure(bounds[k].failure);
    interrupted = interrupted || !bounds[k].solved || bounds[k].failure == kClpInterrupted;
  }
  if (interrupted) {  // the blocks done keep their bounds; no verdict
    result.status = clp_failure(kClpInterrupted);
    result.stable = false;
  }
  result.seconds = seconds_since(start);
  return result;
}

}  // namespace ashlar
