#include "analysis/load_capacity.hpp"

#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <thread>

#include "analysis/clp_barrier.hpp"
#include "analysis/equilibrium_program.hpp"
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
  BlockPrograms(const ClpSimplex& capacity, const ClpSimplex& rays, const Basis* as_built, bool planar)
      : capacity_(capacity), rays_(rays), as_built_(as_built), planar_(planar) {}

  // The bounds of the multiple in `column` (fixed at 1 between calls).
  BlockBounds solve(int column) {
    BlockBounds bounds;
    bounds.solved = true;
    // Least: from the as-built basis, where the multiple 1 is feasible, by
    // the primal simplex (a few dozen pivots).
    capacity_.setColumnBounds(column, 0.0, COIN_DBL_MAX);
    capacity_.setObjectiveCoefficient(column, 1.0);
    if (as_built_) as_built_->restore(capacity_);
    capacity_.primal();
    count(bounds, capacity_);
    if (capacity_.status() == 0) {
      bounds.min = capacity_.primalColumnSolution()[column];
      bounds.max = largest(column, bounds);
    } else if (capacity_.status() != 1) {  // 1: no multiple lets the rest stand
      bounds.failure = capacity_.status();
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
  // structure, by the barrier method under a cap, then the ray test when
  // the cap binds: from the as-built basis the simplex takes 10^4 pivots
  // on a friction dome, whose blocks carry hundreds of times their weight,
  // and the budget ran out on 285 of the 289 blocks of a 16 x 18 dome
  // (the other 4 the ray test finds); the barrier takes 20-70 iterations.
  double largest(int column, BlockBounds& bounds) {
    capacity_.setObjectiveCoefficient(column, -1.0);
    if (planar_) {
      const int unlimited = capacity_.maximumIterations();
      capacity_.setMaximumIterations(kSimplexBudget);
      capacity_.primal();
      capacity_.setMaximumIterations(unlimited);
      count(bounds, capacity_);
      if (capacity_.status() == 0) return capacity_.primalColumnSolution()[column];
      if (capacity_.status() == 2) return std::numeric_limits<double>::infinity();
      if (capacity_.status() != 3) {  // 3: the budget ran out
        bounds.failure = failure_status(capacity_.status());
        return kNaN;
      }
    }
    for (double cap = kFirstCap; cap <= kLastCap; cap *= 100) {
      if (cap < bounds.min) continue;  // the capped program must be feasible (clp_barrier.hpp)
      capacity_.setColumnBounds(column, 0.0, cap);
      // Only the optimum's value is wanted, not a vertex: no crossover, and
      // no presolve (a program that changes in one column's bounds gains
      // nothing from it); the two were a third of the CPU time on a
      // 161-block dome. The barrier's optimum agrees with the vertex's to
      // 6e-10 relative there.
      barrier_.solve(capacity_);
      count(bounds, capacity_);
      if (capacity_.status() != 0) {
        bounds.failure = failure_status(capacity_.status());
        return kNaN;
      }
      // An interior optimum at the cap lies within the barrier's tolerance
      // of it, not on it: a maximum that close goes to the ray test.
      const double multiple = capacity_.primalColumnSolution()[column];
      if (multiple < cap * (1 - kAtCap)) return multiple;
      if (has_ray(column, bounds)) return std::numeric_limits<double>::infinity();
      if (bounds.failure != 0) return kNaN;
    }
    bounds.failure = 4;
    return kNaN;
  }

  bool has_ray(int column, BlockBounds& bounds) {
    if (ray_column_ >= 0) rays_.setColumnBounds(ray_column_, 0.0, 0.0);
    rays_.setColumnBounds(column, 1.0, 1.0);
    ray_column_ = column;
    rays_.dual();  // the previous block's optimum stays dual feasible
    count(bounds, rays_);
    if (rays_.status() > 1) bounds.failure = rays_.status();
    return rays_.status() == 0;
  }

  static void count(BlockBounds& bounds, const ClpSimplex& simplex) {
    ++bounds.programs;
    bounds.pivots += simplex.numberIterations();
  }

  ClpSimplex capacity_, rays_;
  BarrierSolver barrier_;  // its normal equations analysed once for all blocks
  const Basis* as_built_;
  bool planar_;
  int ray_column_ = -1;
};

}  // namespace

LoadCapacity load_capacity(const Structure& structure, const AnalysisSettings& settings, int threads,
                           const ProgressCount& progress) {
  const auto start = Clock::now();
  const EquilibriumProblem problem = build_equilibrium_problem(structure, settings.problem);
  std::vector<int> multiplier_column;
  const EquilibriumProgram program = capacity_program(structure, problem, settings.problem, multiplier_column);

  LoadCapacity result;
  result.min.assign(structure.size(), kNaN);
  result.max.assign(structure.size(), kNaN);
  ClpSimplex capacity;
  load_program(capacity, program);
  const CoinPackedMatrix matrix = *capacity.matrix();
  // The as-built program from scratch by the dual simplex (about half the
  // primal's pivots on domes).
  capacity.dual();
  const int as_built = capacity.status();
  result.programs = 1;
  result.simplex_iterations = capacity.numberIterations();
  result.stable = as_built == 0 && !problem.has_floating_bodies();
  if (as_built > 2) {
    result.status = clp_failure(as_built);
    result.seconds = seconds_since(start);
    return result;
  }
  const Basis basis(capacity);
  const ClpSimplex rays = recession_program(matrix, program);

  std::vector<int> blocks;
  for (int j = 0; j < structure.size(); ++j) {
    if (multiplier_column[j] >= 0) blocks.push_back(j);
  }
  std::vector<BlockBounds> bounds(blocks.size());
  // The copies are made here, one thread reading the models at a time.
  std::vector<BlockPrograms> programs;
  const int workers = worker_count(threads, static_cast<int>(blocks.size()));
  programs.reserve(workers);
  for (int w = 0; w < workers; ++w) programs.emplace_back(capacity, rays, as_built == 0 ? &basis : nullptr, problem.block_rows == 3);
  std::atomic<size_t> next{0};
  std::atomic<int> done{0};
  const int total = static_cast<int>(blocks.size());
  // The helpers answer to the caller's sandbox deadline too; no block is
  // begun once a stop is asked for. Progress is told on the calling thread.
  const Clock::time_point deadline = stop_deadline();
  auto work = [&](BlockPrograms& mine, bool tells) {
    const DeadlineScope scope(deadline);
    for (size_t k = next++; k < blocks.size() && !stop_requested(); k = next++) {
      bounds[k] = mine.solve(multiplier_column[blocks[k]]);
      const int now = ++done;
      if (tells && progress) progress(now, total);
    }
  };
  if (progress) progress(0, total);
  std::vector<std::thread> helpers;
  for (int w = 1; w < workers; ++w) helpers.emplace_back(work, std::ref(programs[w]), false);
  work(programs[0], true);
  for (std::thread& thread : helpers) thread.join();
  if (progress) progress(done, total);

  bool interrupted = false;
  for (size_t k = 0; k < blocks.size(); ++k) {
    result.min[blocks[k]] = bounds[k].min;
    result.max[blocks[k]] = bounds[k].max;
    result.programs += bounds[k].programs;
    result.simplex_iterations += bounds[k].pivots;
    if (bounds[k].failure != 0 && result.status == "optimal") result.status = clp_failure(bounds[k].failure);
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
