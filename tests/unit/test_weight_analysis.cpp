// Weight sensitivity (Shin 2014 eq. 7) against finite differences, and
// necessary weights (eq. 8) against hand statics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "analysis/weight_analysis.hpp"
#include "core/interrupt.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

AnalysisSettings precise(double friction) {
  AnalysisSettings settings;
  settings.problem.friction = friction;
  settings.solver.tolerance = 1e-13;
  return settings;
}

// Resultants of every interface with `extra` newtons added to block i's
// weight, as a point load at its centroid (the QP's units stay put).
std::vector<Vec3> resultants(Structure s, int block, double extra, const AnalysisSettings& settings) {
  s.add_load({block, Vec3(0, 0, -extra), s.block(block).centroid()});
  const EquilibriumResult r = analyze_equilibrium(s, settings);
  EXPECT_TRUE(r.stable);
  std::vector<Vec3> out;
  for (const InterfaceForces& f : r.interfaces) out.push_back(f.resultant);
  return out;
}

}  // namespace

TEST(WeightSensitivity, MatchesCentralDifferencesOnAnArch) {
  const Structure s = semicircular_arch(9, 1.0);
  for (double friction : {std::numeric_limits<double>::infinity(), 0.6}) {
    const AnalysisSettings settings = precise(friction);
    for (int block : {1, 4}) {
      const WeightSensitivity sensitivity = weight_sensitivity(s, block, settings);
      ASSERT_TRUE(sensitivity.valid);
      ASSERT_TRUE(sensitivity.analysis.stable);
      const double weight = s.block(block).mass() * kGravity;
      const double step = 1e-4 * weight;
      const std::vector<Vec3> plus = resultants(s, block, step, settings);
      const std::vector<Vec3> minus = resultants(s, block, -step, settings);
      double largest = 0.0;
      for (const Vec3& change : sensitivity.interface_resultant_change) {
        largest = std::max(largest, change.norm());
      }
      for (size_t i = 0; i < plus.size(); ++i) {
        const Vec3 difference = (plus[i] - minus[i]) / (2 * step);
        EXPECT_LT((sensitivity.interface_resultant_change[i] - difference).norm(), 1e-4 * largest)
            << "interface " << i << " block " << block << " friction " << friction;
      }
      // The supports carry the added weight: vertical resultants add up to 1.
      double vertical = 0.0;
      for (size_t i = 0; i < plus.size(); ++i) {
        const Interface& contact = (*s.interfaces())[i];
        if (s.is_support(contact.a)) vertical += sensitivity.interface_resultant_change[i].z();
        if (s.is_support(contact.b)) vertical -= sensitivity.interface_resultant_change[i].z();
      }
      EXPECT_NEAR(std::abs(vertical), 1.0, 1e-6);
    }
  }
}

TEST(WeightSensitivity, ColumnPassesTheWholeChangeDown) {
  Structure s;
  s.add(box({3, 3, 0.2}, {0, 0, -0.1}), true);
  for (int k = 0; k < 3; ++k) s.add(box({1, 1, 0.5}, {0, 0, 0.25 + 0.5 * k}));
  const WeightSensitivity top = weight_sensitivity(s, 3, precise(0.7));
  ASSERT_TRUE(top.valid);
  for (size_t i = 0; i < s.interfaces()->size(); ++i) {
    EXPECT_NEAR(top.interface_resultant_change[i].norm(), 1.0, 1e-7);
  }
  const WeightSensitivity bottom = weight_sensitivity(s, 1, precise(0.7));
  EXPECT_NEAR(bottom.block_change[3], 0.0, 1e-7);  // nothing above it changes
  EXPECT_GT(bottom.block_change[1], 0.9);
  EXPECT_TRUE(contains(error_of([&] { weight_sensitivity(s, 0, precise(0.7)); }), "is a support"));
  EXPECT_TRUE(contains(error_of([&] { weight_sensitivity(s, 7, precise(0.7)); }), "out of range"));
}

// Figure 8 (a): three stacked blocks, the middle one's centroid 0.1 m
// beyond the bottom one's edge, the top one set back on it. With only the
// middle block weighted, the top block must hold its back end down; the
// top block presses at its own centroid, 0.3 m behind the edge, so it
// needs at least a third of the middle's weight. The bottom block only
// passes forces down and needs none.
TEST(NecessaryWeights, TopBlockHoldsTheOverhangingMiddleOne) {
  Structure s;
  s.add(box({4, 2, 0.2}, {0, 0, -0.1}), true);
  s.add(box({1, 1, 0.5}, {0, 0, 0.25}));     // x in [-0.5, 0.5]
  s.add(box({1, 1, 0.5}, {0.6, 0, 0.75}));   // x in [0.1, 1.1]: centroid beyond the edge
  s.add(box({1, 1, 0.5}, {0.2, 0, 1.25}));   // x in [-0.3, 0.7]: rests on [0.1, 0.7]
  const AnalysisSettings settings = precise(0.7);
  ASSERT_TRUE(analyze_equilibrium(s, settings).stable);  // stands as built
  const NecessaryWeights needed = necessary_weights(s, 2, settings);
  EXPECT_TRUE(needed.stable);
  const double middle = s.block(2).mass() * kGravity;
  EXPECT_EQ(needed.weights[2], middle);
  EXPECT_EQ(needed.weights[0], 0.0);
  EXPECT_GT(needed.weights[3], middle / 3 * (1 - 1e-6));
  EXPECT_LT(needed.weights[3], middle);
  EXPECT_LT(needed.weights[1], 1e-6 * middle);

  // The top block on its own needs nothing from the others.
  const NecessaryWeights top = necessary_weights(s, 3, settings);
  EXPECT_TRUE(top.stable);
  EXPECT_LT(top.weights[1] + top.weights[2], 1e-6 * middle);

  const ImportantWeights important = important_weights(s, {settings});
  EXPECT_EQ(important.solves, 3);
  EXPECT_TRUE(important.unstable_blocks.empty());
  EXPECT_NEAR(important.per_volume[3] * s.block(3).volume(),
              needed.weights[3] + necessary_weights(s, 1, settings).weights[3], 1e-6 * middle);
}

TEST(ImportantWeights, AnInterruptedComputationSaysSo) {
  // Ctrl-C before the first block's problem: nothing is summed and nothing
  // is called unstable (each block's problem would stand on this arch).
  const Structure s = semicircular_arch(9, 0.8);
  interrupt_requested() = true;
  const ImportantWeights important = important_weights(s, {});
  interrupt_requested() = false;
  EXPECT_EQ(important.status, ImportantWeightsStatus::interrupted);
  EXPECT_EQ(important.solves, 0);
  EXPECT_TRUE(important.unstable_blocks.empty());
  for (double w : important.per_volume) EXPECT_EQ(w, 0.0);
  const ImportantWeights done = important_weights(s, {});
  EXPECT_EQ(done.status, ImportantWeightsStatus::done);
  EXPECT_EQ(done.symmetries, 2);  // the arch's mirror: one voussoir of each pair, and the keystone
  EXPECT_EQ(done.solves, 5);
}

TEST(ImportantWeights, EveryWorkerAnswersToTheCallersDeadline) {
  // Two workers under a sandbox deadline already passed: neither solves a
  // block (the helper gets the caller's deadline from the parallel loop).
  const Structure s = semicircular_arch(9, 0.8);
  ImportantWeights important;
  {
    const DeadlineScope past(Clock::now());
    important = important_weights(s, {AnalysisSettings{}, 2});
  }
  EXPECT_EQ(important.status, ImportantWeightsStatus::interrupted);
  EXPECT_EQ(important.solves, 0);
}

TEST(ImportantWeights, WorkersShareTheBlocksAndAgreeWithOne) {
  // Two workers, each a contiguous half of the blocks warm-started along
  // its own chain, against one worker along the whole chain: the same sums
  // to what the warm starts leave open (the weights are a regularised
  // least-squares answer, known to about 1e-5 of the largest).
  const Structure s = semicircular_arch(15, 0.8);
  AnalysisSettings settings;
  settings.problem.friction = std::numeric_limits<double>::infinity();
  const ImportantWeights one = important_weights(s, {settings, 1, /*use_symmetry=*/false});
  const ImportantWeights two = important_weights(s, {settings, 2, /*use_symmetry=*/false});
  ASSERT_EQ(one.solves, 15);
  ASSERT_EQ(two.solves, 15);
  EXPECT_EQ(one.unstable_blocks, two.unstable_blocks);
  double largest = 0.0;
  for (double v : one.per_volume) largest = std::max(largest, v);
  ASSERT_GT(largest, 0.0);
  for (int j = 0; j < s.size(); ++j) EXPECT_NEAR(two.per_volume[j], one.per_volume[j], 1e-4 * largest) << j;
}

TEST(ImportantWeights, SummedOverTheBlocksAskedTheyAreTheirNecessaryWeights) {
  // Two voussoirs asked: two solves, and per block the sum of the two
  // blocks' necessary weights (each solved on its own, cold) over its
  // volume, within what the warm start of the second leaves open.
  const Structure s = semicircular_arch(15, 0.8);
  AnalysisSettings settings;
  settings.problem.friction = std::numeric_limits<double>::infinity();
  const ImportantWeights some = important_weights(s, {settings, 1, /*use_symmetry=*/false, {4, 9}});
  ASSERT_EQ(some.solves, 2);
  const NecessaryWeights four = necessary_weights(s, 4, settings);
  const NecessaryWeights nine = necessary_weights(s, 9, settings);
  std::vector<double> expected(s.size(), 0.0);
  double largest = 0.0;
  for (int j = 0; j < s.size(); ++j) {
    if (s.is_support(j)) continue;
    const double sum = (j == 4 ? 0.0 : four.weights[j]) + (j == 9 ? 0.0 : nine.weights[j]);
    expected[j] = sum / s.block(j).volume();
    largest = std::max(largest, expected[j]);
  }
  ASSERT_GT(largest, 0.0);
  for (int j = 0; j < s.size(); ++j) EXPECT_NEAR(some.per_volume[j], expected[j], 1e-5 * largest) << j;
  EXPECT_THROW(important_weights(s, {settings, 1, false, {4, 4}}), InvalidArgument);
}
