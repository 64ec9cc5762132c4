// Load capacity by linear programming against the analysis's own verdict:
// just inside each bound the structure stands, just outside it does not.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>
#include <utility>
#include <vector>

#include "analysis/load_capacity.hpp"
#include "core/interrupt.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// Whether the structure stands with block i's weight times `multiple`
// (the difference as a point load at its centroid).
bool stands_with(Structure s, int block, double multiple, const AnalysisSettings& settings) {
  const double weight = s.block(block).mass() * kGravity;
  s.add_load({block, Vec3(0, 0, -(multiple - 1.0) * weight), s.block(block).centroid()});
  return analyze_equilibrium(s, settings).stable;
}

}  // namespace

TEST(LoadCapacity, BoundsAgreeWithTheAnalysis) {
  // With its mirror symmetry (one voussoir of each pair solved) and
  // without: every bound against the analysis.
  const Structure s = semicircular_arch(9, 0.8);
  for (const bool symmetry : {true, false})
  for (double friction : {std::numeric_limits<double>::infinity(), 0.5}) {
    AnalysisSettings settings;
    settings.problem.friction = friction;
    const LoadCapacity capacity = load_capacity(s, {settings, 0, symmetry});
    ASSERT_EQ(capacity.status, MarginStatus::optimal);
    EXPECT_EQ(capacity.symmetries, symmetry ? 2 : 1);
    EXPECT_TRUE(capacity.stable);
    int finite_maxima = 0;
    for (int i = 0; i < 9; ++i) {
      const double lo = capacity.min[i], hi = capacity.max[i];
      ASSERT_FALSE(std::isnan(lo)) << i;
      EXPECT_LE(lo, 1.0);
      EXPECT_GE(hi, 1.0);
      EXPECT_NEAR(lo, capacity.min[8 - i], 1e-6) << "symmetric arch";
      if (std::isfinite(hi)) {
        EXPECT_NEAR(hi, capacity.max[8 - i], 1e-6 * hi) << "symmetric arch";
        ++finite_maxima;
        EXPECT_TRUE(stands_with(s, i, hi * (1 - 1e-4), settings)) << i;
        EXPECT_FALSE(stands_with(s, i, hi * (1 + 1e-4), settings)) << i;
      }
      if (lo > 0.0) {
        EXPECT_TRUE(stands_with(s, i, lo * (1 + 1e-4), settings)) << i;
        EXPECT_FALSE(stands_with(s, i, lo * (1 - 1e-4), settings)) << i;
      } else {
        EXPECT_TRUE(stands_with(s, i, 0.0, settings)) << i;
      }
      if (std::isinf(hi)) {
        EXPECT_TRUE(std::isinf(capacity.max[8 - i])) << "symmetric arch";
      }
    }
    EXPECT_GT(finite_maxima, 0);
    // The as-built program, then per block solved at least the least and
    // the largest multiple.
    EXPECT_GE(capacity.programs, 1 + 2 * (symmetry ? 5 : 9));
    for (int support : {9, 10}) EXPECT_TRUE(std::isnan(capacity.max[support]));
  }
}

TEST(LoadCapacity, ACounterweightedCantileverHasItsClosedFormBounds) {
  // In 3D: a 3 x 1 x 0.5 lintel on a 1 x 1 pier (x in [-0.5, 0.5]), its
  // centroid 0.5 beyond the pier's edge at x = 0.5, held down by a 1 x 1 x 2
  // counterweight above the pier (centroid 0.5 behind the edge). Tipping
  // about the edge, the lintel's weight (1.5 units, arm 0.5) against the
  // counterweight's (2 units, arm 0.5): the counterweight needs at least
  // 0.75 of its weight and the lintel stands up to 4/3 of its own. The
  // least multiple 0.75 is the simplex's (the structure cannot stand with
  // the counterweight weightless); the rest, with friction, the
  // equilibrium solver's (0 < mu < infinity) or Clp's barrier (mu = inf).
  Structure s;
  s.add(box({4, 2, 1}, {0, 0, -0.5}), true);
  const int pier = s.add(box({1, 1, 2}, {0, 0, 1}));
  const int lintel = s.add(box({3, 1, 0.5}, {1, 0, 2.25}));
  const int counterweight = s.add(box({1, 1, 2}, {0, 0, 3.5}));
  for (double friction : {0.7, std::numeric_limits<double>::infinity()}) {
    const AnalysisSettings settings = with_friction(friction);
    const LoadCapacity capacity = load_capacity(s, {settings});
    ASSERT_EQ(capacity.status, MarginStatus::optimal);
    EXPECT_TRUE(capacity.stable);
    EXPECT_NEAR(capacity.min[counterweight], 0.75, 1e-6);
    EXPECT_TRUE(std::isinf(capacity.max[counterweight]));
    EXPECT_EQ(capacity.min[lintel], 0.0);
    EXPECT_NEAR(capacity.max[lintel], 4.0 / 3.0, 1e-6);
    EXPECT_EQ(capacity.min[pier], 0.0);
    EXPECT_TRUE(std::isinf(capacity.max[pier]));
    // And the analysis agrees on either side of each finite bound.
    EXPECT_TRUE(stands_with(s, counterweight, 0.75 * (1 + 1e-4), settings));
    EXPECT_FALSE(stands_with(s, counterweight, 0.75 * (1 - 1e-4), settings));
    EXPECT_TRUE(stands_with(s, lintel, 4.0 / 3.0 * (1 - 1e-4), settings));
    EXPECT_FALSE(stands_with(s, lintel, 4.0 / 3.0 * (1 + 1e-4), settings));
  }
}

TEST(LoadCapacity, ACableHoldingACantileverBoundsItsLargestMultiple) {
  // The lintel of the test above without its counterweight, held down at
  // its back end (x = -0.5, 1 from the pier's edge) by a vertical cable to
  // the ground that carries at most the lintel's own weight W: tipping
  // about the edge, k W x 0.5 <= W x 1, so the lintel stands up to twice
  // its weight, and weightless. With a cable the largest multiple is Clp's
  // barrier's, the least the analysis's certified verdict.
  Structure s;
  s.add(box({4, 2, 1}, {0, 0, -0.5}), true);
  const int pier = s.add(box({1, 1, 2}, {0, 0, 1}));
  const int lintel = s.add(box({3, 1, 0.5}, {1, 0, 2.25}));
  Cable cable;
  cable.from = {lintel, Vec3(-0.5, 0, 2.25)};
  cable.to = {0, Vec3(-0.5, 0, 0)};
  cable.max_tension = s.block(lintel).mass() * kGravity;
  s.add_cable(cable);
  for (double friction : {0.7, std::numeric_limits<double>::infinity()}) {
    const AnalysisSettings settings = with_friction(friction);
    const LoadCapacity capacity = load_capacity(s, {settings});
    ASSERT_EQ(capacity.status, MarginStatus::optimal);
    EXPECT_TRUE(capacity.stable);
    EXPECT_EQ(capacity.min[lintel], 0.0);
    EXPECT_NEAR(capacity.max[lintel], 2.0, 1e-6);
    EXPECT_EQ(capacity.min[pier], 0.0);
    EXPECT_TRUE(std::isinf(capacity.max[pier]));
    EXPECT_TRUE(stands_with(s, lintel, 0.0, settings));
    EXPECT_TRUE(stands_with(s, lintel, 2.0 * (1 - 1e-4), settings));
    EXPECT_FALSE(stands_with(s, lintel, 2.0 * (1 + 1e-4), settings));
  }
}

TEST(LoadCapacity, UnstableStructureHasNoMultipleForTheOthers) {
  Structure s;
  s.add(box({3, 3, 0.2}, {0, 0, -0.1}), true);
  s.add(box({1, 1, 0.5}, {0, 0, 0.25}));
  s.add(box({1, 1, 0.5}, {0.7, 0, 0.75}));  // its centroid past the edge below
  const LoadCapacity capacity = load_capacity(s, {});
  EXPECT_FALSE(capacity.stable);
  // Any weight of the top block tips it; a weightless one stands, and the
  // bottom block's weight cannot help.
  EXPECT_NEAR(capacity.min[2], 0.0, 1e-9);
  EXPECT_NEAR(capacity.max[2], 0.0, 1e-9);
  EXPECT_TRUE(std::isnan(capacity.min[1]));
  EXPECT_TRUE(std::isnan(capacity.max[1]));
}

TEST(LoadCapacity, AnInterruptedComputationCarriesNoVerdict) {
  // A sandboxed script's deadline already passed: the programs stop at
  // once, the status says so and nothing is claimed (this arch stands).
  const Structure s = semicircular_arch(9, 0.8);
  LoadCapacity capacity;
  {
    const DeadlineScope past(Clock::now());
    capacity = load_capacity(s, {});
  }
  EXPECT_EQ(capacity.status, MarginStatus::interrupted);
  EXPECT_FALSE(capacity.stable);
  for (int j = 0; j < s.size(); ++j) {
    EXPECT_TRUE(std::isnan(capacity.min[j]) && std::isnan(capacity.max[j])) << j;
  }
  EXPECT_TRUE(load_capacity(s, {}).stable);
}

TEST(LoadCapacity, TellsItsProgressOnTheCallingThread) {
  // 0 of the 9 voussoirs first, then counts that only grow, ending at 9;
  // every call on this thread though a second worker solves blocks too.
  const Structure s = semicircular_arch(9, 0.8);
  std::vector<std::pair<int, int>> told;
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  const LoadCapacity capacity = load_capacity(
      s, {AnalysisSettings{}, 2, /*use_symmetry=*/false}, [&](int done, int total) {
        elsewhere = elsewhere || std::this_thread::get_id() != caller;
        told.emplace_back(done, total);
      });
  ASSERT_EQ(capacity.status, MarginStatus::optimal);
  ASSERT_GE(told.size(), 2u);
  EXPECT_FALSE(elsewhere);
  EXPECT_EQ(told.front(), std::make_pair(0, 9));
  EXPECT_EQ(told.back(), std::make_pair(9, 9));
  for (size_t k = 1; k < told.size(); ++k) EXPECT_GE(told[k].first, told[k - 1].first);
}

TEST(LoadCapacity, BoundsAreTheSameToTheBitInEveryRunAndForAnyNumberOfThreads) {
  // Three chunks of blocks (load_capacity.cpp's kChunkBlocks) for two
  // workers to share, every block solved (no symmetry), on the 3D path
  // (the equilibrium solver's questions, Clp for the rest) and the planar
  // one (the simplex, then Clp's barrier). Bit patterns compared: a NaN
  // (a support) equals a NaN.
  auto same_bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (const bool planar : {false, true}) {
    Structure s = semicircular_arch(40, 0.8);
    s.set_planar(planar);
    AnalysisSettings settings;
    settings.problem.friction = 0.6;
    const LoadCapacity one = load_capacity(s, {settings, 1, /*use_symmetry=*/false});
    ASSERT_EQ(one.status, MarginStatus::optimal) << "planar " << planar;
    int finite = 0;
    for (int j = 0; j < 40; ++j) finite += std::isfinite(one.max[j]) ? 1 : 0;
    EXPECT_GT(finite, 0) << "planar " << planar;
    for (int run = 0; run < 2; ++run) {
      const LoadCapacity two = load_capacity(s, {settings, 2, /*use_symmetry=*/false});
      ASSERT_EQ(two.status, MarginStatus::optimal);
      EXPECT_EQ(two.programs, one.programs);
      EXPECT_EQ(two.simplex_iterations, one.simplex_iterations);
      for (int j = 0; j < s.size(); ++j) {
        EXPECT_TRUE(same_bits(two.min[j], one.min[j])) << "planar " << planar << " block " << j;
        EXPECT_TRUE(same_bits(two.max[j], one.max[j])) << "planar " << planar << " block " << j;
      }
    }
  }
}

TEST(LoadCapacity, TheBlocksAskedHaveTheWholeRunsBoundsAndNoOthersAreSolved) {
  // Four voussoirs of a 40-voussoir arch on the 3D path, no symmetry: the
  // same bounds as when every block is solved (each solve starts from the
  // as-built forces either way; the simplex bases and the guess that a run
  // of unbounded blocks goes on depend on the chunk, so to the solvers'
  // 1e-9), NaN for the blocks not asked, and one program for the as-built
  // structure plus at least two per block asked.
  const Structure s = semicircular_arch(40, 0.8);
  AnalysisSettings settings;
  settings.problem.friction = 0.6;
  const LoadCapacity every = load_capacity(s, {settings, 1, /*use_symmetry=*/false});
  ASSERT_EQ(every.status, MarginStatus::optimal);
  const std::vector<int> asked = {3, 17, 20, 33};
  const LoadCapacity some = load_capacity(s, {settings, 1, /*use_symmetry=*/false, asked});
  ASSERT_EQ(some.status, MarginStatus::optimal);
  EXPECT_TRUE(some.stable);
  EXPECT_GE(some.programs, 1 + 2 * 4);
  EXPECT_LT(some.programs, every.programs / 5);
  int finite = 0;
  for (int j = 0; j < s.size(); ++j) {
    if (std::find(asked.begin(), asked.end(), j) == asked.end()) {
      EXPECT_TRUE(std::isnan(some.min[j]) && std::isnan(some.max[j])) << j;
      continue;
    }
    EXPECT_NEAR(some.min[j], every.min[j], 1e-9 * std::max(1.0, every.min[j])) << j;
    if (std::isfinite(every.max[j])) {
      ++finite;
      EXPECT_NEAR(some.max[j], every.max[j], 1e-9 * every.max[j]) << j;
    } else {
      EXPECT_EQ(some.max[j], every.max[j]) << j;
    }
  }
  EXPECT_GT(finite, 0);
  for (const std::vector<int>& bad : {std::vector<int>{3, 3}, std::vector<int>{3, 42}, std::vector<int>{-1}}) {
    EXPECT_THROW(load_capacity(s, {settings, 1, false, bad}), InvalidArgument);
  }
}
