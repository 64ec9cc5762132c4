// A turning ground (SimulationOptions::ground_rotation) against closed-form
// mechanics in the ground's frame: a block on a support tilted slowly
// starts to slide at the friction angle, a slender block lifts off at
// atan(b / h), a block on a spinning support slides outward once
// omega^2 r > mu g, a free block stays still in the world however the
// ground turns; and a ground that does not turn changes nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "dynamics/rigid_body.hpp"
#include "dynamics/simulation.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// The solver held to 1e-8 of g h, so that "does not move" can be asserted
// near round-off; every step recorded.
SimulationOptions recorded_run(double duration, double friction) {
  SimulationOptions options;
  options.duration = duration;
  options.friction = friction;
  options.tolerance = 1e-8;
  options.record_every = 1;
  return options;
}

// The first recorded time (s) at which `measure` of frame k exceeds
// `threshold`; -1 when it never does.
template <class Measure>
double first_time_above(const SimulationResult& r, double threshold, Measure measure) {
  for (size_t k = 0; k < r.times.size(); ++k) {
    if (measure(k) > threshold) return r.times[k];
  }
  return -1.0;
}

// The root of an increasing f on [lo, hi] by bisection.
template <class F>
double root(F f, double lo, double hi) {
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

TEST(GroundRotation, ABlockOnASlowlyTiltedSupportSlidesAtTheFrictionAngle) {
  // The ground tilts about +y at 0.1 rad/s through the block's base
  // centre; with mu 0.5 the block holds until tan(theta) = mu, at
  // t* = atan(mu) / rate = 4.636 s, then slides down +x:
  //   x'' = g (sin(rate t) - mu cos(rate t)), x(t*) = x'(t*) = 0,
  // whose solution x(t) (below) is the closed form for the first movement.
  // Left out of it: the frame's centrifugal and Coriolis forces, 1e-4 g at
  // this rate, which move t* by about 0.5 ms; but Coriolis', 2 omega x',
  // lifts the sliding block (0.03 m/s^2 at 0.17 m/s), so its travel is
  // checked against the frame's equation of motion along the slope with
  // them (the centroid z_c = 0.1 m above the pivot, r = (x, 0, z_c)):
  //   x'' = g sin(theta) + omega^2 x - mu (g cos(theta) - omega^2 z_c - 2 omega x'),
  // integrated by RK4 (0.1 ms steps) from the slip, where x'' first
  // reaches 0.
  const double rate = 0.1, mu = 0.5, g = kGravity;
  Structure s;
  s.add(box({4, 1, 0.2}, {0, 0, -0.1}), true, "ground");
  s.add(box({0.4, 0.4, 0.2}, {0, 0, 0.1}), false, "block");
  SimulationOptions options = recorded_run(5.2, mu);
  options.ground_rotation = [rate](double t) { return Vec3(0, rate * t, 0); };
  const SimulationResult r = simulate(s, options);

  const double slip = std::atan(mu) / rate;
  const auto slid = [&](double t) {
    const double w = rate, a = w * slip, b = w * t;
    return g * ((std::sin(a) - std::sin(b)) / (w * w) + mu * (std::cos(b) - std::cos(a)) / (w * w) +
                (std::cos(a) + mu * std::sin(a)) * (t - slip) / w);
  };
  const auto moved = [&](size_t k) { return r.poses[k][1].position.x() - r.poses[0][1].position.x(); };
  // Stays put below the friction angle (up to theta* - 0.005 rad).
  double before = 0.0;
  for (size_t k = 0; k < r.times.size() && r.times[k] <= slip - 0.05; ++k) {
    before = std::max(before, (r.poses[k][1].position - r.poses[0][1].position).norm());
  }
  // First movement: the block 10 um down the slope.
  const double threshold = 1e-5;
  const double first = first_time_above(r, threshold, moved);
  const double expected = root([&](double t) { return slid(t) - threshold; }, slip, slip + 1.0);
  const double end = r.times.back(), travelled = moved(r.times.size() - 1);
  const double height = 0.1;
  const auto acceleration = [&](double t, double x, double v) {
    const double theta = rate * t;
    return g * std::sin(theta) + rate * rate * x - mu * (g * std::cos(theta) - rate * rate * height - 2 * rate * v);
  };
  double t = root([&](double t) { return acceleration(t, 0, 0); }, 0.0, 2 * slip), x = 0, v = 0;
  for (const double dt = 1e-4; t < end;) {
    const double h = std::min(dt, end - t);
    const double a1 = acceleration(t, x, v), a2 = acceleration(t + h / 2, x + h / 2 * v, v + h / 2 * a1);
    const double a3 = acceleration(t + h / 2, x + h / 2 * (v + h / 2 * a1), v + h / 2 * a2);
    const double a4 = acceleration(t + h, x + h * (v + h / 2 * a2), v + h * a3);
    x += h * v + h * h / 6 * (a1 + a2 + a3);
    v += h / 6 * (a1 + 2 * a2 + 2 * a3 + a4);
    t += h;
  }
  std::printf("tilting at 0.1 rad/s, mu 0.5: moved %.3g m before t* - 0.05 s; 10 um at %.4f s (closed form %.4f s, "
              "t* %.4f s); %.6f m at %.1f s (with the frame's forces %.6f m, without %.6f m)\n",
              before, first, expected, slip, travelled, end, x, slid(end));
  EXPECT_LT(before, 1e-9);
  EXPECT_NEAR(first, expected, 3e-3);
  EXPECT_NEAR(travelled, x, 1e-3 * x);
}

TEST(GroundRotation, ASlenderBlockOnASlowlyTiltedSupportLiftsOffAtAtanBOverH) {
  // 0.1 m wide (x), 0.5 m tall, friction 0.8 (no sliding): it lifts off its
  // downhill edge when theta = atan(b / h) = 0.1974 rad, at t* = 3.948 s at
  // 0.05 rad/s. Past it, rocking about the edge linearised,
  //   phi'' = p^2 (phi + theta - atan(b / h)), p^2 = 3 g / (4 R),
  // R the half-diagonal, so phi = rate (sinh(p tau) / p - tau), tau = t - t*.
  const double rate = 0.05, b = 0.1, h = 0.5, g = kGravity;
  Structure s;
  s.add(box({3, 1, 0.2}, {0, 0, -0.1}), true, "ground");
  s.add(box({b, 0.4, h}, {0, 0, 0.5 * h}), false, "block");
  SimulationOptions options = recorded_run(4.2, 0.8);
  options.ground_rotation = [rate](double t) { return Vec3(0, rate * t, 0); };
  const SimulationResult r = simulate(s, options);

  const double lift = std::atan(b / h) / rate;
  const double p = std::sqrt(3.0 * g / (4.0 * 0.5 * std::hypot(b, h)));
  const auto rocked = [&](double tau) { return rate * (std::sinh(p * tau) / p - tau); };
  const auto turned = [&](size_t k) { return rotation_vector(r.poses[k][1].rotation).norm(); };
  double before = 0.0;
  for (size_t k = 0; k < r.times.size() && r.times[k] <= lift - 0.1; ++k) before = std::max(before, turned(k));
  const double threshold = 1e-4;  // rad
  const double first = first_time_above(r, threshold, turned);
  const double expected = lift + root([&](double tau) { return rocked(tau) - threshold; }, 0.0, 1.0);
  const double end = r.times.back(), last = turned(r.times.size() - 1);
  std::printf("slender block, b/h 0.2, tilting at 0.05 rad/s: turned %.3g rad before t* - 0.1 s; 1e-4 rad at %.4f s "
              "(closed form %.4f s, t* %.4f s); %.6f rad at %.1f s (closed form %.6f rad)\n",
              before, first, expected, lift, last, end, rocked(end - lift));
  EXPECT_LT(before, 1e-8);
  EXPECT_NEAR(first, expected, 5e-3);
  EXPECT_NEAR(last, rocked(end - lift), 0.01 * rocked(end - lift));
}

TEST(GroundRotation, ABlockOnASpinningSupportSlidesOutwardOnceOmegaSquaredRExceedsMuG) {
  // The ground spins about z at a constant rate omega; a block with its
  // centroid 1 m from the axis holds while omega^2 r < mu g. Above, its
  // radial slide is x'' = omega^2 (r + x) - mu g (Coriolis' force turns its
  // velocity by about 2 v / (omega r) = 0.05 rad, which changes x by
  // 0.1 %): x(t) = (omega^2 r - mu g) / omega^2 (cosh(omega t) - 1).
  const double mu = 0.2, radius = 1.0, g = kGravity;
  const double critical = std::sqrt(mu * g / radius);
  const auto spin = [&](double omega, double duration) {
    Structure s;
    s.add(box({4, 4, 0.2}, {0, 0, -0.1}), true, "ground");
    s.add(box({0.2, 0.2, 0.1}, {radius, 0, 0.05}), false, "block");
    SimulationOptions options = recorded_run(duration, mu);
    options.ground_rotation = [omega](double t) { return Vec3(0, 0, omega * t); };
    return simulate(s, options);
  };
  const SimulationResult below = spin(0.95 * critical, 1.0);
  const double omega = 1.05 * critical, t = 0.2;
  const SimulationResult above = spin(omega, t);
  const Vec3 travel = above.poses.back()[1].position - above.poses.front()[1].position;
  const double expected = (omega * omega * radius - mu * g) / (omega * omega) * (std::cosh(omega * t) - 1.0);
  std::printf("spinning ground, mu 0.2, r 1 m: at 0.95 omega_c moved %.3g m in 1 s; at 1.05 omega_c %.6f m outward "
              "in 0.2 s (closed form %.6f m), %.6f m sideways\n",
              below.max_displacement, travel.x(), expected, travel.y());
  EXPECT_LT(below.max_displacement, 1e-9);
  EXPECT_FALSE(below.moved);
  EXPECT_NEAR(travel.x(), expected, 0.01 * expected);
  EXPECT_LT(std::abs(travel.y()), 0.1 * travel.x());
}

TEST(GroundRotation, AFreeBlockStaysStillInTheWorldWhileTheGroundTurnsUnderIt) {
  // No gravity, no contact: the block does not move in the world, so in the
  // ground's frame its centroid is p + R(t)^T (c0 - p) and its rotation
  // R(t)^T, whatever R(t) does. With a ground turning about all three axes
  // at once (theta'(0) = 0, so the block starts still in the world too)
  // and a block of three different moments of inertia off the pivot, this
  // holds only if every force and moment of the frame (gravity aside) is
  // right: Euler's, centrifugal, Coriolis' (the block turns relative to the
  // ground at -omega) and their moments. The frame's forces are taken at
  // the step's start velocities, so the error is first-order in h: it must
  // halve with the step (a wrong term would leave an error that does not).
  Structure s;
  s.add(box({0.5, 0.3, 0.1}, {0.7, -0.4, 0.3}), false, "block");
  const Vec3 pivot(0.1, 0.2, -0.3), start = s.block(0).centroid();
  const auto theta = [](double t) { return Vec3(0.4 * t * t, -0.3 * t * t * t, 0.25 * t * t + 0.1 * t * t * t); };
  // The largest distance (m) and angle (rad) from the world's stillness
  // over a run of 1 s with steps of h.
  const auto errors = [&](double h) {
    SimulationOptions options = recorded_run(1.0, 0.5);
    options.step = h;
    options.gravity = Vec3::Zero();
    options.ground_pivot = pivot;
    options.ground_rotation = theta;
    const SimulationResult r = simulate(s, options);
    double position = 0.0, rotation = 0.0;
    for (size_t k = 0; k < r.times.size(); ++k) {
      const Quat turned = quaternion_from_rotation_vector(theta(r.times[k]));
      position = std::max(position, (r.poses[k][0].position - (pivot + turned.conjugate() * (start - pivot))).norm());
      rotation = std::max(rotation, rotation_vector(turned * r.poses[k][0].rotation).norm());
    }
    return std::pair{position, rotation};
  };
  const auto [position, rotation] = errors(1e-3);
  const auto [position_half, rotation_half] = errors(5e-4);
  std::printf("free block under a ground turning %.3f rad in 1 s: centroid within %.3g m (%.3g at h / 2), rotation "
              "within %.3g rad (%.3g at h / 2) of the world's stillness\n",
              theta(1.0).norm(), position, position_half, rotation, rotation_half);
  EXPECT_LT(position, 5e-5);
  EXPECT_LT(rotation, 5e-5);
  EXPECT_NEAR(position / position_half, 2.0, 0.1);
  EXPECT_NEAR(rotation / rotation_half, 2.0, 0.1);
}

TEST(GroundRotation, AGroundThatDoesNotTurnChangesNothingToTheBit) {
  // A tall block rocked by a ground shake above Housner's threshold, with
  // and without a ground_rotation that stays zero.
  Structure s;
  s.add(box({3, 1, 0.2}, {0, 0, -0.1}), true, "base");
  s.add(box({0.3, 0.4, 1.2}, {0, 0, 0.6}), false, "block");
  SimulationOptions options = recorded_run(0.3, 0.8);
  options.ground_acceleration = [](double t) { return Vec3(0.5 * kGravity * std::sin(2 * kPi * 2 * t), 0, 0); };
  const SimulationResult still = simulate(s, options);
  options.ground_rotation = [](double) { return Vec3::Zero(); };
  options.ground_pivot = Vec3(2, -1, 3);
  const SimulationResult turning = simulate(s, options);
  ASSERT_EQ(still.poses.size(), turning.poses.size());
  EXPECT_GT(still.max_displacement, 1e-3);  // it does move
  for (size_t k = 0; k < still.poses.size(); ++k) {
    EXPECT_EQ(still.poses[k][1].position, turning.poses[k][1].position) << "frame " << k;
    EXPECT_EQ(still.poses[k][1].rotation.coeffs(), turning.poses[k][1].rotation.coeffs()) << "frame " << k;
  }
}

TEST(GroundRotation, BadRotationsAndPivotsNameTheOptionAndTheValue) {
  Structure s;
  s.add(box({3, 1, 0.2}, {0, 0, -0.1}), true, "base");
  s.add(box({0.3, 0.4, 0.3}, {0, 0, 0.15}), false, "block");
  SimulationOptions options = recorded_run(0.01, 0.8);
  options.ground_pivot = Vec3(0, std::nan(""), 0);
  EXPECT_TRUE(contains(error_of([&] { simulate(s, options); }), "ground_pivot must be a finite point (m), got nan"));
  options.ground_pivot = Vec3::Zero();
  options.ground_rotation = [](double t) { return Vec3(t > 0.005 ? INFINITY : 0.0, 0, 0); };
  EXPECT_TRUE(contains(error_of([&] { simulate(s, options); }), "ground_rotation at t = 0.006 s is not finite: (inf, 0, 0)"));
}
