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

  // Solves `model`, a program with an optimum (feasible and bounded: on
  // an infeasible one Clp's predictor-corrector may abort the process,
  // "dual off to infinity"), by the barrier, without presolve, scaling or
  // crossover:
  // the model's primal and dual solutions are the barrier's last iterate
  // (or, where it stops without a verdict, those of Clp's own barrier and
  // crossover). Returns Clp's status (0 optimal, 1 primal infeasible, 2
  // dual infeasible, 3 iteration limit, 4 numerical difficulties).
  int solve(ClpSimplex& model);
  // Barrier iterations of the last solve.
  int iterations() const { return iterations_; }

private:
  std::unique_ptr<BarrierNormalEquations> normal_;
  int iterations_ = 0;
};

}  // namespace ashlar
