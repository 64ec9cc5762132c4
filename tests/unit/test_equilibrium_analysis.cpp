// The analysis object: setup once, update loads, friction or geometry, and
// solve again, each answer checked against closed-form statics.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "analysis/equilibrium_analysis.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

constexpr double kSlabWeight = 2 * 1 * 0.1 * 2400 * kGravity;  // N

// A 2 x 1 x 0.1 slab on the ground, pushed along x by `push` N at its
// centroid and pressed down by `press` N at x = `press_at`.
Structure pushed_slab(double push, double press = 0.0, double press_at = 0.0) {
  Structure s;
  s.add(box({3, 3, 0.2}, {0, 0, -0.1}), true);
  s.add(box({2, 1, 0.1}, {0, 0, 0.05}));
  if (push != 0.0) s.add_load({1, {push, 0, 0}, {0, 0, 0.05}});
  if (press != 0.0) s.add_load({1, {0, 0, -press}, {press_at, 0, 0.1}});
  return s;
}

}  // namespace

TEST(EquilibriumAnalysis, NewLoadsKeepTheSymbolicAnalysis) {
  const Structure first = pushed_slab(0.0);
  EquilibriumAnalysis analysis(first, {});
  const EquilibriumResult unloaded = analysis.solve();
  ASSERT_EQ(unloaded.status, SolverStatus::converged);
  EXPECT_NEAR(unloaded.interfaces[0].normal_force, kSlabWeight, 1e-8 * kSlabWeight);

  // A vertical load P at x = 0.5: the ground carries W + P, its centre of
  // pressure at x = 0.5 P / (W + P).
  const double press = 2000.0;
  const Structure pressed = pushed_slab(0.0, press, 0.5);
  analysis.update(pressed, {});
  const EquilibriumResult r = analysis.solve(true);
  EXPECT_EQ(analysis.symbolic_analyses(), 1);
  ASSERT_EQ(r.status, SolverStatus::converged);
  EXPECT_TRUE(r.stable);
  EXPECT_NEAR(r.interfaces[0].normal_force, kSlabWeight + press, 1e-8 * (kSlabWeight + press));
  EXPECT_NEAR(r.interfaces[0].center_of_pressure.x(), 0.5 * press / (kSlabWeight + press), 1e-7);
}

TEST(EquilibriumAnalysis, NewFrictionKeepsTheSymbolicAnalysis) {
  // Friction mu c must carry the push H: the tension that keeps vertical
  // balance is H / mu - W, i.e. infeasibility H / (mu W) - 1.
  const double push = 0.8 * kSlabWeight;
  const Structure s = pushed_slab(push);
  EquilibriumAnalysis analysis(s, with_friction(0.9));
  EXPECT_TRUE(analysis.solve().stable);
  for (double mu : {0.7, 0.5, 0.2}) {
    analysis.update(s, with_friction(mu));
    const EquilibriumResult r = analysis.solve();
    ASSERT_EQ(r.status, SolverStatus::converged) << mu;
    EXPECT_FALSE(r.stable);
    const double expected = 0.8 / mu - 1.0;
    EXPECT_NEAR(r.infeasibility, expected, 1e-7 * expected) << mu;
  }
  EXPECT_EQ(analysis.symbolic_analyses(), 1);
}

TEST(EquilibriumAnalysis, NewContactsAnalyseThePatternAgain) {
  const Structure one = pushed_slab(0.0);
  EquilibriumAnalysis analysis(one, {});
  EXPECT_TRUE(analysis.solve().stable);
  // A second slab on the first: new bodies, new contacts.
  Structure two = pushed_slab(0.0);
  two.add(box({1, 1, 0.1}, {0.2, 0, 0.15}));
  analysis.update(two, {});
  const EquilibriumResult r = analysis.solve(true);
  EXPECT_EQ(analysis.symbolic_analyses(), 2);
  ASSERT_EQ(r.status, SolverStatus::converged);
  const double top = 1 * 1 * 0.1 * 2400 * kGravity;
  ASSERT_EQ(r.interfaces.size(), 2u);
  double ground = 0.0, between = 0.0;
  for (const InterfaceForces& f : r.interfaces) (f.a == 0 || f.b == 0 ? ground : between) = f.normal_force;
  EXPECT_NEAR(ground, kSlabWeight + top, 1e-8 * (kSlabWeight + top));
  EXPECT_NEAR(between, top, 1e-8 * top);
}

TEST(EquilibriumAnalysis, ResponseReusesTheAnalysis) {
  // Weight sensitivity of the ground contact to the slab's own weight: one
  // newton more on the slab is one newton more on the ground.
  const Structure s = pushed_slab(0.0);
  EquilibriumAnalysis analysis(s, {});
  analysis.solve();
  ASSERT_TRUE(analysis.prepare_response());
  const EquilibriumProblem& problem = analysis.problem();
  Eigen::VectorXd more_weight = Eigen::VectorXd::Zero(problem.row_count);
  more_weight(problem.row_of_block[1] + problem.vertical_row()) = 1.0 / problem.weight_unit;
  const Eigen::VectorXd multipliers = analysis.solver().multiplier_response(more_weight);
  double normal_change = 0.0;
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    const Eigen::Vector4d dx = analysis.solver().group_response(problem, k, multipliers);
    normal_change += (dx(0) - dx(1)) * problem.weight_unit;
  }
  EXPECT_NEAR(normal_change, 1.0, 1e-6);
  EXPECT_EQ(analysis.symbolic_analyses(), 1);
}

TEST(AnalysisSequence, WarmStartsGiveTheColdAnswersInFewerIterations) {
  // Arches (centreline radius 5 m, no sliding) thinning towards their
  // minimum, t/R = 0.1071 for 16 voussoirs, as a thickness search meets
  // them: each answer is the cold analysis's, and starting from the last
  // optimum saves iterations.
  AnalysisSettings settings;
  settings.problem.friction = std::numeric_limits<double>::infinity();
  AnalysisSequence sequence(settings, true);
  int warm_iterations = 0, cold_iterations = 0;
  for (const double ratio : {0.3, 0.2, 0.15, 0.12, 0.11, 0.105}) {
    const Structure s = semicircular_arch(16, 5 * ratio);
    const EquilibriumResult warm = sequence.analyze(s);
    const EquilibriumResult cold = analyze_equilibrium(s, settings);
    ASSERT_EQ(warm.status, SolverStatus::converged) << ratio;
    EXPECT_EQ(warm.stable, ratio > 0.1071) << ratio;
    EXPECT_EQ(cold.stable, warm.stable) << ratio;
    EXPECT_NEAR(warm.penalty, cold.penalty, 1e-7 * (1.0 + cold.penalty)) << ratio;
    warm_iterations += warm.iterations;
    cold_iterations += cold.iterations;
  }
  EXPECT_LT(warm_iterations, cold_iterations);
  // Another number of blocks: no optimum is offered, the solve is cold.
  const Structure finer = semicircular_arch(24, 1.5);
  EXPECT_EQ(sequence.analyze(finer).iterations, analyze_equilibrium(finer, settings).iterations);
}
