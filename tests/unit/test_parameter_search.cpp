// find_threshold and refine_count against synthetic callbacks whose answers
// follow by hand: a criterion that stands from an exactly known value on, and
// metrics with closed-form changes between counts.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <vector>

#include "analysis/parameter_search.hpp"

using namespace ashlar;

namespace {

constexpr double kThreshold = 0.3137;

ThresholdVerdict stands_from_threshold(double value) {
  ThresholdVerdict verdict;
  verdict.stands = value >= kThreshold;
  return verdict;
}

ThresholdVerdict always(bool stands) {
  ThresholdVerdict verdict;
  verdict.stands = stands;
  return verdict;
}

std::vector<double> probed_values(const Threshold& t) {
  std::vector<double> values;
  for (const ThresholdProbe& probe : t.history) values.push_back(probe.value);
  return values;
}

// Every probe in the history agrees with the bracket it left.
void expect_consistent_history(const Threshold& t) {
  ASSERT_EQ(t.history.size(), static_cast<size_t>(t.evaluations));
  for (const ThresholdProbe& probe : t.history) {
    EXPECT_EQ(probe.verdict.stands, probe.value >= kThreshold) << probe.value;
    EXPECT_GE(probe.seconds, 0.0);
  }
}

}  // namespace

// From 1: 1, 0.5 stand, 0.25 falls; bisecting [0.25, 0.5] leaves a width of
// 0.25 / 2^k, which first drops to 1e-6 of the upper end (~3.137e-7) at
// k = 20 (2^-22 = 2.38e-7; 2^-21 = 4.77e-7 is too wide). The points are then
// multiples of 2^-22, and 0.3137 · 2^22 = 1315753.16, so the bracket is
// [1315753, 1315754] / 2^22, exactly.
TEST(ParameterSearch, ThresholdFromAbove) {
  const Threshold t = find_threshold(1.0, ThresholdSettings{}, stands_from_threshold);
  EXPECT_EQ(t.status, ThresholdStatus::converged);
  EXPECT_EQ(t.evaluations, 3 + 20);
  EXPECT_EQ(t.unstable, 1315753.0 / (1 << 22));
  EXPECT_EQ(t.stable, 1315754.0 / (1 << 22));
  expect_consistent_history(t);
  const std::vector<double> values = probed_values(t);
  EXPECT_EQ(std::vector<double>(values.begin(), values.begin() + 3),
            (std::vector<double>{1.0, 0.5, 0.25}));
}

// From 0.1: 0.1, 0.2 fall, 0.4 stands; bisecting [0.2, 0.4] needs 0.2 / 2^k
// <= ~3.137e-7, so k = 20 again (1.9e-7; 3.8e-7 at k = 19). 0.2 is not a
// binary fraction, so the bracket is checked by what it must satisfy.
TEST(ParameterSearch, ThresholdFromBelow) {
  const Threshold t = find_threshold(0.1, ThresholdSettings{}, stands_from_threshold);
  EXPECT_EQ(t.status, ThresholdStatus::converged);
  EXPECT_EQ(t.evaluations, 3 + 20);
  EXPECT_LT(t.unstable, kThreshold);
  EXPECT_GE(t.stable, kThreshold);
  EXPECT_NEAR(t.stable - t.unstable, 0.2 / (1 << 20), 1e-15);
  EXPECT_LE(t.stable - t.unstable, 1e-6 * t.stable);
  expect_consistent_history(t);
  const std::vector<double> values = probed_values(t);
  EXPECT_EQ(std::vector<double>(values.begin(), values.begin() + 3),
            (std::vector<double>{0.1, 0.2, 0.4}));
}

// A 1 % bracket from 1: [0.25, 0.5] bisected k = 7 times (0.25 / 128 =
// 1.95e-3 <= 3.14e-3; 3.9e-3 at k = 6), leaving [0.3125, 0.3125 + 2^-9].
TEST(ParameterSearch, ThresholdBisectsToTheTolerance) {
  ThresholdSettings settings;
  settings.bracket_tolerance = 1e-2;
  const Threshold t = find_threshold(1.0, settings, stands_from_threshold);
  EXPECT_EQ(t.status, ThresholdStatus::converged);
  EXPECT_EQ(t.evaluations, 10);
  EXPECT_EQ(t.unstable, 0.3125);
  EXPECT_EQ(t.stable, 0.314453125);
  EXPECT_EQ(probed_values(t), (std::vector<double>{1.0, 0.5, 0.25, 0.375, 0.3125, 0.34375,
                                                   0.328125, 0.3203125, 0.31640625,
                                                   0.314453125}));
  expect_consistent_history(t);
}

// Standing all the way down: 1, 0.5, 0.25, 0.125, then the floor itself.
TEST(ParameterSearch, ThresholdStableAtLower) {
  ThresholdSettings settings;
  settings.floor = 0.1;
  settings.ceiling = 10.0;
  const Threshold t = find_threshold(1.0, settings, [](double) { return always(true); });
  EXPECT_EQ(t.status, ThresholdStatus::stable_at_lower);
  EXPECT_STREQ(threshold_status_name(t.status), "stable_at_lower");
  EXPECT_EQ(probed_values(t), (std::vector<double>{1.0, 0.5, 0.25, 0.125, 0.1}));
  EXPECT_EQ(t.evaluations, 5);
  EXPECT_EQ(t.stable, 0.1);
  EXPECT_TRUE(std::isnan(t.unstable));

  const Threshold at_floor = find_threshold(0.1, settings, [](double) { return always(true); });
  EXPECT_EQ(at_floor.status, ThresholdStatus::stable_at_lower);
  EXPECT_EQ(at_floor.evaluations, 1);
}

// Falling all the way up: 1, 2, 4, 8, then the ceiling itself.
TEST(ParameterSearch, ThresholdUnstableAtUpper) {
  ThresholdSettings settings;
  settings.floor = 0.1;
  settings.ceiling = 10.0;
  const Threshold t = find_threshold(1.0, settings, [](double) { return always(false); });
  EXPECT_EQ(t.status, ThresholdStatus::unstable_at_upper);
  EXPECT_STREQ(threshold_status_name(t.status), "unstable_at_upper");
  EXPECT_EQ(probed_values(t), (std::vector<double>{1.0, 2.0, 4.0, 8.0, 10.0}));
  EXPECT_EQ(t.evaluations, 5);
  EXPECT_EQ(t.unstable, 10.0);
  EXPECT_TRUE(std::isnan(t.stable));
}

// The budget counts every call, the first included, and is never exceeded;
// running out keeps the bracket so far, in each phase.
TEST(ParameterSearch, ThresholdAnalysisBudget) {
  ThresholdSettings settings;
  settings.max_evaluations = 23;  // exactly what ThresholdFromAbove needs
  EXPECT_EQ(find_threshold(1.0, settings, stands_from_threshold).status,
            ThresholdStatus::converged);

  settings.max_evaluations = 22;
  Threshold t = find_threshold(1.0, settings, stands_from_threshold);
  EXPECT_EQ(t.status, ThresholdStatus::max_analyses);
  EXPECT_STREQ(threshold_status_name(t.status), "max_analyses");
  EXPECT_EQ(t.evaluations, 22);
  EXPECT_EQ(t.stable - t.unstable, std::ldexp(1.0, -21));
  EXPECT_LT(t.unstable, kThreshold);
  EXPECT_GE(t.stable, kThreshold);

  settings.max_evaluations = 10;  // bisecting: the 1 % bracket of ThresholdBisectsToTheTolerance
  t = find_threshold(1.0, settings, stands_from_threshold);
  EXPECT_EQ(t.status, ThresholdStatus::max_analyses);
  EXPECT_EQ(t.evaluations, 10);
  EXPECT_EQ(t.unstable, 0.3125);
  EXPECT_EQ(t.stable, 0.314453125);

  settings.max_evaluations = 3;  // halving
  t = find_threshold(1.0, settings, [](double) { return always(true); });
  EXPECT_EQ(t.status, ThresholdStatus::max_analyses);
  EXPECT_EQ(probed_values(t), (std::vector<double>{1.0, 0.5, 0.25}));
  EXPECT_EQ(t.stable, 0.25);
  EXPECT_TRUE(std::isnan(t.unstable));

  t = find_threshold(1.0, settings, [](double) { return always(false); });  // doubling
  EXPECT_EQ(t.status, ThresholdStatus::max_analyses);
  EXPECT_EQ(probed_values(t), (std::vector<double>{1.0, 2.0, 4.0}));
  EXPECT_EQ(t.unstable, 4.0);
  EXPECT_TRUE(std::isnan(t.stable));

  settings.max_evaluations = 1;
  t = find_threshold(1.0, settings, stands_from_threshold);
  EXPECT_EQ(t.status, ThresholdStatus::max_analyses);
  EXPECT_EQ(t.evaluations, 1);
}

// The history keeps each verdict as the criterion returned it.
TEST(ParameterSearch, ThresholdHistoryKeepsVerdicts) {
  int calls = 0;
  const auto criterion = [&](double value) {
    ThresholdVerdict verdict = stands_from_threshold(value);
    if (++calls % 2 == 0) {
      verdict.analysis = VerdictAnalysis{value / 10.0, calls, SolverStatus::inaccurate};
    }
    return verdict;
  };
  ThresholdSettings settings;
  settings.bracket_tolerance = 1e-2;
  const Threshold t = find_threshold(1.0, settings, criterion);
  ASSERT_EQ(t.history.size(), 10u);
  for (size_t k = 0; k < t.history.size(); ++k) {
    const ThresholdProbe& probe = t.history[k];
    ASSERT_EQ(probe.verdict.analysis.has_value(), k % 2 == 1) << k;
    if (!probe.verdict.analysis) continue;
    EXPECT_EQ(probe.verdict.analysis->infeasibility, probe.value / 10.0);
    EXPECT_EQ(probe.verdict.analysis->iterations, static_cast<int>(k + 1));
    EXPECT_EQ(probe.verdict.analysis->status, SolverStatus::inaccurate);
  }
}

TEST(ParameterSearch, ThresholdPropagatesCriterionErrors) {
  int calls = 0;
  const auto criterion = [&](double value) {
    if (++calls == 3) throw std::runtime_error("model failed");
    return stands_from_threshold(value);
  };
  EXPECT_THROW(find_threshold(1.0, ThresholdSettings{}, criterion), std::runtime_error);
  EXPECT_EQ(calls, 3);
}

// metric(n) = 1 + 1/n^2, so the change from n to 2n is
// (1/n^2 - 1/(4n^2)) / (1 + 1/(4n^2)) = 3 / (4n^2 + 1): 3/65, 3/257, then
// 3/1025 <= 1 % at 32. Against the finest (1 + 1/1024), 16 differs by
// 3/1025 and 8 by 15/1025 = 1.46 %, so 16 is adequate.
// One settled change stops the refinement (confirm = 1; the default asks two).
RefineSettings stop_at_first_agreement() {
  RefineSettings settings;
  settings.confirm = 1;
  return settings;
}

TEST(ParameterSearch, RefineSettlingMetric) {
  const auto metric = [](int n) { return 1.0 + 1.0 / (static_cast<double>(n) * n); };
  EXPECT_EQ(RefineSettings{}.confirm, 2);  // one agreement can be luck
  const Refinement r = refine_count(stop_at_first_agreement(), metric);
  EXPECT_TRUE(r.converged);
  ASSERT_EQ(r.history.size(), 4u);
  const int counts[] = {4, 8, 16, 32};
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(r.history[k].count, counts[k]);
    EXPECT_EQ(r.history[k].value, metric(counts[k]));
    EXPECT_GE(r.history[k].seconds, 0.0);
  }
  EXPECT_TRUE(std::isnan(r.history[0].change));
  EXPECT_DOUBLE_EQ(r.history[1].change, 3.0 / 65.0);
  EXPECT_DOUBLE_EQ(r.history[2].change, 3.0 / 257.0);
  EXPECT_DOUBLE_EQ(r.history[3].change, 3.0 / 1025.0);
  EXPECT_EQ(r.adequate, 2u);
  EXPECT_EQ(r.history[r.adequate].count, 16);

  // Two settled changes in a row: on to 64 (change 3/4097). Against 1 +
  // 1/4096, 16 differs by 15/4097 and 8 by 63/4097 = 1.54 %: still 16.
  RefineSettings twice;
  twice.confirm = 2;
  const Refinement r2 = refine_count(twice, metric);
  EXPECT_TRUE(r2.converged);
  ASSERT_EQ(r2.history.size(), 5u);
  EXPECT_EQ(r2.history.back().count, 64);
  EXPECT_DOUBLE_EQ(r2.history.back().change, 3.0 / 4097.0);
  EXPECT_EQ(r2.history[r2.adequate].count, 16);
}

// Counts: max(n + 1, ceil(1.5 n)) = 4, 6, 9, 14, 21, then 32 capped at 30.
// metric(n) = n changes by a third or so every step and never settles, so
// the finest count is the answer.
TEST(ParameterSearch, RefineNonSettlingMetric) {
  RefineSettings settings;
  settings.growth = 1.5;
  settings.max = 30;
  const Refinement r = refine_count(settings, [](int n) { return static_cast<double>(n); });
  EXPECT_FALSE(r.converged);
  std::vector<int> counts;
  for (const RefineStep& step : r.history) counts.push_back(step.count);
  EXPECT_EQ(counts, (std::vector<int>{4, 6, 9, 14, 21, 30}));
  EXPECT_DOUBLE_EQ(r.history[5].change, 9.0 / 30.0);
  EXPECT_EQ(r.adequate, 5u);

  // A growth of 1 still moves on by one.
  settings.start = 1;
  settings.growth = 1.0;
  settings.max = 5;
  counts.clear();
  for (const RefineStep& step : refine_count(settings, [](int n) { return 1.0 * n; }).history) {
    counts.push_back(step.count);
  }
  EXPECT_EQ(counts, (std::vector<int>{1, 2, 3, 4, 5}));

  settings.start = 5;
  const Refinement single = refine_count(settings, [](int) { return 1.0; });
  EXPECT_FALSE(single.converged);
  EXPECT_EQ(single.history.size(), 1u);
  EXPECT_EQ(single.adequate, 0u);
}

// 4 matches the finest exactly, but 8 is 50 % off, so the coarsest count
// from which every value is within 1 % is 16 (0.4 %).
TEST(ParameterSearch, RefineLuckyCoarseCount) {
  const std::map<int, double> values = {{4, 1.0}, {8, 1.5}, {16, 1.004}, {32, 1.0}};
  const Refinement r = refine_count(stop_at_first_agreement(), [&](int n) { return values.at(n); });
  EXPECT_TRUE(r.converged);
  ASSERT_EQ(r.history.size(), 4u);
  EXPECT_DOUBLE_EQ(r.history[3].change, 0.004);
  EXPECT_EQ(r.adequate, 2u);
  EXPECT_EQ(r.history[r.adequate].count, 16);
  EXPECT_EQ(r.history[r.adequate].value, 1.004);
}

// A zero value is matched only by zero: 1 then 0 is an infinite change.
TEST(ParameterSearch, RefineZeroValues) {
  const std::map<int, double> values = {{4, 1.0}, {8, 0.0}, {16, 0.0}};
  const Refinement r = refine_count(stop_at_first_agreement(), [&](int n) { return values.at(n); });
  EXPECT_TRUE(r.converged);
  ASSERT_EQ(r.history.size(), 3u);
  EXPECT_EQ(r.history[1].change, std::numeric_limits<double>::infinity());
  EXPECT_EQ(r.history[2].change, 0.0);
  EXPECT_EQ(r.history[r.adequate].count, 8);
}
