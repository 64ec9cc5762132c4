// Clp's barrier on CHOLMOD normal equations against closed-form optima, and
// the same analysis reused for programs that differ in bounds and objective.
#include <gtest/gtest.h>

#include <ClpSimplex.hpp>
#include <CoinPackedMatrix.hpp>
#include <limits>
#include <vector>

#include "analysis/clp_barrier.hpp"

using namespace ashlar;

namespace {

// maximise c . x over x1 + 2 x2 <= 4, 3 x1 + x2 <= 6, 0 <= x <= upper.
ClpSimplex two_by_two(double upper) {
  const std::vector<int> rows{0, 1, 0, 1}, columns{0, 0, 1, 1};
  const std::vector<double> values{1, 3, 2, 1};
  CoinPackedMatrix matrix(true, rows.data(), columns.data(), values.data(), 4);
  const std::vector<double> column_lower(2, 0.0), column_upper(2, upper), cost{-1.0, -1.0};
  const std::vector<double> row_lower(2, -COIN_DBL_MAX), row_upper{4.0, 6.0};
  ClpSimplex model;
  model.setLogLevel(0);
  model.loadProblem(matrix, column_lower.data(), column_upper.data(), cost.data(), row_lower.data(),
                    row_upper.data());
  return model;
}

}  // namespace

TEST(ClpBarrier, ReachesTheClosedFormOptimaWithOneAnalysis) {
  ClpSimplex model = two_by_two(COIN_DBL_MAX);
  BarrierSolver barrier;
  // Both rows bind: x = (8/5, 6/5).
  ASSERT_EQ(barrier.solve(model), 0);
  EXPECT_GT(barrier.iterations(), 0);
  EXPECT_NEAR(model.primalColumnSolution()[0], 1.6, 1e-7);
  EXPECT_NEAR(model.primalColumnSolution()[1], 1.2, 1e-7);
  EXPECT_NEAR(model.objectiveValue(), -2.8, 1e-7);
  // Another objective on the same matrix: x1 alone, up to 3 x1 <= 6.
  model.setObjectiveCoefficient(1, 0.0);
  ASSERT_EQ(barrier.solve(model), 0);
  EXPECT_NEAR(model.primalColumnSolution()[0], 2.0, 1e-7);
  // Other bounds: x1 <= 1 binds, and x2 then meets x1 + 2 x2 <= 4.
  model.setObjectiveCoefficient(1, -1.0);
  // Without crossover a variable at its bound stays an interior iterate's
  // distance from it: Clp's primal tolerance, 1e-7.
  model.setColumnUpper(0, 1.0);
  ASSERT_EQ(barrier.solve(model), 0);
  EXPECT_NEAR(model.primalColumnSolution()[0], 1.0, 1e-6);
  EXPECT_NEAR(model.primalColumnSolution()[1], 1.5, 1e-6);
  EXPECT_NEAR(model.objectiveValue(), -2.5, 1e-6);
  // A changed entry is another matrix, analysed afresh: with 3 x1 + x2 <= 6
  // turned into x1 + x2 <= 6 the optimum moves to x = (4, 0).
  model.setColumnUpper(0, COIN_DBL_MAX);
  model.modifyCoefficient(1, 0, 1.0);
  ASSERT_EQ(barrier.solve(model), 0);
  EXPECT_NEAR(model.objectiveValue(), -4.0, 1e-6);
}

TEST(ClpBarrier, FindsAnUnboundedDirectionCappedByABound) {
  // Without the rows' limits x2 grows alone up to its bound: the cap binds.
  ClpSimplex model = two_by_two(1e4);
  model.setRowUpper(0, COIN_DBL_MAX);
  model.setRowUpper(1, COIN_DBL_MAX);
  BarrierSolver barrier;
  ASSERT_EQ(barrier.solve(model), 0);
  EXPECT_NEAR(model.objectiveValue(), -2e4, 2e4 * 1e-7);
}
