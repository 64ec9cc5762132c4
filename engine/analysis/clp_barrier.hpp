// Clp's barrier method (ClpInterior's Mehrotra predictor-corrector) with the
// normal equations A D A^T factored by CHOLMOD (core/sparse_cholesky.hpp)
// instead of Clp's own Cholesky, whose ordering is by row counts only: on
// the 305-block dome's capacity program (1,734 rows, 18,834 columns) Clp's
// factor takes 1.5e7 flops an iteration. The pattern of A D A^T depends only
// on the constraint matrix, so one BarrierSolver analyses it once and every
// later program with the same matrix (other bounds, other objective) reuses
// the analysis. Clp stays in the .cpp.
#pragma once

#include <memory>

class ClpSimplex;

namespace ashlar {

struct BarrierNormalEquations;  // the analysed pattern and its factor (in the .cpp)

class BarrierSolver {
public:
  BarrierSolver();
  ~BarrierSolver();
  BarrierSolver(BarrierSolver&&) noexcept;
  BarrierSolver& operator=(BarrierSolver&&) noexcept;

  // Solves `model`, a feasible program (on an infeasible one Clp's
  // predictor-corrector may abort the process, "dual off to infinity"; on
  // an unbounded one it may stop far out and call that optimal, a load
  // factor of 1e16 with rows broken), by the barrier, without presolve,
  // scaling or crossover:
  // the model's primal and dual solutions are the barrier's last iterate
  // (or, where it stops without a verdict, those of Clp's own barrier and
  // crossover). Returns Clp's status (0 optimal, 1 primal infeasible, 2
  // dual infeasible, 3 iteration limit, 4 numerical difficulties).
  // iteration_limit: the barrier's iterations before it stops with status
  // 3; 0 for ClpSolve's (1,000 on programs of more than 10,000 rows and
  // columns, else Clp's default).
  int solve(ClpSimplex& model, int iteration_limit = 0);
  // Barrier iterations of the last solve.
  int iterations() const { return iterations_; }

private:
  std::unique_ptr<BarrierNormalEquations> normal_;
  int iterations_ = 0;
};

}  // namespace ashlar
