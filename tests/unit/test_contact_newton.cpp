// The semismooth Newton method of dynamics/contact_newton.hpp on one step
// of a box standing on the ground by its four corners (three independent:
// the rows are redundant), under gravity and a horizontal body force a
// (the ground an incline of slope a / g): against the closed forms of a
// block on an incline, sliding when a > mu g (the step's velocity
// h (a - mu g) along the slope, none across it, no rotation) and sticking
// otherwise (no velocity, friction m a h); and against the contact laws
// row by row. And a column of 20 such boxes, sideways force below the
// friction and the uplift threshold, from no impulse: statics, at rest.
// And 300 boxes side by side (1,200 rows): solved 200 rows a call.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "dynamics/contact_newton.hpp"
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

TEST(ContactNewton, ABoxOnAnInclineSlidesAtGTimesSinMinusMuCosAndSticksBelowTheFrictionAngle) {
  const double tolerance = 1e-12;  // m/s
  for (const double friction : {0.3, 0.8}) {
    const double sideways = 0.5 * kGravity;  // an incline of slope 0.5 (26.6 degrees)
    Column c = column(1, sideways, friction);
    const ContactNewtonReport report = solve_contact_newton(c.rows, c.bodies, tolerance, 30);
    const bool slides = sideways > friction * kGravity;
    const Vec3 expected(slides ? kStep * (sideways - friction * kGravity) : 0.0, 0.0, 0.0);
    std::printf("box on a slope of 0.5, friction %.1f: %d iterations, |F| %.3g m/s, velocity (%.9g, %.3g, %.3g) m/s "
                "(closed form %.9g), angular %.3g rad/s\n",
                friction, report.iterations, report.largest, c.bodies.linear[1].x(), c.bodies.linear[1].y(),
                c.bodies.linear[1].z(), expected.x(), c.bodies.angular[1].norm());
    EXPECT_LE(report.largest, tolerance);
    EXPECT_LE(report.iterations, 30);
    // The closed form, to the tolerance (m/s; rad/s times the half side).
    EXPECT_NEAR((c.bodies.linear[1] - expected).norm(), 0.0, 10.0 * tolerance);
    EXPECT_NEAR(c.bodies.angular[1].norm() * kSide, 0.0, 10.0 * tolerance);
    // The ground's impulse: the weight times the step, and the friction
    // mu N when sliding, m a h when sticking.
    Vec3 impulse = Vec3::Zero();
    for (const ContactRow& row : c.rows) impulse += row.frame.transpose() * row.impulse;
    const double weight = kMass * kGravity * kStep;
    EXPECT_NEAR(impulse.z(), weight, 1e-9 * weight);
    EXPECT_NEAR(-impulse.x(), slides ? friction * weight : kMass * sideways * kStep, 1e-9 * weight);
    // The laws, row by row (the four corners share the load in no
    // particular way; each must keep them).
    EXPECT_LE(worst_law_residual(c, 1e-9 * weight), 10.0 * tolerance);
  }
}

TEST(ContactNewton, CarriesAColumnsWeightAndSidewaysForceToTheGroundThroughItsRedundantCorners) {
  // 20 blocks, 0.05 g sideways (below the friction, 0.6, and the column's
  // uplift threshold, 0.125 g): statics holds and nothing moves. From no
  // impulse at all (the sweeps alone take more than 1,000 sweeps).
  const int n = 20;
  const double sideways = 0.05 * kGravity;
  const double tolerance = 1e-11;  // m/s
  Column c = column(n, sideways, 0.6);
  const ContactNewtonReport report = solve_contact_newton(c.rows, c.bodies, tolerance, 300);
  Vec3 impulse = Vec3::Zero();
  for (const ContactRow& row : c.rows) {
    if (row.a == 0) impulse += row.frame.transpose() * row.impulse;
  }
  double fastest = 0.0;
  for (int i = 1; i <= n; ++i) {
    fastest = std::max({fastest, c.bodies.linear[i].norm(), c.bodies.angular[i].norm() * kSide});
  }
  std::printf("column of %d: %d iterations, |F| %.3g m/s, fastest point %.3g m/s, ground impulse (%.9g, %.3g, %.9g) N s\n",
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

TEST(ContactNewton, SolvesAStepOfMoreThanAThousandRowsOnTheRowsThatBreakTheLawsTwoHundredAtATime) {
  // 300 boxes side by side on the ground (1,200 rows, four corners each),
  // 0.1 g sideways (below the friction, 0.6): each box alone is statics.
  // Past 1,000 rows a call solves the rows above the tolerance with the
  // other rows of their boxes, 200 rows at most, the rest held: 50 boxes
  // a call come to rest, the others keep their free velocities and no
  // impulse, and six calls bring all 300 to rest.
  const int boxes = 300;
  const double sideways = 0.1 * kGravity;
  const double tolerance = 1e-11;  // m/s
  Column c;
  const Column one = column(1, sideways, 0.6);
  c.bodies.linear.assign(boxes + 1, one.bodies.linear[1]);
  c.bodies.angular.assign(boxes + 1, Vec3::Zero());
  c.bodies.inverse_mass.assign(boxes + 1, one.bodies.inverse_mass[1]);
  c.bodies.inverse_inertia.assign(boxes + 1, one.bodies.inverse_inertia[1]);
  c.bodies.linear[0].setZero();
  c.bodies.inverse_mass[0] = 0.0;
  c.bodies.inverse_inertia[0] = Mat3::Zero();
  for (int i = 1; i <= boxes; ++i) {
    for (ContactRow row : one.rows) {
      row.b = i;  // the arms are relative to the centroids: the same for every box
      c.rows.push_back(row);
    }
  }
  const Vec3 free_velocity = one.bodies.linear[1];
  const double weight = kMass * kGravity * kStep;
  const auto at_rest = [&](int i) {
    return c.bodies.linear[i].norm() < 10.0 * tolerance && c.bodies.angular[i].norm() * kSide < 10.0 * tolerance;
  };
  for (int call = 1; call <= 6; ++call) {
    const ContactNewtonReport report = solve_contact_newton(c.rows, c.bodies, tolerance, 30);
    EXPECT_GT(report.iterations, 0);
    EXPECT_LE(report.largest, tolerance);
    int resting = 0;
    for (int i = 1; i <= boxes; ++i) {
      Vec3 impulse = Vec3::Zero();
      for (int k = 4 * (i - 1); k < 4 * i; ++k) impulse += c.rows[k].frame.transpose() * c.rows[k].impulse;
      if (at_rest(i)) {
        ++resting;
        EXPECT_NEAR(impulse.z(), weight, 1e-9 * weight);
        EXPECT_NEAR(impulse.x(), -kMass * sideways * kStep, 1e-9 * weight);
      } else {
        // Held: untouched.
        EXPECT_TRUE(c.bodies.linear[i] == free_velocity) << "box " << i;
        EXPECT_TRUE(impulse.isZero(0.0)) << "box " << i;
      }
    }
    EXPECT_EQ(resting, 50 * call) << "after call " << call;
  }
  // Nothing left above the tolerance: a call does nothing.
  EXPECT_EQ(solve_contact_newton(c.rows, c.bodies, tolerance, 30).iterations, 0);
}
