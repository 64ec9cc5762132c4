// Load traces (Shin 2014, "Force flow", figure 10): the force direction
// against the QP's own point loads, determinism, and where the weight of an
// H frame's beam goes.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/force_flow.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// Two posts of two 0.4 x 0.4 x 0.5 blocks on a ground slab, centred on
// x = -1 and x = +1, and a 0.4 x 0.4 beam on top from x = beam_from to
// x = beam_to (the thesis's figure 10). Blocks: posts 0-3, beam 4, ground 5.
Structure frame(double beam_from, double beam_to) {
  Structure s;
  for (double x : {-1.0, 1.0}) {
    s.add(box({0.4, 0.4, 0.5}, {x, 0, 0.25}));
    s.add(box({0.4, 0.4, 0.5}, {x, 0, 0.75}));
  }
  s.add(box({beam_to - beam_from, 0.4, 0.4}, {(beam_from + beam_to) / 2, 0, 1.2}), false, "beam");
  s.add(box({4, 1, 0.2}, {0, 0, -0.1}), true, "ground");
  return s;
}

constexpr int kBeam = 4;

// The share of the traces that reached the ground under the post at x.
double share_under(const Structure& s, const ForceFlow& flow, double x) {
  double share = 0.0;
  for (const SupportShare& arrived : flow.shares) {
    if (std::abs((*s.interfaces())[arrived.interface].center.x() - x) < 0.3) share += arrived.share;
  }
  return share;
}

// Every trace ends on a support interface: in its plane, within its extent.
void expect_all_reach_the_ground(const Structure& s, const ForceFlow& flow) {
  ASSERT_TRUE(flow.valid);
  EXPECT_EQ(flow.lost, 0);
  double total = 0.0;
  for (const SupportShare& arrived : flow.shares) total += arrived.share;
  EXPECT_NEAR(total, 1.0, 1e-12);
  for (size_t t = 0; t < flow.polylines.size(); ++t) {
    const int reached = flow.support_interface[t];
    ASSERT_GE(reached, 0) << "trace " << t;
    const Interface& contact = (*s.interfaces())[reached];
    EXPECT_TRUE(s.is_support(contact.a) || s.is_support(contact.b));
    const Vec3 end = flow.polylines[t].back();
    EXPECT_LT(std::abs((end - contact.center).dot(contact.normal)), 1e-9) << "trace " << t;
    Box3 extent;
    for (const Vec3& p : contact.vertices) extent.add(p);
    EXPECT_TRUE(((end.array() >= extent.lo.array() - 1e-9) &&
                 (end.array() <= extent.hi.array() + 1e-9)).all())
        << "trace " << t;
  }
}

}  // namespace

TEST(ForceFlow, PointForceRowsAreThoseOfAPointLoad) {
  for (bool planar : {false, true}) {
    Structure plain = frame(-1.4, 1.4);
    plain.set_planar(planar);
    Structure loaded = plain;
    // Off the centroid and, in 3D, along every axis, so every moment row counts.
    const Vec3 force = planar ? Vec3(300, 0, -700) : Vec3(300, -200, -700);
    const Vec3 at = planar ? Vec3(0.9, 0, 1.3) : Vec3(0.9, 0.1, 1.3);
    loaded.add_load({kBeam, force, at});
    const EquilibriumOptions options;
    const EquilibriumProblem without = build_equilibrium_problem(plain, options);
    const EquilibriumProblem with = build_equilibrium_problem(loaded, options);
    ASSERT_EQ(without.weight_unit, with.weight_unit);
    Eigen::VectorXd expected = Eigen::VectorXd::Zero(with.row_count);
    expected.segment(with.row_of_block[kBeam], with.block_rows) =
        point_force_rows(with, loaded, kBeam, force, at);
    EXPECT_LT((with.rhs - without.rhs - expected).lpNorm<Eigen::Infinity>(), 1e-12)
        << (planar ? "planar" : "3D");
    EXPECT_GT(expected.lpNorm<Eigen::Infinity>(), 0.1);
  }
}

TEST(ForceFlow, ContainsPointOfConvexAndNonConvexBlocks) {
  const Block cube = make_box({1, 2, 3}, {0, 0, 0});
  EXPECT_TRUE(contains_point(cube, {0.1, 0.9, -1.4}));
  EXPECT_FALSE(contains_point(cube, {0.6, 0, 0}));
  EXPECT_FALSE(contains_point(cube, {0, 0, 1.6}));
  // An L: the notch's corner square (1..2, 1..2) is outside.
  const Block l = make_prism({{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}},
                             {0, 0, 1});
  EXPECT_TRUE(contains_point(l, {0.5, 1.5, 0.5}));
  EXPECT_TRUE(contains_point(l, {1.5, 0.5, 0.5}));
  EXPECT_FALSE(contains_point(l, {1.5, 1.5, 0.5}));
  EXPECT_FALSE(contains_point(l, {0.5, 0.5, 1.5}));
}

TEST(ForceFlow, SameSeedSameTracesOtherSeedOtherTraces) {
  const Structure s = frame(-1.4, 1.4);
  ForceFlowOptions options;
  options.traces = 50;
  const AnalysisSettings settings;
  const ForceFlow first = trace_loads(s, kBeam, options, settings);
  const ForceFlow again = trace_loads(s, kBeam, options, settings);
  options.seed = 2;
  const ForceFlow other = trace_loads(s, kBeam, options, settings);
  ASSERT_EQ(first.polylines.size(), 50u);
  EXPECT_EQ(first.polylines, again.polylines);
  EXPECT_EQ(first.support_interface, again.support_interface);
  EXPECT_NE(first.polylines, other.polylines);
}

TEST(ForceFlow, SymmetricFrameSplitsTheBeamsWeightEvenly) {
  const Structure s = frame(-1.4, 1.4);
  ForceFlowOptions options;
  options.traces = 400;
  const ForceFlow flow = trace_loads(s, kBeam, options, AnalysisSettings{});
  EXPECT_TRUE(flow.stable);
  expect_all_reach_the_ground(s, flow);
  EXPECT_EQ(flow.shares.size(), 2u);
  EXPECT_NEAR(share_under(s, flow, -1.0), 0.5, 0.08);
  EXPECT_NEAR(share_under(s, flow, 1.0), 0.5, 0.08);
  for (const std::vector<Vec3>& polyline : flow.polylines) {
    EXPECT_EQ(polyline.front(), s.block(kBeam).centroid());
  }
}

TEST(ForceFlow, OffCentreBeamSendsMostToTheNearerPost) {
  // Centroid at x = 0.5: by statics 3/4 of its weight rests on the right post.
  const Structure s = frame(-1.2, 2.2);
  ForceFlowOptions options;
  options.traces = 400;
  const ForceFlow flow = trace_loads(s, kBeam, options, AnalysisSettings{});
  expect_all_reach_the_ground(s, flow);
  EXPECT_GT(share_under(s, flow, 1.0), 0.6);
  EXPECT_LT(share_under(s, flow, -1.0), 0.4);
}

TEST(ForceFlow, FirstStepSplitsTheBeamLikeItsReactions) {
  // The step's density is proportional to the force passed on: 3/4 of the
  // off-centre beam's weight rests on the right post.
  const Structure s = frame(-1.2, 2.2);
  ForceFlowOptions options;
  options.traces = 1000;
  options.max_steps = 1;
  const ForceFlow flow = trace_loads(s, kBeam, options, AnalysisSettings{});
  ASSERT_TRUE(flow.valid);
  EXPECT_EQ(flow.lost, 1000);
  int right = 0;
  for (const std::vector<Vec3>& polyline : flow.polylines) {
    ASSERT_EQ(polyline.size(), 2u);
    EXPECT_NEAR(polyline[1].z(), 1.0, 1e-9);  // on a post's top
    right += polyline[1].x() > 0.0;
  }
  EXPECT_NEAR(right / 1000.0, 0.75, 0.05);
}

TEST(ForceFlow, PointsAreSpreadLinearlyInTheVertexForces) {
  // A right-triangular prism on the ground, its vertical face at x = 0 and
  // its base from x = 0 to L: its weight acts at x = L / 3, so the base's
  // vertex forces are 2 : 1 between x = 0 and x = L, and a density linear
  // in them has mean x = L (2 + 2 x 1) / (3 (2 + 1)) = 4 L / 9 (uniform
  // points: L / 2, the resultant: L / 3).
  const double length = 1.2;
  Structure s;
  s.add(std::make_shared<const Block>(
      make_prism({{0, 0, 0}, {length, 0, 0}, {0, 0, 0.9}}, {0, 0.5, 0})));
  s.add(box({3, 3, 0.2}, {0.6, 0, -0.1}), true);
  ForceFlowOptions options;
  options.traces = 4000;
  const ForceFlow flow = trace_loads(s, 0, options, AnalysisSettings{});
  expect_all_reach_the_ground(s, flow);
  double mean = 0.0;
  for (const std::vector<Vec3>& polyline : flow.polylines) mean += polyline[1].x() / options.traces;
  EXPECT_NEAR(mean, 4 * length / 9, 0.015 * length);
}

TEST(ForceFlow, WithoutTurningBackTracesGoStraightDown) {
  const Structure s = frame(-1.2, 2.2);
  ForceFlowOptions options;
  options.traces = 400;
  options.turn_back = false;
  const ForceFlow flow = trace_loads(s, kBeam, options, AnalysisSettings{});
  expect_all_reach_the_ground(s, flow);
  EXPECT_NEAR(share_under(s, flow, 1.0), 0.75, 0.06);
  for (const std::vector<Vec3>& polyline : flow.polylines) {
    ASSERT_EQ(polyline.size(), 4u);  // centroid, top of a post, its middle joint, the ground
    EXPECT_NEAR(polyline[2].z(), 0.5, 1e-9);
    EXPECT_NEAR(polyline[3].z(), 0.0, 1e-9);
  }
}

TEST(ForceFlow, RandomStartsLieInsideTheBlock) {
  const Structure s = frame(-1.4, 1.4);
  ForceFlowOptions options;
  options.traces = 400;
  options.start = TraceStart::random;
  const ForceFlow flow = trace_loads(s, kBeam, options, AnalysisSettings{});
  expect_all_reach_the_ground(s, flow);
  Vec3 mean = Vec3::Zero();
  for (const std::vector<Vec3>& polyline : flow.polylines) {
    EXPECT_TRUE(contains_point(s.block(kBeam), polyline.front()));
    mean += polyline.front() / options.traces;
  }
  // Uniform in a 2.8 m beam: the mean x has a standard error of 0.04 m.
  EXPECT_LT((mean - s.block(kBeam).centroid()).norm(), 0.15);
  EXPECT_NEAR(share_under(s, flow, -1.0), 0.5, 0.08);
}

TEST(ForceFlow, UnstableStructuresAreTracedAndSaySo) {
  // A block overhanging its support by more than half: it needs tension.
  Structure s;
  s.add(box({1, 1, 1}, {0.8, 0, 0.5}));
  s.add(box({1, 1, 1}, {0, 0, -0.5}), true);
  ForceFlowOptions options;
  options.traces = 20;
  const ForceFlow flow = trace_loads(s, 0, options, AnalysisSettings{});
  EXPECT_FALSE(flow.stable);
  EXPECT_FALSE(flow.analysis.stable);
  expect_all_reach_the_ground(s, flow);
}

TEST(ForceFlow, BadArgumentsAreNamed) {
  const Structure s = frame(-1.4, 1.4);
  const AnalysisSettings settings;
  ForceFlowOptions options;
  EXPECT_TRUE(contains(error_of([&] { trace_loads(s, 5, options, settings); }), "is a support"));
  EXPECT_TRUE(contains(error_of([&] { trace_loads(s, 6, options, settings); }), "out of range"));
  EXPECT_TRUE(contains(error_of([&] { trace_loads(s, -1, options, settings); }), "out of range"));
  options.traces = 0;
  EXPECT_TRUE(contains(error_of([&] { trace_loads(s, kBeam, options, settings); }),
                       "traces must be at least 1"));
  Structure floating = s;
  floating.add(box({0.2, 0.2, 0.2}, {0, 0, 5}), false, "cloud");
  options.traces = 1;
  EXPECT_TRUE(contains(error_of([&] { trace_loads(floating, 6, options, settings); }),
                       "touches nothing"));
}
