// The contact solver (dynamics/contact_solver.hpp) on one step of a column
// of blocks standing on the ground, against statics: the ground's impulse
// carries the column's weight times the step, and the friction the
// horizontal body force times the step; no block moves. With its global
// steps the solve takes tens of sweeps; the sweeps alone (the same fixed
// point) more than ten times as many; a solve cut short reports its
// largest residual and where. A grid of such columns side by side, large
// enough to be split over two threads, meets the same statics and gives
// the same impulses in every solve.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dynamics/contact_solver.hpp"
#include "box_column.hpp"

using namespace ashlar;
using namespace ashlar::test;

namespace {

// The impulse (world frame, N s) the ground's joint gives the column.
Vec3 ground_impulse(const Column& c) {
  Vec3 total = Vec3::Zero();
  for (const ContactRow& row : c.rows) {
    if (row.a == 0) total += row.frame.transpose() * row.impulse;
  }
  return total;
}

double fastest(const Column& c) {
  double speed = 0.0;
  for (size_t i = 1; i < c.bodies.linear.size(); ++i) {
    speed = std::max({speed, c.bodies.linear[i].norm(), c.bodies.angular[i].norm() * kSide});
  }
  return speed;
}

// `columns` columns of `levels` blocks side by side on the ground (body
// 0), touching: each bed joint's and each side joint's four corners a row,
// level by level from the top (the simulation's order), the side joints
// of a level after its bed joints. Body 1 + level * columns + column.
Column grid(int columns, int levels, double sideways, double friction) {
  Column c = column(columns * levels, sideways, friction);
  c.rows.clear();
  const auto body = [&](int column, int level) { return level < 0 ? 0 : 1 + level * columns + column; };
  const auto centroid = [&](int column, int level) {
    return level < 0 ? Vec3(0, 0, -0.5 * kHeight) : Vec3(column * kSide, 0, (level + 0.5) * kHeight);
  };
  const auto add = [&](int column_a, int level_a, int column_b, int level_b, const Vec3& normal,
                       const std::vector<Vec3>& points) {
    for (const Vec3& point : points) {
      ContactRow row;
      row.a = body(column_a, level_a);
      row.b = body(column_b, level_b);
      row.arm_a = point - centroid(column_a, level_a);
      row.arm_b = point - centroid(column_b, level_b);
      row.frame = contact_frame(normal);
      row.friction = friction;
      c.rows.push_back(row);
    }
  };
  const double half = 0.5 * kSide;
  for (int level = levels - 1; level >= 0; --level) {
    const double z = level * kHeight;
    for (int column = 0; column < columns; ++column) {
      const double x = column * kSide;
      add(column, level - 1, column, level, Vec3::UnitZ(),
          {Vec3(x - half, -half, z), Vec3(x + half, -half, z), Vec3(x - half, half, z), Vec3(x + half, half, z)});
    }
    for (int column = 0; column + 1 < columns; ++column) {
      const double x = column * kSide + half;
      add(column, level, column + 1, level, Vec3::UnitX(),
          {Vec3(x, -half, z), Vec3(x, half, z), Vec3(x, -half, z + kHeight), Vec3(x, half, z + kHeight)});
    }
  }
  return c;
}

}  // namespace

TEST(ContactSolver, AColumnCarriesItsWeightAndTheSidewaysForceToTheGroundInAFewSweeps) {
  // 20 blocks, 4 m high, 0.5 m wide: 0.05 g sideways is below the
  // friction (0.6) and below the whole column's uplift threshold
  // (g b / h = 0.125 g), so the base's centre of pressure stays inside it.
  const int n = 20;
  const double sideways = 0.05 * 9.81;
  ContactSolverSettings settings;
  // Held to 1e-9 m/s: the per-point residual adds up along the column
  // (each joint may slip by it), so the statics below hold to about
  // n^2 blocks' mass times it.
  settings.velocity_tolerance = 1e-9;
  Column c = column(n, sideways, 0.6);
  const ContactSolverReport report = ContactSolver().solve(c.rows, c.bodies, settings);
  const Vec3 impulse = ground_impulse(c);
  std::printf("column of %d: %d sweeps, %d global steps, residual %.3g m/s, ground impulse (%.6g, %.3g, %.6g) N s\n",
              n, report.sweeps, report.global_steps, report.residual, impulse.x(), impulse.y(), impulse.z());
  EXPECT_TRUE(report.converged);
  EXPECT_LE(report.residual, settings.velocity_tolerance);
  // Statics, to the solver's tolerance.
  const double slack = 10.0 * n * n * kMass * settings.velocity_tolerance;
  EXPECT_NEAR(impulse.z(), n * kMass * 9.81 * kStep, slack);
  EXPECT_NEAR(impulse.x(), -n * kMass * sideways * kStep, slack);
  EXPECT_NEAR(impulse.y(), 0.0, slack);
  EXPECT_LT(fastest(c), 10.0 * n * settings.velocity_tolerance);
  EXPECT_GE(report.global_steps, 1);
  EXPECT_LE(report.sweeps, 100);
  // The sweeps alone carry a change of load one joint a sweep: more than
  // ten times the sweeps (they stop at max_sweeps, 1,000, unsolved).
  settings.global_steps = false;
  settings.interior_after_sweeps = 0;
  Column alone = column(n, sideways, 0.6);
  const ContactSolverReport sweeps_only = ContactSolver().solve(alone.rows, alone.bodies, settings);
  std::printf("column of %d, sweeps only: %d sweeps, residual %.3g m/s\n", n, sweeps_only.sweeps, sweeps_only.residual);
  EXPECT_GT(sweeps_only.sweeps, 10 * report.sweeps);
}

TEST(ContactSolver, ASolveCutShortReportsItsLargestResidualAndWhere) {
  Column c = column(10, 0.0, 0.6);
  ContactSolverSettings settings;
  settings.velocity_tolerance = 1e-9;
  settings.max_sweeps = 1;
  settings.global_steps = false;
  const ContactSolverReport report = ContactSolver().solve(c.rows, c.bodies, settings);
  EXPECT_FALSE(report.converged);
  EXPECT_EQ(report.sweeps, 1);
  EXPECT_GT(report.residual, settings.velocity_tolerance);
  // Before any impulse every block falls at g h, together: the joints
  // between blocks close at no speed, the ground's points at g h (and,
  // once the first has pushed the bottom block up and turned it, the
  // others faster): the largest residual is at least g h, at the ground.
  EXPECT_GE(report.residual, 9.81 * kStep - 1e-12);
  ASSERT_GE(report.worst_row, 0);
  ASSERT_LT(report.worst_row, static_cast<int>(c.rows.size()));
  EXPECT_EQ(c.rows[report.worst_row].a, 0);
}

TEST(ContactSolver, AGridSplitOverTwoThreadsCarriesItsWeightAndGivesTheSameImpulsesEveryTime) {
  // 10 columns of 30 blocks: 2,280 rows, over the 2,000 from which a solve
  // is split. 0.05 g sideways is below the friction (0.6) and the grid's
  // uplift threshold (g b / h = 0.83 g), so statics hold as for one column.
  const int columns = 10, levels = 30, n = columns * levels;
  const double sideways = 0.0;
  ContactSolverSettings settings;
  settings.velocity_tolerance = 1e-9;
  const auto solve = [&](int threads, Column& c) {
    const ContactSolverReport report = ContactSolver(threads).solve(c.rows, c.bodies, settings);
    const Vec3 impulse = ground_impulse(c);
    std::printf("grid of %d on %d thread(s): %zu rows, %d sweeps, %d global steps, residual %.3g m/s\n", n, threads,
                c.rows.size(), report.sweeps, report.global_steps, report.residual);
    EXPECT_TRUE(report.converged);
    const double slack = 10.0 * levels * levels * kMass * settings.velocity_tolerance;
    EXPECT_NEAR(impulse.z(), n * kMass * 9.81 * kStep, slack);
    EXPECT_NEAR(impulse.x(), -n * kMass * sideways * kStep, slack);
    EXPECT_NEAR(impulse.y(), 0.0, slack);
    EXPECT_LT(fastest(c), 10.0 * levels * settings.velocity_tolerance);
  };
  Column split = grid(columns, levels, sideways, 0.6), again = split, one = split;
  ASSERT_GT(split.rows.size(), 2000u);
  solve(2, split);
  solve(2, again);
  solve(1, one);
  for (size_t k = 0; k < split.rows.size(); ++k) {
    ASSERT_EQ(split.rows[k].impulse, again.rows[k].impulse) << "row " << k;  // to the bit
  }
  for (size_t i = 0; i < split.bodies.linear.size(); ++i) {
    ASSERT_EQ(split.bodies.linear[i], again.bodies.linear[i]) << "body " << i;
    ASSERT_EQ(split.bodies.angular[i], again.bodies.angular[i]) << "body " << i;
  }
}
