// The analysis object: setup once, update loads, friction or geometry, and
// solve again, each answer checked against closed-form statics.
#include <dirent.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>

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

// Where the iterate tells the optimum's active set (interior_point.cpp's
// polish), the solve finishes on it, to rounding rather than to the
// solver's tolerance; a warm start from that answer begins at the
// interior iterate before it (the polished one is a vertex of the optimal
// face) and gives the cold answer again. Reference: a block set off
// (0.2, 0.1) m on another, both on the ground. With no horizontal load
// the optimum is the least-norm corner compressions (the force_weight
// term, equilibrium_problem.hpp) that balance each joint's resultant W at
// (e_x, e_y) from the joint's centre, with corners at (+-a, +-b):
// c = W / 4 (1 + e_x x / a^2 + e_y y / b^2).
TEST(EquilibriumAnalysis, AnOffsetBlockIsPolishedToItsLeastNormCorners) {
  Structure s;
  s.add(box({3, 3, 0.2}, {0, 0, -0.1}), true);
  s.add(box({1, 1, 0.4}, {0, 0, 0.2}));
  s.add(box({1, 1, 0.4}, {0.2, 0.1, 0.6}));
  const double weight = 1 * 1 * 0.4 * 2400 * kGravity;  // N, each block
  EquilibriumAnalysis analysis(s, {});
  const EquilibriumResult cold = analysis.solve();
  ASSERT_EQ(cold.status, SolverStatus::converged);
  EXPECT_GT(analysis.solution().interior.x.size(), 0) << "not polished";
  ASSERT_EQ(cold.interfaces.size(), 2u);
  ASSERT_EQ(cold.vertex_forces.size(), 8u);  // four corners a joint
  for (size_t v = 0; v < cold.vertex_forces.size(); ++v) {
    const InterfaceForces& joint = cold.interfaces[cold.vertex_interface[v]];
    const bool top = std::min(joint.a, joint.b) == 1;
    // The joint's centre, half sizes and resultant's place (m), and load (N).
    const Vec3 centre = top ? Vec3(0.1, 0.05, 0.4) : Vec3(0, 0, 0);
    const double a = top ? 0.4 : 0.5, b = top ? 0.45 : 0.5;
    const double ex = (top ? 0.2 : 0.1) - centre.x(), ey = (top ? 0.1 : 0.05) - centre.y();
    const double load = top ? weight : 2 * weight;
    const Vec3 corner = cold.vertex_positions[v] - centre;
    const double expected = load / 4 * (1 + ex * corner.x() / (a * a) + ey * corner.y() / (b * b));
    EXPECT_NEAR(cold.vertex_forces[v](0), expected, 1e-11 * weight) << "vertex " << v << " at " << corner.transpose();
  }
  const EquilibriumResult warm = analysis.solve(true);
  ASSERT_EQ(warm.status, SolverStatus::converged);
  for (size_t v = 0; v < cold.vertex_forces.size(); ++v) {
    EXPECT_NEAR(warm.vertex_forces[v](0), cold.vertex_forces[v](0), 1e-8 * weight);
  }
}

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

namespace {

// The threads of this process (each test runs in a process of its own).
int thread_count() {
  int count = 0;
  if (DIR* dir = ::opendir("/proc/self/task")) {
    while (const dirent* entry = ::readdir(dir)) count += entry->d_name[0] != '.';
    ::closedir(dir);
  }
  return count;
}

// The largest difference of two solutions' unknowns, relative to the
// larger unknown (scaled units: forces of a mean body weight).
double relative_difference(const Eigen::VectorXd& x, const Eigen::VectorXd& y) {
  return (x - y).lpNorm<Eigen::Infinity>() / std::max(1.0, y.lpNorm<Eigen::Infinity>());
}

}  // namespace

TEST(EquilibriumAnalysis, NewPointLoadsAloneGiveTheFreshAnalysis) {
  // An arch with a push and a press on voussoir 6: update_loads changes
  // only the right-hand side, which is then the fresh build's to the bit,
  // and so is every iterate.
  const Structure plain = semicircular_arch(16, 1.0);
  Structure loaded = semicircular_arch(16, 1.0);
  const Vec3 at = loaded.block(5).centroid() + Vec3(0.1, 0.0, 0.05);
  loaded.add_load({5, {4000, 0, -30000}, at});
  const AnalysisSettings settings = with_friction(0.7);
  EquilibriumAnalysis analysis(plain, settings);
  ASSERT_TRUE(analysis.solve().stable);
  analysis.update_loads(loaded);
  const EquilibriumResult reused = analysis.solve();
  EquilibriumAnalysis fresh(loaded, settings);
  const EquilibriumResult expected = fresh.solve();
  EXPECT_EQ(analysis.symbolic_analyses(), 1);
  ASSERT_EQ(reused.status, SolverStatus::converged);
  EXPECT_EQ(reused.stable, expected.stable);
  EXPECT_EQ(reused.iterations, expected.iterations);
  EXPECT_EQ(analysis.problem().rhs, fresh.problem().rhs);
  EXPECT_LE(relative_difference(analysis.solution().x, fresh.solution().x), 1e-10);
  ASSERT_EQ(reused.interfaces.size(), expected.interfaces.size());
  const double weight = analysis.problem().total_weight;
  for (size_t i = 0; i < expected.interfaces.size(); ++i) {
    EXPECT_NEAR(reused.interfaces[i].normal_force, expected.interfaces[i].normal_force, 1e-10 * weight) << i;
  }
  // Warm from the unloaded optimum: the same answer to the solver's tolerance.
  analysis.update_loads(plain);
  analysis.solve();
  analysis.update_loads(loaded);
  const EquilibriumResult warm = analysis.solve(true);
  ASSERT_EQ(warm.status, SolverStatus::converged);
  EXPECT_NEAR(warm.penalty, expected.penalty, 1e-8 * (1.0 + expected.penalty));
  EXPECT_EQ(analysis.symbolic_analyses(), 1);
}

TEST(EquilibriumAnalysis, HeavierBlockByTheRightHandSideAlone) {
  // Voussoir 8 half as heavy again: set_rhs adds 0.5 W to its vertical
  // row, the same QP as a fresh analysis of the arch with 0.5 W pressing
  // down at its centroid (point loads keep the units), to rounding.
  const Structure plain = semicircular_arch(16, 1.0);
  const int j = 7;
  const double extra = 0.5 * plain.block(j).mass() * kGravity;  // N
  Structure heavier = semicircular_arch(16, 1.0);
  heavier.add_load({j, {0, 0, -extra}, heavier.block(j).centroid()});
  EquilibriumAnalysis analysis(plain, {});
  ASSERT_TRUE(analysis.solve().stable);
  const EquilibriumProblem& problem = analysis.problem();
  Eigen::VectorXd rhs = problem.rhs;
  rhs(problem.row_of_block[j] + problem.vertical_row()) += extra / problem.weight_unit;
  analysis.set_rhs(rhs);
  const EquilibriumResult reused = analysis.solve();
  EquilibriumAnalysis fresh(heavier, {});
  const EquilibriumResult expected = fresh.solve();
  EXPECT_EQ(analysis.symbolic_analyses(), 1);
  ASSERT_EQ(reused.status, SolverStatus::converged);
  EXPECT_EQ(reused.stable, expected.stable);
  EXPECT_LE((analysis.problem().rhs - fresh.problem().rhs).lpNorm<Eigen::Infinity>(), 1e-14);
  EXPECT_LE(relative_difference(analysis.solution().x, fresh.solution().x), 1e-10);
  // Another length is refused.
  EXPECT_THROW(analysis.set_rhs(Eigen::VectorXd::Zero(problem.row_count + 1)), std::invalid_argument);
}

TEST(EquilibriumAnalysis, AGroupChangedInPlaceKeepsTheSymbolicAnalysis) {
  // From a problem built by the caller: the slab's ground contact carries
  // its weight; a corner's effect cut off and then restored changes the
  // QP, not the pattern.
  const Structure s = pushed_slab(0.0);
  EquilibriumProblem problem = build_equilibrium_problem(s, {});
  EquilibriumAnalysis analysis(std::move(problem), {});
  EXPECT_THROW(analysis.solve(), std::logic_error);  // no structure to report on
  ASSERT_EQ(analysis.solve_qp(analysis.settings().solver).status, SolverStatus::converged);
  const Eigen::VectorXd before = analysis.solution().x;
  const ForceGroup original = analysis.problem().groups[0];
  ForceGroup cut = original;
  cut.on_b.setZero();  // and so on_a()
  analysis.set_group(0, cut);
  ASSERT_EQ(analysis.solve_qp(analysis.settings().solver).status, SolverStatus::converged);
  // The other three corners carry the slab (a vertex that carries nothing
  // keeps only the interior point's rounding of a force).
  EXPECT_GT(relative_difference(analysis.solution().x, before), 0.1);
  EXPECT_LT(analysis.solution().x(0), 1e-3);
  analysis.set_group(0, original);
  ASSERT_EQ(analysis.solve_qp(analysis.settings().solver).status, SolverStatus::converged);
  EXPECT_LE(relative_difference(analysis.solution().x, before), 1e-12);
  EXPECT_EQ(analysis.symbolic_analyses(), 1);
  ForceGroup other_kind = original;
  other_kind.kind = GroupKind::weight;
  EXPECT_THROW(analysis.set_group(0, other_kind), std::invalid_argument);
}

TEST(EquilibriumAnalysis, OneCoreMeansNoHelperThreads) {
  // A column of 400 blocks: a normal matrix of 2,400 rows, which on all
  // cores is factorised in two halves side by side (a helper thread,
  // core/sparse_cholesky.hpp), on one core whole.
  Structure column;
  column.add(box({2, 2, 0.5}, {0, 0, -0.25}), true);
  for (int k = 0; k < 400; ++k) column.add(box({1, 1, 0.5}, {0, 0, 0.25 + 0.5 * k}));
  EquilibriumAnalysis warm_up(column, {}, SolverCores::one);  // libraries' own threads, if any
  ASSERT_TRUE(warm_up.solve().stable);
  const int threads = thread_count();
  EquilibriumAnalysis one(column, {}, SolverCores::one);
  EXPECT_EQ(one.cores(), SolverCores::one);
  const EquilibriumResult on_one = one.solve();
  // A new pattern (a block more) is analysed on one core again.
  Structure taller = column;
  taller.add(box({1, 1, 0.5}, {0, 0, 0.25 + 0.5 * 400}));
  one.update(taller, {});
  EXPECT_EQ(one.symbolic_analyses(), 2);
  EXPECT_TRUE(one.solve().stable);
  EXPECT_EQ(thread_count(), threads);
  if (std::thread::hardware_concurrency() >= 2) {
    EquilibriumAnalysis all(column, {});
    EXPECT_EQ(all.cores(), SolverCores::all);
    const EquilibriumResult on_all = all.solve();
    EXPECT_GT(thread_count(), threads);
    EXPECT_EQ(on_all.stable, on_one.stable);
    EXPECT_NEAR(on_all.penalty, on_one.penalty, 1e-9 * (1.0 + on_one.penalty));
  }
}
