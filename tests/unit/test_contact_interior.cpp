// The interior-point method of dynamics/contact_interior.hpp on one step
// of a box standing on the ground by its four corners (three independent:
// the rows are redundant), under gravity and a horizontal body force a
// (the ground an incline of slope a / g): against the closed forms of a
// block on an incline, sliding when a > mu g (the step's velocity
// h (a - mu g) along the slope, none across it, no rotation) and sticking
// otherwise (no velocity, friction m a h); and against the contact laws
// row by row. A box sliding across the ground, its slip turned off the
// body force's direction (Coulomb's friction opposes the slip after the
// step). And a column of 20 such boxes, sideways force below the
// friction and the uplift threshold, from no impulse: statics, at rest.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dynamics/contact_interior.hpp"
#include "dynamics/contact_solver.hpp"
#include "box_column.hpp"

using namespace ashlar;
using namespace ashlar::test;

namespace {

// How far (m/s) row k breaks the contact laws (contact_solver.hpp) at the
// bodies' velocities; and whether its impulse is outside the cone.
double law_residual(const Column& c, const ContactRow& row, double impulse_tolerance) {
  const auto point_velocity = [&](int body, const Vec3& arm) {
    return Vec3(c.bodies.linear[body] + c.bodies.angular[body].cross(arm));
  };
  const Vec3 u = row.frame * (point_velocity(row.b, row.arm_b) - point_velocity(row.a, row.arm_a));
  const Vec3& p = row.impulse;
  if (p.x() < -impulse_tolerance || p.tail<2>().norm() > row.friction * p.x() + impulse_tolerance) return HUGE_VAL;
  const double normal = p.x() > 0.0 ? std::abs(u.x()) : std::max(0.0, -u.x());
  const Eigen::Vector2d slip = u.tail<2>();
  const double friction = p.tail<2>().norm();
  double tangential = slip.norm();
  if (friction >= row.friction * p.x() - impulse_tolerance && friction > 0.0) {
    tangential = (slip + slip.norm() * p.tail<2>() / friction).norm();  // slip opposite the friction
  }
  return std::max(normal, tangential);
}

// Impulses (N s) within impulse_tolerance of their cones count as in them.
double worst_law_residual(const Column& c, double impulse_tolerance) {
  double worst = 0.0;
  for (const ContactRow& row : c.rows) worst = std::max(worst, law_residual(c, row, impulse_tolerance));
  return worst;
}

}  // namespace

TEST(ContactInterior, ABoxOnAnInclineSlidesAtGTimesSinMinusMuCosAndSticksBelowTheFrictionAngle) {
  const double tolerance = 1e-10;  // m/s
  for (const double friction : {0.3, 0.8}) {
    const double sideways = 0.5 * kGravity;  // an incline of slope 0.5 (26.6 degrees)
    Column c = column(1, sideways, friction);
    std::vector<double> shift;
    const ContactInteriorReport report = solve_contact_interior(c.rows, c.bodies, tolerance, 30, shift);
    const bool slides = sideways > friction * kGravity;
    const Vec3 expected(slides ? kStep * (sideways - friction * kGravity) : 0.0, 0.0, 0.0);
    std::printf("box on a slope of 0.5, friction %.1f: %d iterations, residual %.3g m/s, velocity (%.9g, %.3g, %.3g) m/s "
                "(closed form %.9g), angular %.3g rad/s\n",
                friction, report.iterations, report.largest, c.bodies.linear[1].x(), c.bodies.linear[1].y(),
                c.bodies.linear[1].z(), expected.x(), c.bodies.angular[1].norm());
    EXPECT_LE(report.largest, tolerance);
    // The closed form, to the tolerance (m/s; rad/s times the half side).
    EXPECT_NEAR((c.bodies.linear[1] - expected).norm(), 0.0, 10.0 * tolerance);
    EXPECT_NEAR(c.bodies.angular[1].norm() * kSide, 0.0, 10.0 * tolerance);
    // The ground's impulse: the weight times the step, and the friction
    // mu N when sliding, m a h when sticking.
    Vec3 impulse = Vec3::Zero();
    for (const ContactRow& row : c.rows) impulse += row.frame.transpose() * row.impulse;
    const double weight = kMass * kGravity * kStep;
    // (to the tolerance's momentum, m times it, times 10)
    const double slack = 10.0 * kMass * tolerance;
    EXPECT_NEAR(impulse.z(), weight, slack);
    EXPECT_NEAR(-impulse.x(), slides ? friction * weight : kMass * sideways * kStep, slack);
    // The laws, row by row (the four corners share the load in no
    // particular way; each must keep them).
    EXPECT_LE(worst_law_residual(c, 1e-9 * weight), 10.0 * tolerance);
  }
}

TEST(ContactInterior, CarriesAColumnsWeightAndSidewaysForceToTheGroundThroughItsRedundantCorners) {
  // 20 blocks, 0.05 g sideways (below the friction, 0.6, and the column's
  // uplift threshold, 0.125 g): statics holds and nothing moves. From no
  // impulse at all (the sweeps alone take more than 1,000 sweeps).
  const int n = 20;
  const double sideways = 0.05 * kGravity;
  const double tolerance = 1e-11;  // m/s
  Column c = column(n, sideways, 0.6);
  std::vector<double> shift;
  const ContactInteriorReport report = solve_contact_interior(c.rows, c.bodies, tolerance, 30, shift);
  Vec3 impulse = Vec3::Zero();
  for (const ContactRow& row : c.rows) {
    if (row.a == 0) impulse += row.frame.transpose() * row.impulse;
  }
  double fastest = 0.0;
  for (int i = 1; i <= n; ++i) {
    fastest = std::max({fastest, c.bodies.linear[i].norm(), c.bodies.angular[i].norm() * kSide});
  }
  std::printf("column of %d: %d iterations, residual %.3g m/s, fastest point %.3g m/s, ground impulse (%.9g, %.3g, %.9g) N s\n",
              n, report.iterations, report.largest, fastest, impulse.x(), impulse.y(), impulse.z());
  EXPECT_LE(report.largest, tolerance);
  const double weight = n * kMass * kGravity * kStep;
  EXPECT_LE(worst_law_residual(c, 1e-9 * weight), 10.0 * tolerance);
  // Statics, and rest, to the tolerance (the per-joint error adds up
  // along the column: n^2 blocks' mass times it).
  const double slack = 10.0 * n * n * kMass * tolerance;
  EXPECT_NEAR(impulse.z(), weight, slack);
  EXPECT_NEAR(impulse.x(), -n * kMass * sideways * kStep, slack);
  EXPECT_NEAR(impulse.y(), 0.0, slack);
  EXPECT_LT(fastest, 10.0 * n * tolerance);
}

TEST(ContactInterior, ABoxSlidingAcrossTheGroundSlowsAlongItsSlipByMuGH) {
  // Free velocity (0.3, 0.1) m/s across the ground plus a sideways body
  // force along x: friction mu m g h opposes the slip after the step,
  // which keeps the free slip's direction when |v_free| > mu g h:
  // v = v_free (1 - mu g h / |v_free|). The slip's direction ties the
  // friction to the pressure: the fixed point's shift is not zero. (The
  // residual measures the friction's direction against the slip's, 0.3
  // m/s: 1e-8 m/s is a relative 3e-8.)
  const double tolerance = 1e-8;  // m/s
  const double friction = 0.6;
  Column c = column(1, 0.2 * kGravity, friction);
  c.bodies.linear[1] += Vec3(0.3, 0.1, 0.0);
  const Eigen::Vector2d slip = c.bodies.linear[1].head<2>();
  std::vector<double> shift;
  const ContactInteriorReport report = solve_contact_interior(c.rows, c.bodies, tolerance, 30, shift);
  const Eigen::Vector2d expected = slip * (1.0 - friction * kGravity * kStep / slip.norm());
  std::printf("box sliding: %d rounds, %d iterations, residual %.3g m/s, velocity (%.12g, %.12g, %.3g) m/s "
              "(closed form %.12g, %.12g)\n",
              report.fixed_point_iterations, report.iterations, report.largest, c.bodies.linear[1].x(),
              c.bodies.linear[1].y(), c.bodies.linear[1].z(), expected.x(), expected.y());
  EXPECT_TRUE(report.improved);
  EXPECT_GT(report.fixed_point_iterations, 1);
  EXPECT_LE(report.largest, tolerance);
  EXPECT_NEAR((c.bodies.linear[1].head<2>() - expected).norm(), 0.0, 10.0 * tolerance);
  EXPECT_NEAR(c.bodies.linear[1].z(), 0.0, 10.0 * tolerance);
  EXPECT_NEAR(c.bodies.angular[1].norm() * kSide, 0.0, 10.0 * tolerance);
  const double weight = kMass * kGravity * kStep;
  EXPECT_LE(worst_law_residual(c, 1e-9 * weight), 10.0 * tolerance);
}

TEST(ContactInterior, LeavesAStepThatKeepsTheLawsAsItCame) {
  Column c = column(3, 0.05 * kGravity, 0.6);
  const double tolerance = 1e-10;  // m/s
  std::vector<double> shift;
  ASSERT_TRUE(solve_contact_interior(c.rows, c.bodies, tolerance, 30, shift).improved);
  const Column solved = c;
  const ContactInteriorReport again = solve_contact_interior(c.rows, c.bodies, tolerance, 30, shift);
  EXPECT_EQ(again.iterations, 0);
  EXPECT_FALSE(again.improved);
  EXPECT_LE(again.largest, tolerance);
  for (size_t k = 0; k < c.rows.size(); ++k) EXPECT_TRUE(c.rows[k].impulse == solved.rows[k].impulse);
  for (int i = 0; i <= 3; ++i) EXPECT_TRUE(c.bodies.linear[i] == solved.bodies.linear[i]);
}

TEST(ContactInterior, LeavesAStepWithAFrictionlessRowAsItCame) {
  Column c = column(1, 0.0, 0.6);
  c.rows[0].friction = 0.0;
  const Column before = c;
  std::vector<double> shift;
  const ContactInteriorReport report = solve_contact_interior(c.rows, c.bodies, 1e-10, 30, shift);
  EXPECT_EQ(report.iterations, 0);
  EXPECT_FALSE(report.improved);
  EXPECT_TRUE(c.bodies.linear[1] == before.bodies.linear[1]);
}
