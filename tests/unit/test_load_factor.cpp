// Load factor and friction demand against closed-form statics (a block
// tipping or sliding, a stack, a block on an incline) and against the
// interior-point analysis's own verdict just inside and outside the limit.
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

#include "analysis/equilibrium.hpp"
#include "analysis/kinematic.hpp"
#include "analysis/load_factor.hpp"
#include "core/interrupt.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

constexpr double kNoSliding = std::numeric_limits<double>::infinity();

// Blocks of width b (x) and height h, stacked on a support; planar.
Structure stack(int count, double b, double h) {
  Structure s;
  s.add(box({2.0, 1.0, 0.2}, {0, 0, -0.1}), true);
  for (int k = 0; k < count; ++k) s.add(box({b, 0.6, h}, {0, 0, (k + 0.5) * h}));
  s.set_planar(true);
  return s;
}

LoadFactorSettings lateral(double friction, const Vec3& direction = Vec3(1, 0, 0)) {
  LoadFactorSettings settings;
  settings.problem.friction = friction;
  settings.direction = direction;
  return settings;
}

// Whether it stands with `factor` times each block's weight along `direction`
// as point loads at the centroids.
bool stands_with(Structure s, double factor, const Vec3& direction, double friction) {
  for (int j = 0; j < s.size(); ++j) {
    if (s.is_support(j)) continue;
    s.add_load({j, factor * s.block(j).mass() * kGravity * direction, s.block(j).centroid()});
  }
  AnalysisSettings settings;
  settings.problem.friction = friction;
  return analyze_equilibrium(s, settings).stable;
}

// A 3D wall of `columns` x `courses` blocks in stack bond on a support:
// 120 blocks at 12 x 10, past the bodies from which a 3D load factor keeps
// the barrier's own optimum.
Structure stack_bonded_wall(int columns, int courses) {
  Structure s;
  s.add(box({0.5 * columns + 1.0, 1.0, 0.2}, {0.25 * (columns - 1), 0, -0.1}), true);
  for (int k = 0; k < courses; ++k) {
    for (int c = 0; c < columns; ++c) s.add(box({0.5, 0.3, 0.25}, {0.5 * c, 0, (k + 0.5) * 0.25}));
  }
  return s;
}

}  // namespace

TEST(LoadFactor, BlockTipsAtWidthOverHeight) {
  const Structure s = stack(1, 0.4, 1.2);
  for (const double sign : {1.0, -1.0}) {
    const LoadFactor f = load_factor(s, lateral(kNoSliding, Vec3(sign, 0, 0)));
    ASSERT_EQ(f.status, MarginStatus::optimal);
    EXPECT_TRUE(f.stable);
    EXPECT_NEAR(f.factor, 0.4 / 1.2, 1e-9);
    ASSERT_EQ(f.limit.size(), 1u);
    EXPECT_EQ(f.limit[0].mode, LimitMode::hinge);
    EXPECT_NEAR(f.limit[0].pivot.x(), sign * 0.2, 1e-9) << "it tips about the leeward edge";
    EXPECT_NEAR(f.limit[0].pivot.z(), 0.0, 1e-9);
    EXPECT_GT(sign * f.mechanism[1].rotation.y(), 0.0) << "the top moves with the load";
    EXPECT_EQ(f.mechanism[0].velocity.norm(), 0.0);
  }
}

TEST(LoadFactor, BlockSlidesAtTheFrictionCoefficient) {
  const LoadFactor f = load_factor(stack(1, 0.4, 1.2), lateral(0.2));
  ASSERT_EQ(f.status, MarginStatus::optimal);
  EXPECT_NEAR(f.factor, 0.2, 1e-9);
  ASSERT_EQ(f.limit.size(), 1u);
  EXPECT_EQ(f.limit[0].mode, LimitMode::sliding);
  EXPECT_GT(f.mechanism[1].velocity.x(), 0.0);
}

TEST(LoadFactor, StackTipsAsAWhole) {
  // The top k blocks tip about their lowest joint at b / (k h): the whole
  // stack, about the support, goes first.
  const LoadFactor f = load_factor(stack(3, 0.5, 0.4), lateral(kNoSliding));
  ASSERT_EQ(f.status, MarginStatus::optimal);
  EXPECT_NEAR(f.factor, 0.5 / 1.2, 1e-9);
  ASSERT_EQ(f.limit.size(), 1u);
  EXPECT_EQ(f.limit[0].mode, LimitMode::hinge);
  EXPECT_NEAR(f.limit[0].pivot.z(), 0.0, 1e-9);
}

TEST(LoadFactor, ALoadThatStandsAloneIsUnboundedWithoutAProgram) {
  // A block of width b and height h pushed by lambda times its weight
  // along (t, 0, -1) / |(t, 0, -1)|, on top of its weight: with l = lambda
  // / |(t, 0, -1)| the resultant leans at l t / (1 + l), below t for every
  // lambda. It stands for every lambda while t stays under both mu
  // (sliding) and b / h (tipping), and otherwise gives way at l = r / (t -
  // r), r the smaller of the two.
  const Structure s = stack(1, 0.4, 1.2);  // b / h = 1/3
  const LoadFactor leaning = load_factor(s, lateral(0.7, Vec3(0.3, 0, -1)));
  EXPECT_EQ(leaning.status, MarginStatus::unbounded);
  EXPECT_TRUE(leaning.stable);
  EXPECT_EQ(leaning.iterations, 0) << "the load alone was proven to stand: no program solved";
  const LoadFactor slides = load_factor(s, lateral(0.2, Vec3(0.3, 0, -1)));
  ASSERT_EQ(slides.status, MarginStatus::optimal);
  EXPECT_NEAR(slides.factor, std::sqrt(1.09) * 0.2 / (0.3 - 0.2), 1e-9);
  const LoadFactor tips = load_factor(s, lateral(0.7, Vec3(0.5, 0, -1)));
  ASSERT_EQ(tips.status, MarginStatus::optimal);
  EXPECT_NEAR(tips.factor, std::sqrt(1.25) * (1.0 / 3.0) / (0.5 - 1.0 / 3.0), 1e-9);
}

TEST(LoadFactor, GravityNeverTopplesItAndLiftingOffTakesOneG) {
  const Structure s = stack(2, 0.4, 1.2);
  EXPECT_EQ(load_factor(s, lateral(0.7, Vec3(0, 0, -1))).status, MarginStatus::unbounded);
  const LoadFactor lift = load_factor(s, lateral(0.7, Vec3(0, 0, 2)));
  ASSERT_EQ(lift.status, MarginStatus::optimal);
  EXPECT_NEAR(lift.factor, 1.0, 1e-9);
  // Weightless at one g, any motion that lifts a block is a mechanism: the
  // solver picks one of them (a block rises, none sinks).
  double rising = 0.0;
  for (int i = 1; i < s.size(); ++i) {
    rising = std::max(rising, lift.mechanism[i].velocity.z());
    EXPECT_GE(lift.mechanism[i].velocity.z(), -1e-9) << "block " << i;
  }
  EXPECT_GT(rising, 0.0);
}

TEST(LoadFactor, PointLoadTipsTheBlock) {
  Structure s = stack(1, 0.4, 1.2);
  const double weight = s.block(1).mass() * kGravity;
  s.add_load({1, Vec3(1000, 0, 0), Vec3(0, 0, 1.2)});
  LoadFactorSettings settings = lateral(kNoSliding);
  settings.pattern = LoadPattern::point_loads;
  const LoadFactor f = load_factor(s, settings);
  ASSERT_EQ(f.status, MarginStatus::optimal);
  EXPECT_NEAR(f.factor, weight * 0.2 / (1000 * 1.2), 1e-9);
}

TEST(LoadFactor, ArchAgreesWithTheAnalysisOnEitherSide) {
  const Structure s = semicircular_arch(16, 0.9);
  for (const double friction : {kNoSliding, 0.4}) {
    const LoadFactor f = load_factor(s, lateral(friction));
    ASSERT_EQ(f.status, MarginStatus::optimal);
    ASSERT_GT(f.factor, 0.05);
    EXPECT_TRUE(stands_with(s, f.factor * (1 - 1e-4), Vec3(1, 0, 0), friction)) << friction;
    EXPECT_FALSE(stands_with(s, f.factor * (1 + 1e-4), Vec3(1, 0, 0), friction)) << friction;
    if (std::isinf(friction)) {
      // No sliding: a four-hinge mechanism, hinges alternating between the
      // intrados and the extrados.
      ASSERT_EQ(f.limit.size(), 4u);
      for (const LimitInterface& limit : f.limit) EXPECT_EQ(limit.mode, LimitMode::hinge);
    }
  }
}

TEST(LoadFactor, ReportsWhatItCannotAnswer) {
  Structure floating = stack(1, 0.4, 1.2);
  floating.add(box({0.2, 0.2, 0.2}, {5, 0, 5}));
  EXPECT_EQ(load_factor(floating, lateral(0.7)).status, MarginStatus::floating);
  EXPECT_TRUE(contains(error_of([] { load_factor(stack(1, 1, 1), lateral(0.7, Vec3(0, 0, 0))); }),
                       "direction"));
  EXPECT_TRUE(contains(error_of([] { load_factor(stack(1, 1, 1), lateral(0.7, Vec3(1, 1, 0))); }),
                       "planar"));
  LoadFactorSettings settings;
  settings.pattern = LoadPattern::point_loads;
  EXPECT_TRUE(contains(error_of([&] { load_factor(stack(1, 1, 1), settings); }), "no point loads"));
}

TEST(FrictionDemand, BlockOnAnInclineNeedsTheTangentOfItsSlope) {
  for (const double slope : {0.1, 0.35, 0.6}) {
    Structure s;
    const Vec3 axis(0, 1, 0), origin(0, 0, 0);
    s.add(std::make_shared<const Block>(make_box({3.0, 1.0, 0.2}, {0, 0, -0.1}).rotated(axis, slope, origin)), true);
    s.add(std::make_shared<const Block>(make_box({1.0, 0.6, 0.4}, {0, 0, 0.2}).rotated(axis, slope, origin)));
    const FrictionDemand demand = friction_demand(s, {EquilibriumOptions{}, 1e-9});
    ASSERT_EQ(demand.status, MarginStatus::optimal);
    EXPECT_NEAR(demand.friction, std::tan(slope), 1e-7 * std::tan(slope)) << slope;
    // The lower end is proven too small (on this 3D block, by the interior
    // point's multipliers): it must be.
    EXPECT_LT(demand.lower, std::tan(slope)) << slope;
    EXPECT_LE(demand.friction - demand.lower, 1e-9 * demand.friction) << slope;
    ASSERT_EQ(demand.critical.size(), 1u);
  }
}

TEST(FrictionDemand, AStopAskedMidSearchKeepsTheBracketItHad) {
  // Ctrl-C asked once the bracket has its first digit, on a 3D block on an
  // incline (the interior point's programs): interrupted, and the bracket
  // so far still holds the closed form tan(slope).
  const double slope = 0.35;
  Structure s;
  const Vec3 axis(0, 1, 0), origin(0, 0, 0);
  s.add(std::make_shared<const Block>(make_box({3.0, 1.0, 0.2}, {0, 0, -0.1}).rotated(axis, slope, origin)), true);
  s.add(std::make_shared<const Block>(make_box({1.0, 0.6, 0.4}, {0, 0, 0.2}).rotated(axis, slope, origin)));
  const FrictionDemand demand = friction_demand(s, {EquilibriumOptions{}, 1e-9}, [](int done, int) {
    if (done >= 1) interrupt_requested() = true;
  });
  interrupt_requested() = false;
  EXPECT_EQ(demand.status, MarginStatus::interrupted);
  EXPECT_LT(demand.lower, std::tan(slope));
  EXPECT_GE(demand.friction, std::tan(slope) * (1 - 1e-12));
  EXPECT_GT(demand.friction - demand.lower, 1e-9 * demand.friction);  // stopped before the bracket closed
}

TEST(FrictionDemand, ArchAgreesWithTheAnalysis) {
  const Structure s = semicircular_arch(16, 0.65);
  const FrictionDemand demand = friction_demand(s, {});
  ASSERT_EQ(demand.status, MarginStatus::optimal);
  ASSERT_GT(demand.friction, 0.05);
  AnalysisSettings settings;
  settings.problem.friction = demand.friction * (1 + 1e-4);
  EXPECT_TRUE(analyze_equilibrium(s, settings).stable);
  settings.problem.friction = demand.friction * (1 - 1e-4);
  EXPECT_FALSE(analyze_equilibrium(s, settings).stable);
}

TEST(FrictionDemand, TellsTheDigitsOfItsBracket) {
  // 0 of the 6 digits that tolerance 1e-6 asks for first, then counts
  // that only grow, ending at 6: the bracket [lower, friction] is then
  // within 1e-6 relative.
  std::vector<std::pair<int, int>> told;
  const FrictionDemand demand = friction_demand(semicircular_arch(16, 0.65), {EquilibriumOptions{}, 1e-6},
                                                [&](int done, int total) { told.emplace_back(done, total); });
  ASSERT_EQ(demand.status, MarginStatus::optimal);
  ASSERT_GE(told.size(), 2u);
  EXPECT_EQ(told.front(), std::make_pair(0, 6));
  EXPECT_EQ(told.back(), std::make_pair(6, 6));
  for (size_t k = 1; k < told.size(); ++k) EXPECT_GE(told[k].first, told[k - 1].first);
  EXPECT_LE(demand.friction - demand.lower, 1e-6 * demand.friction);
}

TEST(FrictionDemand, NoneOnFlatGroundAndNoneEnoughWhenItFalls) {
  const FrictionDemand flat = friction_demand(stack(2, 0.4, 0.4), {});
  EXPECT_EQ(flat.status, MarginStatus::optimal);
  EXPECT_EQ(flat.friction, 0.0);
  const FrictionDemand thin = friction_demand(semicircular_arch(16, 0.3), {});
  EXPECT_EQ(thin.status, MarginStatus::unstable);
  EXPECT_TRUE(std::isinf(thin.friction));
  EXPECT_TRUE(contains(error_of([] { friction_demand(stack(1, 1, 1), {EquilibriumOptions{}, 0.0}); }),
                       "tolerance"));
}

TEST(LoadFactor, TellsEveryIterationOfItsProgram) {
  // One call per Clp iteration (the barrier's, its crossover's and the
  // simplex's pivots alike), counting up from 1 with no total known ahead;
  // the factor's iterations are that count, and the count changes nothing.
  const Structure s = semicircular_arch(16, 0.65);
  std::vector<std::pair<int, int>> told;
  const LoadFactor factor =
      load_factor(s, lateral(kNoSliding), [&](int done, int total) { told.emplace_back(done, total); });
  ASSERT_EQ(factor.status, MarginStatus::optimal);
  ASSERT_FALSE(told.empty());
  for (size_t k = 0; k < told.size(); ++k) EXPECT_EQ(told[k], std::make_pair(static_cast<int>(k) + 1, kTotalUnknown));
  EXPECT_EQ(factor.iterations, static_cast<int>(told.size()));
  EXPECT_EQ(load_factor(s, lateral(kNoSliding)).factor, factor.factor);
}

TEST(LoadFactor, TheKinematicSearchTellsTheDigitsOfItsBracket) {
  // A squat block slides at mu = 0.5 before it tips: 0 of the 3 digits
  // that tolerance 1e-3 asks for first, then counts that only grow, ending
  // at 3 with the factor within 1e-3 below the equilibrium method's 0.5.
  const Structure s = stack(1, 1.0, 0.3);
  AnalysisSettings settings;
  settings.problem.friction = 0.5;
  std::vector<std::pair<int, int>> told;
  const KinematicLoadFactor factor = kinematic_load_factor(
      s, {lateral(0.5), settings, 1e-3}, [&](int done, int total) { told.emplace_back(done, total); });
  ASSERT_EQ(factor.status, MarginStatus::optimal);
  ASSERT_GE(told.size(), 2u);
  EXPECT_EQ(told.front(), std::make_pair(0, 3));
  EXPECT_EQ(told.back(), std::make_pair(3, 3));
  for (size_t k = 1; k < told.size(); ++k) EXPECT_GE(told[k].first, told[k - 1].first);
  EXPECT_LE(factor.factor, 0.5 * (1 + 1e-9));
  EXPECT_GE(factor.factor, 0.5 * (1 - 1e-3));
}

TEST(LoadFactor, AnInterruptedSearchCarriesNoVerdict) {
  // Ctrl-C (the flag the host's handler sets) stops Clp after its current
  // iteration: the answer says so, with no factor and no verdict, though
  // this stack stands and tips at b/h = 1/3.
  const Structure s = stack(1, 0.4, 1.2);
  interrupt_requested() = true;
  const LoadFactor factor = load_factor(s, lateral(kNoSliding));
  const FrictionDemand demand = friction_demand(s, {lateral(kNoSliding).problem});
  interrupt_requested() = false;
  EXPECT_EQ(factor.status, MarginStatus::interrupted);
  EXPECT_TRUE(std::isnan(factor.factor));
  EXPECT_FALSE(factor.stable);
  EXPECT_EQ(demand.status, MarginStatus::interrupted);
  EXPECT_TRUE(std::isnan(demand.friction));
  // And without the request, the same calls answer.
  EXPECT_NEAR(load_factor(s, lateral(kNoSliding)).factor, 0.4 / 1.2, 1e-9);
}

TEST(LoadFactor, AStopAskedMidProgramCarriesNoVerdict) {
  // Ctrl-C asked during the program (from its third iteration's progress
  // call), on a planar arch (barrier and crossover) and on a 3D wall of
  // 120 blocks (the barrier's own optimum): interrupted, no factor, no
  // verdict; each answers without the request.
  for (const Structure& s : {semicircular_arch(16, 0.65), stack_bonded_wall(12, 10)}) {
    const LoadFactor factor = load_factor(s, lateral(0.7), [](int done, int) {
      if (done == 3) interrupt_requested() = true;
    });
    interrupt_requested() = false;
    EXPECT_EQ(factor.status, MarginStatus::interrupted);
    EXPECT_TRUE(std::isnan(factor.factor));
    EXPECT_FALSE(factor.stable);
    const LoadFactor answered = load_factor(s, lateral(0.7));
    EXPECT_EQ(answered.status, MarginStatus::optimal);
    EXPECT_GT(answered.factor, 0.0);
    EXPECT_TRUE(stands_with(s, answered.factor * (1 - 1e-4), Vec3(1, 0, 0), 0.7));
    EXPECT_FALSE(stands_with(s, answered.factor * (1 + 1e-4), Vec3(1, 0, 0), 0.7));
  }
}
