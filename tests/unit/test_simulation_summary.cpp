// The engineer's summary of a simulation against closed forms: a block
// sliding down an incline (displacement 1/2 g (sin - mu cos) t^2, its
// drift, when it starts), a block in free fall (when it has fallen by the
// criterion's drop, sqrt(2 d / g)), a slender block rocking under a ramp of
// ground acceleration (when it first moves: Housner's uplift, a_g = g b / h,
// then the linearised rocking solution until a vertex has moved the
// threshold).
#include <gtest/gtest.h>

#include <cmath>

#include "dynamics/simulation_summary.hpp"
#include "structure/structure_transform.hpp"
#include "test_support.hpp"

using namespace ashlar;

TEST(SimulationSummary, SlidingBlockMatchesHalfGSinMinusMuCosTSquared) {
  const double angle = 30.0 * kPi / 180.0, mu = 0.3, duration = 0.5;
  Structure flat;
  flat.add(box({4, 1, 0.2}, {0, 0, -0.1}), true, "slab");
  flat.add(box({0.4, 0.4, 0.2}, {-1.5, 0, 0.1}), false, "block");
  const Structure s = rotated(flat, Vec3::UnitY(), angle, Vec3::Zero());
  SimulationOptions options;
  options.duration = duration;
  options.friction = mu;
  options.tolerance = 1e-8;
  options.record_every = 1;
  const SimulationResult r = simulate(s, options);
  const SimulationSummary summary = summarize(s, r, {});
  const double a = kGravity * (std::sin(angle) - mu * std::cos(angle));
  const double expected = 0.5 * a * duration * duration;
  std::printf("sliding: residual %.6f m, closed form %.6f m\n", summary.residual, expected);
  EXPECT_NEAR(summary.residual, expected, 0.01 * expected);
  EXPECT_NEAR(summary.residual_displacement[1], summary.residual, 0.0);
  EXPECT_EQ(summary.residual_block, 1);
  EXPECT_NEAR(summary.peak, summary.residual, 1e-12);  // it only ever goes further
  EXPECT_EQ(summary.residual_displacement[0], 0.0);    // the support
  // Moved once a vertex went 1e-3 of the diagonal: 1/2 a t^2 = that.
  const double diagonal = s.block(1).bounds().diagonal();
  const double start = std::sqrt(2e-3 * diagonal / a);
  ASSERT_TRUE(summary.first_movement);
  std::printf("sliding: first movement %.4f s, closed form %.4f s\n", *summary.first_movement, start);
  EXPECT_NEAR(*summary.first_movement, start, 0.02 * start + options.step);
  EXPECT_FALSE(summary.collapse_time);
  EXPECT_TRUE(summary.fallen.empty());
  // Drift: the slope's horizontal part of the slide over the centroid's
  // height above the block's lowest vertex (the base of the free blocks).
  const Drift d = drift(s, r, {1});
  double lowest = 1e9;
  for (const Vec3& p : s.block(1).vertices()) lowest = std::min(lowest, p.z());
  EXPECT_NEAR(d.height, s.block(1).centroid().z() - lowest, 1e-12);
  EXPECT_NEAR(d.residual, expected * std::cos(angle) / d.height, 0.01 * d.residual);
  EXPECT_EQ(d.values.size(), r.times.size());
  EXPECT_EQ(error_of([&] { drift(s, r, {0}); }), "drift: block 1 is a support, which does not move");
}

TEST(SimulationSummary, FreeFallCollapsesWhenTheDropReachesTheCriterion) {
  Structure s;
  s.add(box({0.4, 0.4, 0.2}, {0, 0, 5}), false, "falling");
  s.add(box({0.4, 0.4, 0.2}, {3, 0, 0.1}), false, "resting");
  s.add(box({5, 1, 0.2}, {2, 0, -0.1}), true, "floor");
  SimulationOptions options;
  options.duration = 0.4;
  options.record_every = 1;
  const SimulationResult r = simulate(s, options);
  // Dropped by half its smallest extent (0.2 m): 0.1 m, after sqrt(2 d / g).
  const SimulationSummary summary = summarize(s, r, {});
  ASSERT_EQ(summary.fallen, std::vector<int>{0});
  ASSERT_TRUE(summary.collapse_time);
  const double expected = std::sqrt(2 * 0.1 / kGravity);
  std::printf("free fall: collapse at %.4f s, closed form %.4f s\n", *summary.collapse_time, expected);
  EXPECT_NEAR(*summary.collapse_time, expected, options.step);
  EXPECT_EQ(summary.fall_times.size(), 1u);
  // Below a level: 4.5 m, half a metre down.
  SummaryOptions level;
  level.fall_level = 4.5;
  level.fall_fraction = 100;  // only the level counts
  const SimulationSummary below = summarize(s, r, level);
  ASSERT_TRUE(below.collapse_time);
  EXPECT_NEAR(*below.collapse_time, std::sqrt(2 * 0.5 / kGravity), options.step);
  EXPECT_EQ(below.fallen, std::vector<int>{0});  // the resting block started below the level
  EXPECT_EQ(error_of([&] {
              SummaryOptions o;
              o.fall_fraction = 0;
              summarize(s, r, o);
            }),
            "simulation summary: fall_fraction must be > 0, got 0");
}

TEST(SimulationSummary, RockingBlockFirstMovesAfterHousnersUpliftAsTheLinearisedSolutionSays) {
  // Block 0.3 m wide (x), 1.2 m tall, ground acceleration a_g = k t along x:
  // it lifts off an edge at t_u = g (b / h) / k (Housner 1963). Then, rocking
  // about that edge, the linearised equation theta'' = p^2 (theta + (k / g) tau)
  // (tau = t - t_u, p^2 = 3 g / (4 R)) gives theta = (k / g) (sinh(p tau) / p - tau)
  // from rest; the farthest vertex (the top edge's far end, 2 R... from the
  // pivot edge in the x-z plane) has moved theta times its distance.
  const double width = 0.3, height = 1.2, depth = 0.4, k = 20.0;
  Structure s;
  s.add(box({3, 1, 0.2}, {0, 0, -0.1}), true, "base");
  s.add(box({width, depth, height}, {0, 0, height / 2}), false, "block");
  SimulationOptions options;
  options.duration = 0.3;
  options.friction = 0.8;
  options.tolerance = 1e-8;
  options.record_every = 1;
  options.ground_acceleration = [k](double t) { return Vec3(k * t, 0, 0); };
  const SimulationResult r = simulate(s, options);
  SummaryOptions o;
  o.moved_fraction = 1e-4;
  const SimulationSummary summary = summarize(s, r, o);
  const double R = 0.5 * std::hypot(width, height), p = std::sqrt(3 * kGravity / (4 * R));
  const double uplift = kGravity * (width / height) / k;
  const double reach = 2 * R;  // pivot edge to the opposite top edge
  const double threshold = o.moved_fraction * s.block(1).bounds().diagonal();
  double lo = 0, hi = 1;
  for (int it = 0; it < 100; ++it) {
    const double tau = 0.5 * (lo + hi);
    ((k / kGravity) * (std::sinh(p * tau) / p - tau) * reach > threshold ? hi : lo) = tau;
  }
  const double expected = uplift + hi;
  ASSERT_TRUE(summary.first_movement);
  std::printf("rocking: first movement %.4f s, closed form %.4f s (uplift at %.4f s)\n", *summary.first_movement,
              expected, uplift);
  EXPECT_NEAR(*summary.first_movement, expected, 2 * options.step);
}
