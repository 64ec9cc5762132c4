// Rigid-block dynamics (dynamics/simulation.hpp) against closed-form
// mechanics: free fall, a block at rest, sliding down an incline (and not
// below the friction angle), tipping, Housner's rocking threshold, a block
// wedged between walls with no floor, the inertia of a box, and the
// interrupt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "core/interrupt.hpp"
#include "dynamics/contact_points.hpp"
#include "dynamics/rigid_body.hpp"
#include "dynamics/simulation.hpp"
#include "structure/structure_transform.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// Block i's centroid at the last recorded frame minus where it started (m).
Vec3 travel(const SimulationResult& r, int i) {
  return r.poses.back()[i].position - r.poses.front()[i].position;
}

// Angle (rad) block i has turned through by the last frame.
double turned(const SimulationResult& r, int i) { return rotation_vector(r.poses.back()[i].rotation).norm(); }

// The largest angle (rad) block i turned through at any recorded frame.
double most_turned(const SimulationResult& r, int i) {
  double most = 0.0;
  for (const std::vector<RigidPose>& frame : r.poses) most = std::max(most, rotation_vector(frame[i].rotation).norm());
  return most;
}

// A 0.4 x 0.4 x 0.2 m block near the upper end of a 4 m slab, the whole
// tilted by `angle` about +y (the slab then falls towards +x).
Structure incline(double angle, const Vec3& block_size = {0.4, 0.4, 0.2}, double block_x = -1.5) {
  Structure s;
  s.add(box({4, 1, 0.2}, {0, 0, -0.1}), true, "slab");
  s.add(box(block_size, {block_x, 0, 0.5 * block_size.z()}), false, "block");
  return rotated(s, Vec3::UnitY(), angle, Vec3::Zero());
}

// The solver held to 1e-8 of g h (1e-10 m/s at the default step), so that
// "does not move" can be asserted near round-off.
SimulationOptions lasting(double duration, double friction) {
  SimulationOptions options;
  options.duration = duration;
  options.friction = friction;
  options.tolerance = 1e-8;
  return options;
}

}  // namespace

TEST(Dynamics, InertiaOfABoxIsTheClosedForm) {
  const Block b = make_box({1, 2, 3}, {5, -1, 2});
  const Mat3 inertia = inertia_tensor(b);
  const double m = b.mass();
  const Mat3 expected = (m / 12.0 * Vec3(4 + 9, 1 + 9, 1 + 4)).asDiagonal();
  EXPECT_LT((inertia - expected).norm(), 1e-9 * expected.norm());
}

TEST(Dynamics, FreeFallIsHalfGTSquared) {
  Structure s;
  s.add(box({1, 1, 1}, {0, 0, 10}));
  const SimulationResult r = simulate(s, lasting(1.0, 0.7));
  EXPECT_EQ(r.status, SimulationStatus::completed);
  EXPECT_EQ(r.steps, 1000);
  EXPECT_NEAR(travel(r, 0).z(), -0.5 * kGravity, 1e-9);
  EXPECT_TRUE(r.moved);
  EXPECT_FALSE(r.settled);
}

TEST(Dynamics, ABlockAtRestStaysAtRest) {
  Structure s;
  s.add(box({4, 4, 0.5}, {0, 0, -0.25}), true, "ground");
  s.add(box({1, 0.5, 0.4}, {0.3, 0.2, 0.2}), false, "block");
  s.add(box({0.6, 0.5, 0.4}, {0.5, 0.2, 0.6}), false, "on top");
  const SimulationResult r = simulate(s, lasting(1.0, 0.6));
  EXPECT_LT(r.max_displacement, 1e-9);
  EXPECT_FALSE(r.moved);
  EXPECT_TRUE(r.settled);
}

TEST(Dynamics, ABlockDroppedBouncesBackWithRestitutionOneAndStaysDownWithZero) {
  // Dropped flat from 0.5 m: with e = 1 it comes back up to its height (no
  // energy lost or gained at the impact), with e = 0 it stays on the ground.
  // Highest point after 0.4 s, lowest before.
  const auto highest_after_impact = [](double restitution) {
    Structure s;
    s.add(box({4, 4, 0.5}, {0, 0, -0.25}), true, "ground");
    s.add(box({0.5, 0.5, 0.3}, {0, 0, 0.65}), false, "block");
    // It falls 0.5 m in 0.319 s; bounced, it is up again at 0.64 s.
    SimulationOptions options = lasting(0.7, 0.7);
    options.restitution = restitution;
    options.record_every = 1;
    const SimulationResult r = simulate(s, options);
    double lowest = 1e9, highest_after = -1e9;
    for (size_t k = 0; k < r.times.size(); ++k) {
      const double z = r.poses[k][1].position.z();
      if (r.times[k] < 0.4) lowest = std::min(lowest, z);
      else highest_after = std::max(highest_after, z);
    }
    return std::make_pair(lowest, highest_after);
  };
  const auto [lowest_elastic, back_up] = highest_after_impact(1.0);
  const auto [lowest_plastic, after_plastic] = highest_after_impact(0.0);
  std::printf("dropped 0.5 m: e = 1 lands at z %.6f and comes back to %.6f (started at 0.65); e = 0 lands at "
              "%.6f, then reaches %.6f\n", lowest_elastic, back_up, lowest_plastic, after_plastic);
  EXPECT_NEAR(lowest_elastic, 0.15, 0.01);  // the gap closes to within a step's travel
  EXPECT_NEAR(back_up, 0.65, 1e-4);  // the drop height, to 0.02 % of the drop
  EXPECT_NEAR(lowest_plastic, 0.15, 0.01);
  // No bounce: the overlap of the landing step (under a step's travel) is
  // taken back by moving it up to the ground, with no speed.
  EXPECT_LT(after_plastic, 0.15 + 1e-9);
}

TEST(Dynamics, SlidesDownAnInclineHalfGSinMinusMuCosTSquared) {
  const double angle = 30.0 * kPi / 180.0, mu = 0.3;
  const SimulationResult r = simulate(incline(angle), lasting(1.0, mu));
  const double expected = 0.5 * kGravity * (std::sin(angle) - mu * std::cos(angle));  // t = 1 s
  const double distance = travel(r, 1).norm();
  std::printf("incline 30 deg, mu 0.3: slid %.6f m in 1 s, closed form %.6f m (%.3f %%)\n", distance, expected,
              100.0 * (distance / expected - 1.0));
  EXPECT_NEAR(distance, expected, 0.01 * expected);
  // Down the slope, along it.
  EXPECT_NEAR(travel(r, 1).normalized().dot(Vec3(std::cos(angle), 0, -std::sin(angle))), 1.0, 1e-6);
}

TEST(Dynamics, StaysOnAnInclineFlatterThanTheFrictionAngle) {
  const double mu = 0.5;  // friction angle atan(0.5) = 26.6 degrees
  const SimulationResult r = simulate(incline(25.0 * kPi / 180.0), lasting(1.0, mu));
  std::printf("incline 25 deg, mu 0.5: largest displacement %.3g m in 1 s\n", r.max_displacement);
  EXPECT_LT(r.max_displacement, 1e-6);
  EXPECT_FALSE(r.moved);
}

TEST(Dynamics, ATallBlockPastItsTippingAngleTopplesAndOneInsideStays) {
  // 0.2 m wide, 1 m tall: it tips about its downhill edge once tan(angle)
  // exceeds 0.2 (11.3 degrees); friction 1 keeps it from sliding.
  const Vec3 size{0.2, 0.4, 1.0};
  const SimulationResult past = simulate(incline(13.0 * kPi / 180.0, size, 0.0), lasting(1.5, 1.0));
  const SimulationResult inside = simulate(incline(9.5 * kPi / 180.0, size, 0.0), lasting(1.5, 1.0));
  std::printf("tall block at 13 deg: turned %.3f rad; at 9.5 deg: turned %.3g rad\n", turned(past, 1),
              turned(inside, 1));
  EXPECT_GT(turned(past, 1), 0.5);
  EXPECT_TRUE(past.moved);
  EXPECT_LT(turned(inside, 1), 1e-6);
  EXPECT_FALSE(inside.moved);
}

TEST(Dynamics, RocksOnlyAboveHousnersThresholdGBOverH) {
  // Block 0.3 m wide (x), 1.2 m tall: its base must accelerate sideways by
  // more than g b / h = g / 4 before it lifts off a corner (Housner 1963):
  // at 2 % below the threshold it stays, at 2 % above it lifts.
  const auto rocking = [](double fraction) {
    Structure s;
    s.add(box({3, 1, 0.2}, {0, 0, -0.1}), true, "base");
    s.add(box({0.3, 0.4, 1.2}, {0, 0, 0.6}), false, "block");
    SimulationOptions options = lasting(0.5, 0.8);
    const double amplitude = fraction * kGravity * 0.3 / 1.2;
    options.ground_acceleration = [amplitude](double t) { return Vec3(amplitude * std::sin(2 * kPi * 2 * t), 0, 0); };
    options.record_every = 1;
    return most_turned(simulate(s, options), 1);
  };
  const double below = rocking(0.98), above = rocking(1.02);
  std::printf("Housner: base at 0.98 g b/h turns the block at most %.3g rad, at 1.02 g b/h %.3g rad\n", below, above);
  EXPECT_LT(below, 1e-9);
  EXPECT_GT(above, 1e-6);  // 3.2e-5 rad: six orders above the round-off below
}

TEST(Dynamics, ABlockWedgedBetweenWallsWithNoFloorFallsWhateverTheFriction) {
  // Rigid-block equilibrium can hold it by friction on its sides with no
  // normal force pressing them; nothing presses them, so it falls freely.
  for (const double mu : {0.7, 10.0}) {
    Structure s;
    s.add(box({0.5, 1, 2}, {-0.45, 0, 1}), true, "left wall");
    s.add(box({0.5, 1, 2}, {0.45, 0, 1}), true, "right wall");
    s.add(box({0.4, 0.6, 0.4}, {0, 0, 1.5}), false, "wedged");
    const SimulationResult r = simulate(s, lasting(0.5, mu));
    std::printf("wedged block, mu %g: fell %.6f m in 0.5 s (free fall %.6f m)\n", mu, -travel(r, 2).z(),
                0.5 * kGravity * 0.25);
    EXPECT_NEAR(travel(r, 2).z(), -0.5 * kGravity * 0.25, 1e-6);
    EXPECT_TRUE(r.moved);
  }
}

// Two unit cubes meeting corner to corner along an edge, the upper one
// turned up about that edge by `opening` degrees (a hinge; beyond the
// detection's face angle, so the pair has no face contact): the pair's
// contact points.
std::vector<ContactPoint> hinge_points(double opening) {
  const Block lower = make_box({1, 1, 1}, {0.5, 0.5, 0.5});
  const Block upper = make_box({1, 1, 1}, {0.5, 0.5, 1.5}).rotated({0, 1, 0}, opening * kPi / 180.0, {1, 0, 1});
  const std::vector<const Block*> posed{&lower, &upper};
  std::vector<RigidPose> poses(2);
  poses[0].position = lower.centroid();
  poses[1].position = upper.centroid();
  return find_contact_points(posed, poses, {false, false}, {0, 1}, 0.01, std::acos(0.99));
}

TEST(Dynamics, AHingeBetweenTwoBlocksCarriesOneNormalNotAWedgeOfTwo) {
  // At 10 degrees the lower cube's two hinge corners press on the upper
  // cube's bottom face and the upper cube's two corners, at the same
  // places, are left out: both points have that face's normal. Kept, they
  // would add two points whose normal is 10 degrees from it, a wedge that
  // friction locks (tan 5 degrees < 0.7).
  const std::vector<ContactPoint> hinge = hinge_points(10.0);
  const Vec3 bottom = Eigen::AngleAxisd(10.0 * kPi / 180.0, Vec3::UnitY()) * Vec3(0, 0, -1);
  ASSERT_EQ(hinge.size(), 2u);
  for (const ContactPoint& c : hinge) {
    EXPECT_EQ(c.a, 0);
    EXPECT_EQ(c.b, 1);
    EXPECT_NEAR((c.normal - bottom).norm(), 0.0, 1e-12);
    EXPECT_NEAR(c.point.x(), 0.5, 1e-12);  // the corners on the edge x = 1, z = 1
    EXPECT_NEAR(c.point.z(), 0.5, 1e-12);
  }
  // At 60 degrees the faces are no hinge's sides: each cube's corners make
  // points against the other's face, two normals 60 degrees apart.
  const std::vector<ContactPoint> corner = hinge_points(60.0);
  ASSERT_EQ(corner.size(), 4u);
  EXPECT_EQ(std::count_if(corner.begin(), corner.end(), [](const ContactPoint& c) { return c.a == 0; }), 2);
}

TEST(Dynamics, ACornerAtTheEdgeOfAnotherBlockPressesTheFaceTurnedTowardsIt) {
  // A unit cube leaning back 10 degrees from the end face x = 1 of another,
  // its two bottom corners on that face's lower edge and 0.02 mm into the
  // other cube. Those corners lie on the other's bottom plane too, where
  // they are least deep (0 against 2e-5 m), but that face is turned away
  // from the leaning cube: they press the end face, which is turned
  // towards it (before, the bottom face: the two cubes pushed apart along
  // z, and a corner so placed on an arch's extrados made the neighbours
  // push each other both ways).
  const Block leaning =
      make_box({1, 1, 1}, {0.5 + 2e-5, 0.5, 0.5}).rotated({0, 1, 0}, -10.0 * kPi / 180.0, {1 + 2e-5, 0, 0});
  const Block other = make_box({1, 1, 1}, {1.5, 0.5, 0.5});
  const std::vector<const Block*> posed{&leaning, &other};
  std::vector<RigidPose> poses(2);
  poses[0].position = leaning.centroid();
  poses[1].position = other.centroid();
  const std::vector<ContactPoint> points =
      find_contact_points(posed, poses, {false, false}, {0, 1}, 0.01, std::acos(0.99));
  ASSERT_EQ(points.size(), 2u);  // the other's two corners there: the same hinge
  for (const ContactPoint& c : points) {
    EXPECT_EQ(c.a, 0);
    EXPECT_NEAR((c.normal - Vec3(-1, 0, 0)).norm(), 0.0, 1e-12);
  }
}

TEST(Dynamics, AnInterruptedRunKeepsWhatItComputedAndGivesNoVerdict) {
  Structure s;
  s.add(box({1, 1, 1}, {0, 0, 10}));
  SimulationOptions options = lasting(1.0, 0.7);
  options.progress = [](double t) {
    if (t >= 0.0995) interrupt_requested() = true;
  };
  const SimulationResult r = simulate(s, options);
  interrupt_requested() = false;
  EXPECT_EQ(r.status, SimulationStatus::interrupted);
  EXPECT_EQ(r.steps, 100);
  EXPECT_FALSE(r.moved);
  EXPECT_NEAR(r.times.back(), 0.1, 1e-12);
}

TEST(Dynamics, BadOptionsNameTheOptionAndTheValue) {
  Structure s;
  s.add(box({1, 1, 1}, {0, 0, 0.5}));
  SimulationOptions options;
  options.step = -1;
  EXPECT_EQ(error_of([&] { simulate(s, options); }), "simulate: step must be a time > 0 (s), got -1");
  options = {};
  options.restitution = 2;
  EXPECT_EQ(error_of([&] { simulate(s, options); }), "simulate: restitution must be in [0, 1], got 2");
}
