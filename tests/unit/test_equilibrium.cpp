// Equilibrium analysis against closed-form statics.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/equilibrium.hpp"
#include "analysis/equilibrium_problem.hpp"
#include "analysis/interior_point.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "geometry/block_builders.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

Structure block_on_ground() {
  Structure s;
  s.add(box({3, 3, 0.2}, {0, 0, -0.1}), true);
  s.add(box({1, 1, 0.5}, {0, 0, 0.25}));
  return s;
}

// A 1 x 1 x 0.5 block on the ground and a second one on it, offset by dx.
Structure overhanging_stack(double dx) {
  Structure s = block_on_ground();
  s.add(box({1, 1, 0.5}, {dx, 0, 0.75}));
  return s;
}

// A 2 x 1 x 0.3 block resting on a slab inclined by `angle` about y, rotated
// about `turn` around z as a whole so that the slope need not follow x.
Structure block_on_incline(double angle, double turn = 0.0) {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({6, 3, 0.5}, {0, 0, -0.25})
                                          .rotated(Vec3::UnitY(), -angle, Vec3::Zero())
                                          .rotated(Vec3::UnitZ(), turn, Vec3::Zero())),
        true);
  s.add(std::make_shared<const Block>(make_box({2, 1, 0.3}, {0, 0, 0.15})
                                          .rotated(Vec3::UnitY(), -angle, Vec3::Zero())
                                          .rotated(Vec3::UnitZ(), turn, Vec3::Zero())));
  return s;
}

}  // namespace

TEST(Equilibrium, BlockOnGroundCarriesItsWeightEvenly) {
  const Structure s = block_on_ground();
  const EquilibriumResult r = analyze_equilibrium(s, {});
  ASSERT_EQ(r.status, SolverStatus::converged);
  EXPECT_TRUE(r.stable);
  EXPECT_EQ(r.infeasibility, 0.0);
  const double weight = 0.5 * 2400 * kGravity;
  ASSERT_EQ(r.interfaces.size(), 1u);
  EXPECT_NEAR(r.interfaces[0].normal_force, weight, 1e-7 * weight);
  EXPECT_NEAR(r.interfaces[0].tension, 0.0, 1e-7 * weight);
  EXPECT_LE((r.interfaces[0].resultant - Vec3(0, 0, weight)).norm(), 1e-7 * weight);
  EXPECT_LE(r.interfaces[0].center_of_pressure.head<2>().norm(), 1e-8);
  ASSERT_EQ(r.vertex_forces.size(), 4u);
  for (const Eigen::Vector4d& f : r.vertex_forces) {
    EXPECT_NEAR(f(0), weight / 4, 1e-7 * weight);  // the regularisation spreads it evenly
    EXPECT_NEAR(f(2), 0.0, 1e-7 * weight);
  }
  EXPECT_GT(r.factorizations, 0);
  EXPECT_EQ(r.factorizations, r.iterations);
}

TEST(Equilibrium, PointLoadMovesTheCentreOfPressure) {
  Structure s = block_on_ground();
  const double weight = 0.5 * 2400 * kGravity;
  // A downward load equal to the weight at x = 0.3 puts the resultant at x = 0.15.
  s.add_load({1, {0, 0, -weight}, {0.3, 0, 0.5}});
  const EquilibriumResult r = analyze_equilibrium(s, {});
  EXPECT_TRUE(r.stable);
  EXPECT_NEAR(r.interfaces[0].normal_force, 2 * weight, 1e-7 * weight);
  EXPECT_NEAR(r.interfaces[0].center_of_pressure.x(), 0.15, 1e-7);
}

TEST(Equilibrium, OverhangTipsPastTheEdge) {
  for (double dx : {0.0, 0.3, 0.49}) {
    EXPECT_TRUE(analyze_equilibrium(overhanging_stack(dx), {}).stable) << dx;
  }
  for (double dx : {0.51, 0.6, 0.9}) {
    const EquilibriumResult r = analyze_equilibrium(overhanging_stack(dx), {});
    EXPECT_EQ(r.status, SolverStatus::converged);
    EXPECT_FALSE(r.stable) << dx;
    EXPECT_GT(r.infeasibility, 0.0) << dx;
  }
  // Infeasibility grows with the overhang.
  const double a = analyze_equilibrium(overhanging_stack(0.6), {}).infeasibility;
  const double b = analyze_equilibrium(overhanging_stack(0.8), {}).infeasibility;
  EXPECT_LT(a, b);
}

TEST(Equilibrium, InclineSlidesWhenTangentExceedsFriction) {
  const double mu = 0.5;
  for (double turn : {0.0, 0.7}) {
    EXPECT_TRUE(analyze_equilibrium(block_on_incline(std::atan(0.49), turn), with_friction(mu)).stable);
    const EquilibriumResult r = analyze_equilibrium(block_on_incline(std::atan(0.51), turn), with_friction(mu));
    EXPECT_FALSE(r.stable) << turn;
    EXPECT_GT(r.infeasibility, 0.0);
  }
  // Without sliding the steep block stands.
  EXPECT_TRUE(analyze_equilibrium(block_on_incline(std::atan(0.9)), with_friction(INFINITY)).stable);
}

TEST(Equilibrium, SlidingNeedsTheTensionThatMakesUpTheFriction) {
  // A flat slab pushed sideways along its contact's edge direction: friction
  // mu c must carry the push H, so sum c = H / mu and the tension that keeps
  // vertical balance is H / mu - W, i.e. infeasibility H / (mu W) - 1.
  const double mu = 0.7;
  for (double ratio : {0.69, 0.8, 1.0, 2.0}) {
    Structure s;
    s.add(box({3, 3, 0.2}, {0, 0, -0.1}), true);
    s.add(std::make_shared<const Block>(make_box({2, 1, 0.1}, {0, 0, 0.05})));
    const double weight = 2 * 1 * 0.1 * 2400 * kGravity;
    s.add_load({1, {ratio * weight, 0, 0}, {0, 0, 0.05}});
    const EquilibriumResult r = analyze_equilibrium(s, with_friction(mu));
    if (ratio < mu) {
      EXPECT_EQ(r.status, SolverStatus::converged);
      EXPECT_TRUE(r.stable);
      continue;
    }
    EXPECT_EQ(r.status, SolverStatus::converged) << ratio;
    EXPECT_FALSE(r.stable);
    const double expected = ratio / mu - 1.0;
    EXPECT_NEAR(r.infeasibility, expected, 1e-7 * expected) << ratio;
  }
}

TEST(Equilibrium, NoEquilibriumAtAllIsUnstableWithInfiniteInfeasibility) {
  // Without friction nothing can resist a sideways push, tension or not.
  Structure s = block_on_ground();
  s.add_load({1, {500, 0, 0}, {0, 0, 0.25}});
  const EquilibriumResult r = analyze_equilibrium(s, with_friction(0.0));
  EXPECT_EQ(r.status, SolverStatus::numerical_error);
  EXPECT_FALSE(r.stable);
  EXPECT_TRUE(std::isinf(r.infeasibility));
}

TEST(Equilibrium, FreeBlockTouchingNothingIsUnstable) {
  Structure s = block_on_ground();
  s.add(box({1, 1, 1}, {10, 0, 5}));
  const EquilibriumResult r = analyze_equilibrium(s, {});
  EXPECT_FALSE(r.stable);
  ASSERT_EQ(r.floating_blocks.size(), 1u);
  EXPECT_EQ(r.floating_blocks[0], 2);
  EXPECT_TRUE(std::isinf(r.infeasibility));
}

TEST(Equilibrium, BlockTouchingOnlyAtAnEdgeIsUnstable) {
  // A cube standing on one of its edges in the middle of the block below:
  // a line contact, not a face, so no interface, and it is reported as
  // resting on nothing (edge-to-face contacts are not modelled).
  Structure s = block_on_ground();
  s.add(std::make_shared<const Block>(
      make_box({0.5, 0.5, 0.5}, {0, 0, 0}).rotated(Vec3::UnitY(), M_PI / 4, Vec3::Zero())
          .translated({0.2, 0, 0.5 + 0.25 * std::sqrt(2.0)})));
  const EquilibriumResult r = analyze_equilibrium(s, {});
  EXPECT_EQ(s.interfaces()->size(), 1u);
  EXPECT_FALSE(r.stable);
  ASSERT_EQ(r.floating_blocks.size(), 1u);
  EXPECT_EQ(r.floating_blocks[0], 2);
}

TEST(Equilibrium, UnitsAndRigidMotionDoNotChangeTheAnswer) {
  const EquilibriumResult reference = analyze_equilibrium(overhanging_stack(0.7), {});
  for (double scale : {1e-3, 1e3}) {
    Structure scaled;
    const Structure s = overhanging_stack(0.7);
    for (int i = 0; i < s.size(); ++i) {
      std::vector<Vec3> vertices = s.block(i).vertices();
      for (Vec3& p : vertices) p *= scale;
      scaled.add(std::make_shared<const Block>(vertices, s.block(i).faces()), s.is_support(i));
    }
    const EquilibriumResult r = analyze_equilibrium(scaled, {});
    EXPECT_FALSE(r.stable);
    EXPECT_NEAR(r.infeasibility, reference.infeasibility, 1e-6 * reference.infeasibility) << scale;
  }
  Structure moved;
  const Structure s = overhanging_stack(0.7);
  for (int i = 0; i < s.size(); ++i) {
    moved.add(std::make_shared<const Block>(
                  s.block(i).rotated(Vec3::UnitZ(), 0.4, Vec3(1, 2, 0)).translated({50, -20, 3})),
              s.is_support(i));
  }
  const EquilibriumResult r = analyze_equilibrium(moved, {});
  EXPECT_NEAR(r.infeasibility, reference.infeasibility, 1e-6 * reference.infeasibility);
}

TEST(Equilibrium, PlanarEquationsGiveTheSameAnswer) {
  // The overhanging stack is an extrusion along y with in-plane loads: its
  // 3-equation planar problem has the same optimum as the 6-equation one.
  for (double dx : {0.3, 0.7}) {
    Structure s = overhanging_stack(dx);
    s.add_load({2, {-300, 0, -500}, {dx + 0.2, 0, 1.0}});
    const EquilibriumResult spatial = analyze_equilibrium(s, {});
    s.set_planar(true);
    const EquilibriumProblem problem = build_equilibrium_problem(s, {});
    EXPECT_EQ(problem.block_rows, 3);
    EXPECT_EQ(problem.row_count, 6);
    const EquilibriumResult planar = analyze_equilibrium(s, {});
    EXPECT_EQ(planar.stable, spatial.stable) << dx;
    EXPECT_NEAR(planar.infeasibility, spatial.infeasibility, 1e-6 * (1 + spatial.infeasibility));
    EXPECT_NEAR(planar.objective, spatial.objective, 1e-6 * std::abs(spatial.objective));
  }
}

TEST(Equilibrium, PlanarStructuresRejectOutOfPlaneLoads) {
  Structure s = overhanging_stack(0.2);
  s.set_planar(true);
  s.add_load({1, {0, 100, 0}, {0, 0, 0.25}});
  EXPECT_THROW(analyze_equilibrium(s, {}), InvalidArgument);
  Structure off_plane = overhanging_stack(0.2);
  off_plane.set_planar(true);
  off_plane.add_load({1, {100, 0, 0}, {0, 0.3, 0.25}});
  EXPECT_THROW(analyze_equilibrium(off_plane, {}), InvalidArgument);
}

TEST(Equilibrium, WarmStartConverges) {
  const Structure s = overhanging_stack(0.7);
  const EquilibriumResult cold = analyze_equilibrium(s, {});
  const EquilibriumResult warm = analyze_equilibrium(s, {}, &cold);
  EXPECT_EQ(warm.status, SolverStatus::converged);
  EXPECT_NEAR(warm.objective, cold.objective, 1e-8 * std::abs(cold.objective));
}

TEST(Equilibrium, AnInterruptedSolveCarriesNoVerdict) {
  // Start within the inaccurate tolerance of the optimum of a stable stack,
  // then interrupt: the answer would pass as inaccurate and stable, but an
  // interrupted analysis must say so and carry no verdict.
  const Structure s = overhanging_stack(0.3);
  AnalysisSettings rough;
  rough.solver.tolerance = 1e-6;
  const EquilibriumResult near_optimum = analyze_equilibrium(s, rough);
  ASSERT_TRUE(near_optimum.stable);
  interrupt_requested() = true;
  const EquilibriumResult r = analyze_equilibrium(s, {}, &near_optimum);
  interrupt_requested() = false;
  EXPECT_EQ(r.status, SolverStatus::interrupted);
  EXPECT_FALSE(r.stable);
  EXPECT_TRUE(std::isinf(r.infeasibility));
}

TEST(Equilibrium, AnAnswerShortOfTheToleranceIsTheIterateItsFiguresDescribe) {
  // A tolerance of zero cannot be met: the solve runs on to the rounding
  // floor, where the error no longer falls every iteration, and stops once
  // the most accurate iterate is 8 iterations old. That iterate is restored
  // by undoing the step taken from it; the figures reported with it (from
  // the iteration it was reached) must be those of the returned unknowns.
  for (const Structure& s : {overhanging_stack(0.7), semicircular_arch(16, 0.5)}) {
    const EquilibriumProblem problem = build_equilibrium_problem(s, {});
    EquilibriumSolver solver(problem);
    InteriorPointSettings settings;
    settings.tolerance = 0.0;
    InteriorPointSolution solution;
    const InteriorPointInfo info = solver.solve(problem, settings, solution, false);
    ASSERT_EQ(info.status, SolverStatus::inaccurate);
    const Eigen::Index m = solution.w.size();
    ASSERT_GT(m, 0);
    EXPECT_NEAR(solution.w.dot(solution.z) / static_cast<double>(m), info.complementarity,
                1e-9 * info.complementarity);
    // Balance rows: |A x - b| is part of the reported primal residual.
    Eigen::VectorXd balance = -problem.rhs;
    for (size_t k = 0; k < problem.groups.size(); ++k) {
      problem.add_effect(problem.groups[k], solution.x.segment<4>(4 * static_cast<Eigen::Index>(k)), balance);
    }
    EXPECT_LE(balance.lpNorm<Eigen::Infinity>(), info.primal_residual * (1 + 1e-6) + 1e-15);
  }
}

TEST(Equilibrium, ARefittedSolverSolvesAsANewOne) {
  // Three blocks stacked on the ground, each contact a pair of bodies in
  // the pattern. An extra vertical force group (the weight group of
  // necessary weights), moved from the top block to the middle one, adds
  // only to a diagonal block: the refitted solver takes it without a new
  // analysis and finds what a solver built for it finds.
  Structure s = overhanging_stack(0.2);
  s.add(box({1, 1, 0.5}, {0.3, 0, 1.25}));
  EquilibriumProblem problem = build_equilibrium_problem(s, {});
  ForceGroup lift;
  lift.kind = GroupKind::weight;
  lift.row_a = problem.row_of_block[3];
  lift.set_alone_on_a(problem.vertical_row(), 0, 1.0);
  problem.groups.push_back(lift);
  EquilibriumSolver solver(problem);
  InteriorPointSolution first;
  ASSERT_EQ(solver.solve(problem, {}, first).status, SolverStatus::converged);

  problem.groups.back().row_a = problem.row_of_block[2];
  EXPECT_FALSE(solver.fits(problem));
  ASSERT_TRUE(solver.refit(problem));
  EXPECT_TRUE(solver.fits(problem));
  EquilibriumSolver fresh(problem);
  InteriorPointSolution refitted, reference;
  const InteriorPointInfo info = solver.solve(problem, {}, refitted);
  const InteriorPointInfo reference_info = fresh.solve(problem, {}, reference);
  ASSERT_EQ(info.status, SolverStatus::converged);
  EXPECT_EQ(info.iterations, reference_info.iterations);
  EXPECT_NEAR(info.objective, reference_info.objective, 1e-12 * std::abs(reference_info.objective));
  EXPECT_LE((refitted.x - reference.x).lpNorm<Eigen::Infinity>(), 1e-9);

  // A group between the top block and the ground's neighbour it does not
  // touch (block 1, under the middle one) needs an entry the pattern lacks.
  EquilibriumProblem coupled = problem;
  coupled.groups.back().row_b = problem.row_of_block[1];
  coupled.groups.back().row_a = problem.row_of_block[3];
  EXPECT_FALSE(solver.refit(coupled));
  EXPECT_TRUE(solver.fits(problem)) << "a refit that fails leaves the solver as it was";
}

TEST(Equilibrium, PlanarTwinVerticesAreSolvedAsOneGroup) {
  // A planar arch's joints are rectangles across its depth: each vertex at
  // y = -0.5 has a twin at y = 0.5 with the same in-plane effect, and the
  // solver takes each pair as one group. Solved vertex by vertex (no merge)
  // the QP is the same, with one optimum (the objective is strictly
  // convex), so the merged solve split back into twins must be it.
  Structure arch = semicircular_arch(16, 0.5);
  arch.set_planar(true);
  const EquilibriumProblem problem = build_equilibrium_problem(arch, {});
  ASSERT_EQ(problem.contact_vertex_count, 4 * 17);  // 17 joints of 4 vertices
  InteriorPointSettings separate;
  separate.merge_twins = false;
  EquilibriumSolver solver(problem), reference_solver(problem);
  InteriorPointSolution twin_solution, reference;
  const InteriorPointInfo info = solver.solve(problem, {}, twin_solution);
  const InteriorPointInfo reference_info = reference_solver.solve(problem, separate, reference);
  ASSERT_EQ(info.status, SolverStatus::converged);
  ASSERT_EQ(reference_info.status, SolverStatus::converged);
  EXPECT_EQ(info.groups, 2 * 17);
  EXPECT_EQ(reference_info.groups, 4 * 17);
  EXPECT_NEAR(info.objective, reference_info.objective, 1e-9 * std::abs(reference_info.objective));
  ASSERT_EQ(twin_solution.x.size(), reference.x.size());
  ASSERT_EQ(twin_solution.z.size(), reference.z.size());
  // x is unique, but the objective holds the statically indeterminate
  // forces only by the regularisation h = force_weight / n per squared unit
  // of force, so stopping at a duality gap g leaves them known to
  // sqrt(2 g / h): 5.7e-3 (scaled) for the 16 voussoirs.
  const double known_to = std::sqrt(2.0 * InteriorPointSettings{}.tolerance * 16 / EquilibriumOptions{}.force_weight);
  EXPECT_LE((twin_solution.x - reference.x).lpNorm<Eigen::Infinity>(), known_to);
  // Each twin gets half the group's multipliers: with them the split answer
  // is stationary for the problem itself, vertex by vertex (the multipliers
  // are not unique where a vertex has no compression and every friction row
  // is active, so they are checked through this, not one by one).
  const std::vector<int> first_row = problem.inequality_starts();
  for (int k = 0; k < static_cast<int>(problem.groups.size()); ++k) {
    const ForceGroup& group = problem.groups[k];
    const GroupRules& rules = problem.rules_of(group);
    const Eigen::Vector4d xk = twin_solution.x.segment<4>(4 * k);
    const Eigen::Vector4d stationarity =
        rules.hessian.cwiseProduct(xk) + rules.linear - problem.reaction(group, twin_solution.y) -
        rules.rows.transpose() * twin_solution.z.segment(first_row[k], rules.rows.rows());
    EXPECT_LE(stationarity.lpNorm<Eigen::Infinity>(), 1e-9) << k;
  }
  // The response to more weight on the crown voussoir, at the same answer,
  // vertex by vertex and merged (the twins' Phi is the group's over two).
  // At different answers it would differ: it holds the active set, and the
  // multipliers of rows at the edge of it are not unique.
  ASSERT_TRUE(solver.prepare_response(problem, twin_solution));
  ASSERT_TRUE(reference_solver.prepare_response(problem, twin_solution, false));
  Eigen::VectorXd more = Eigen::VectorXd::Zero(problem.row_count);
  more(problem.row_of_block[8] + problem.vertical_row()) = 1.0;
  const Eigen::VectorXd y = solver.multiplier_response(more);
  const Eigen::VectorXd y_reference = reference_solver.multiplier_response(more);
  for (int k = 0; k < problem.contact_vertex_count; ++k) {
    const Eigen::Vector4d dx = solver.group_response(problem, k, y);
    const Eigen::Vector4d dx_reference = reference_solver.group_response(problem, k, y_reference);
    EXPECT_LE((dx - dx_reference).lpNorm<Eigen::Infinity>(),
              1e-6 * (1.0 + dx_reference.lpNorm<Eigen::Infinity>())) << k;
  }
  // The same arch solved in 3D, where the twins' moments about x differ and
  // nothing merges, has the same optimum: the pair carries equal forces.
  Structure general = arch;
  general.set_planar(false);
  const EquilibriumResult result_3d = analyze_equilibrium(general, {});
  ASSERT_EQ(result_3d.status, SolverStatus::converged);
  EXPECT_NEAR(info.objective, result_3d.objective, 1e-8 * std::abs(result_3d.objective));
}

TEST(Equilibrium, BadSettingsAreRejected) {
  AnalysisSettings settings;
  settings.problem.friction_sides = 2;
  EXPECT_THROW(analyze_equilibrium(block_on_ground(), settings), InvalidArgument);
  settings = {};
  settings.problem.friction = -1;
  EXPECT_THROW(analyze_equilibrium(block_on_ground(), settings), InvalidArgument);
}
