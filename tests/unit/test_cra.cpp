// Coupled rigid-block analysis (cra.hpp) against closed-form statics:
// stacks, symmetric supports, a block on an incline, a block past its
// support's edge.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/cra.hpp"
#include "core/error.hpp"
#include "core/interrupt.hpp"
#include "geometry/block_builders.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

AnalysisSettings cra_settings(AnalysisMethod method, double mu = 0.6) {
  AnalysisSettings settings;
  settings.method = method;
  settings.problem.friction = mu;
  return settings;
}

// Ground, then `count` 1 x 1 x 0.5 blocks, block k offset by k * dx.
Structure stack(int count, double dx) {
  Structure s;
  s.add(box({3, 3, 0.2}, {0, 0, -0.1}), true);
  for (int k = 0; k < count; ++k) s.add(box({1, 1, 0.5}, {k * dx, 0, 0.25 + 0.5 * k}));
  return s;
}

// A 2 x 1 x 0.3 block on a slab inclined by `angle` about y (as in
// test_equilibrium.cpp): the slope falls towards +x.
Structure block_on_incline(double angle) {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({6, 3, 0.5}, {0, 0, -0.25}).rotated(Vec3::UnitY(), -angle, Vec3::Zero())),
        true);
  s.add(std::make_shared<const Block>(make_box({2, 1, 0.3}, {0, 0, 0.15}).rotated(Vec3::UnitY(), -angle, Vec3::Zero())));
  return s;
}

double weight_of(const Structure& s, int block) { return s.block(block).mass() * kGravity; }

// The interface between blocks a and b (either order), or -1.
int interface_between(const EquilibriumResult& r, int a, int b) {
  for (size_t i = 0; i < r.interfaces.size(); ++i) {
    const InterfaceForces& f = r.interfaces[i];
    if ((f.a == a && f.b == b) || (f.a == b && f.b == a)) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace

class CraMethods : public ::testing::TestWithParam<AnalysisMethod> {};

INSTANTIATE_TEST_SUITE_P(Cra, CraMethods, ::testing::Values(AnalysisMethod::cra, AnalysisMethod::cra_penalty),
                         [](const auto& info) { return std::string(kAnalysisMethodNames.name(info.param)); });

TEST_P(CraMethods, TwoStackedBoxesCarryTheirWeightUnderTheirCentroids) {
  const Structure s = stack(2, 0.2);
  const EquilibriumResult r = analyze_equilibrium(s, cra_settings(GetParam()));
  ASSERT_EQ(r.status, SolverStatus::converged);
  EXPECT_TRUE(r.stable);
  EXPECT_EQ(r.infeasibility, 0.0);
  EXPECT_EQ(r.method, GetParam());
  EXPECT_GT(r.iterations, 0);
  const double w = weight_of(s, 1);
  const int top = interface_between(r, 1, 2), bottom = interface_between(r, 0, 1);
  ASSERT_GE(top, 0);
  ASSERT_GE(bottom, 0);
  // Each joint carries the weight above it, its centre of pressure under
  // the centroid of what it carries (x = 0.2, and 0.1 for both blocks).
  EXPECT_NEAR(r.interfaces[top].normal_force, w, 1e-6 * w);
  EXPECT_NEAR(r.interfaces[bottom].normal_force, 2 * w, 2e-6 * w);
  EXPECT_NEAR(r.interfaces[top].center_of_pressure.x(), 0.2, 1e-6);
  EXPECT_NEAR(r.interfaces[top].center_of_pressure.y(), 0.0, 1e-6);
  EXPECT_NEAR(r.interfaces[bottom].center_of_pressure.x(), 0.1, 1e-6);
  EXPECT_NEAR(r.interfaces[bottom].tension, 0.0, 1e-6 * w);
  // No friction is needed, and none is used.
  EXPECT_LE(r.interfaces[top].resultant.head<2>().norm(), 1e-6 * w);
  ASSERT_EQ(r.displacements.size(), 3u);
  EXPECT_EQ(r.displacements[0].translation, Vec3::Zero());  // the support
}

TEST_P(CraMethods, ThreeBlocksColumn) {
  const Structure s = stack(3, 0.0);
  const EquilibriumResult r = analyze_equilibrium(s, cra_settings(GetParam()));
  ASSERT_EQ(r.status, SolverStatus::converged);
  EXPECT_TRUE(r.stable);
  const double w = weight_of(s, 1);
  for (int k = 0; k < 3; ++k) {
    const int i = interface_between(r, k, k + 1);
    ASSERT_GE(i, 0);
    EXPECT_NEAR(r.interfaces[i].normal_force, (3 - k) * w, 1e-6 * w) << "joint " << k;
    EXPECT_NEAR(r.interfaces[i].center_of_pressure.head<2>().norm(), 0.0, 1e-6) << "joint " << k;
  }
}

TEST_P(CraMethods, CubeOnFourCornersCarriesAQuarterAtEach) {
  // compas_cra's tests/test_cra.py: a unit cube on another, 0.25 of its
  // weight at each corner (by symmetry, and the least sum of squares).
  Structure s;
  s.add(box({1, 1, 1}, {0, 0, 0}), true);
  s.add(box({1, 1, 1}, {0, 0, 1}));
  const EquilibriumResult r = analyze_equilibrium(s, cra_settings(GetParam()));
  ASSERT_EQ(r.status, SolverStatus::converged);
  EXPECT_TRUE(r.stable);
  const double w = weight_of(s, 1);
  ASSERT_EQ(r.vertex_forces.size(), 4u);
  for (const Eigen::Vector4d& f : r.vertex_forces) {
    EXPECT_NEAR(f(0) - f(1), 0.25 * w, 1e-6 * w);
    EXPECT_NEAR(f.tail<2>().norm(), 0.0, 1e-6 * w);
  }
  // Compressed corners sit at the overlap: the block sinks by eps L.
  const double sink = -r.displacements[1].translation.z();
  EXPECT_GT(sink, 0.0);
  EXPECT_LE(sink, 1e-3 * 2.0);  // well within d_bnd of the block size
}

TEST(Cra, InclineBelowFrictionAngleStandsOnFrictionWSinTheta) {
  const double angle = 20.0 * M_PI / 180.0;  // tan 20 deg = 0.36 < 0.6 cos 45 deg
  const Structure s = block_on_incline(angle);
  const double w = weight_of(s, 1);
  for (const AnalysisMethod method : {AnalysisMethod::cra, AnalysisMethod::cra_penalty}) {
    SCOPED_TRACE(kAnalysisMethodNames.name(method));
    const EquilibriumResult r = analyze_equilibrium(s, cra_settings(method));
    ASSERT_EQ(r.status, SolverStatus::converged);
    EXPECT_TRUE(r.stable);
    ASSERT_EQ(r.interfaces.size(), 1u);
    const InterfaceForces& f = r.interfaces[0];
    const double friction = (f.resultant - f.normal_force * (*s.interfaces())[0].normal).norm();
    EXPECT_NEAR(std::abs(f.normal_force), w * std::cos(angle), 1e-6 * w);
    EXPECT_NEAR(friction, w * std::sin(angle), 1e-6 * w);
    // The force on the block balances its weight.
    const double on_block = f.b == 1 ? 1.0 : -1.0;
    EXPECT_NEAR((on_block * f.resultant - Vec3(0, 0, w)).norm(), 0.0, 1e-6 * w);
  }
}

TEST(Cra, InclineSteeperThanFrictionAngleSlidesDownTheSlope) {
  const double angle = 40.0 * M_PI / 180.0;  // tan 40 deg = 0.84 > 0.6
  const Structure s = block_on_incline(angle);
  const EquilibriumResult hard = analyze_equilibrium(s, cra_settings(AnalysisMethod::cra));
  EXPECT_FALSE(hard.stable);
  EXPECT_NE(hard.status, SolverStatus::converged);
  EXPECT_EQ(hard.status, SolverStatus::infeasible);
  // The penalty form answers with tension.
  const EquilibriumResult r = analyze_equilibrium(s, cra_settings(AnalysisMethod::cra_penalty));
  ASSERT_TRUE(r.status == SolverStatus::converged || r.status == SolverStatus::inaccurate) << status_name(r.status);
  EXPECT_FALSE(r.stable);
  EXPECT_GT(r.infeasibility, 1e-3);
  EXPECT_GT(r.interfaces[0].tension, 0.01 * weight_of(s, 1));
  // The slab's surface rises towards +x: down the slope is (-cos, 0, -sin).
  const Vec3 down(-std::cos(angle), 0.0, -std::sin(angle));
  const Vec3 t = r.displacements[1].translation;
  EXPECT_GT(t.dot(down), 0.5 * t.norm());
  EXPECT_GT(t.dot(down), 0.0);
}

TEST(Cra, BlockPastItsSupportsEdgeFalls) {
  // compas_cra's tests/test_cra_penalty.py: a unit cube shifted by 0.75 on
  // another (its centroid 0.25 past the edge); the penalty answer still
  // carries the whole weight, with tension.
  Structure s;
  s.add(box({1, 1, 1}, {0, 0, 0}), true);
  s.add(box({1, 1, 1}, {0.75, 0, 1}));
  const double w = weight_of(s, 1);
  const EquilibriumResult hard = analyze_equilibrium(s, cra_settings(AnalysisMethod::cra));
  EXPECT_FALSE(hard.stable);
  EXPECT_EQ(hard.status, SolverStatus::infeasible);
  const EquilibriumResult r = analyze_equilibrium(s, cra_settings(AnalysisMethod::cra_penalty));
  ASSERT_EQ(r.status, SolverStatus::converged);
  EXPECT_FALSE(r.stable);
  ASSERT_EQ(r.interfaces.size(), 1u);
  // Moments about the support's edge (x = 0.5): the weight 0.25 past it is
  // held by tension T at the contact's far side 0.25 before it, T = W, and
  // compression 2 W at the edge.
  EXPECT_NEAR(r.interfaces[0].normal_force, w, 1e-6 * w);
  EXPECT_NEAR(r.interfaces[0].tension, w, 1e-5 * w);
  EXPECT_NEAR(r.interfaces[0].compression, 2 * w, 1e-5 * w);
  EXPECT_NEAR(r.infeasibility, 1.0, 1e-5);  // T over the weight
}

TEST(Cra, FloatingBlockIsUnstable) {
  Structure s = stack(1, 0.0);
  s.add(box({1, 1, 0.5}, {5, 0, 3}));
  const EquilibriumResult r = analyze_equilibrium(s, cra_settings(AnalysisMethod::cra));
  EXPECT_FALSE(r.stable);
  ASSERT_EQ(r.floating_blocks.size(), 1u);
  EXPECT_EQ(r.floating_blocks[0], 2);
  EXPECT_TRUE(std::isinf(r.infeasibility));
}

TEST(Cra, InterruptStopsWithoutVerdict) {
  const Structure s = stack(2, 0.0);
  interrupt_requested() = true;
  const EquilibriumResult r = analyze_equilibrium(s, cra_settings(AnalysisMethod::cra));
  interrupt_requested() = false;
  EXPECT_EQ(r.status, SolverStatus::interrupted);
  EXPECT_FALSE(r.stable);
}

TEST(Cra, BadSettingsAreInvalidArguments) {
  const Structure s = stack(1, 0.0);
  AnalysisSettings settings = cra_settings(AnalysisMethod::cra);
  settings.cra.overlap = -1.0;
  EXPECT_NE(error_of([&] { analyze_equilibrium(s, settings); }).find("overlap must be"), std::string::npos);
  settings = cra_settings(AnalysisMethod::cra);
  settings.cra.displacement_bound = 1e-5;  // below the overlap
  EXPECT_NE(error_of([&] { analyze_equilibrium(s, settings); }).find("displacement_bound must be"), std::string::npos);
  settings = cra_settings(AnalysisMethod::cra);
  settings.cra.complementarity = -0.1;
  EXPECT_NE(error_of([&] { analyze_equilibrium(s, settings); }).find("complementarity must be"), std::string::npos);
  settings = cra_settings(AnalysisMethod::cra_penalty);
  settings.cra.max_iterations = 0;
  EXPECT_NE(error_of([&] { analyze_equilibrium(s, settings); }).find("max_iterations"), std::string::npos);
  Structure cabled = stack(1, 0.0);
  cabled.add_cable({{0, Vec3(0, 0, 0)}, {1, Vec3(0, 0, 0.5)}});
  EXPECT_NE(error_of([&] { analyze_equilibrium(cabled, cra_settings(AnalysisMethod::cra)); }).find("cables"),
            std::string::npos);
}

TEST(Cra, MethodNamesRoundTrip) {
  EXPECT_EQ(kAnalysisMethodNames.parse("cra"), AnalysisMethod::cra);
  EXPECT_EQ(kAnalysisMethodNames.parse("cra_penalty"), AnalysisMethod::cra_penalty);
  EXPECT_STREQ(kAnalysisMethodNames.name(AnalysisMethod::cra_penalty), "cra_penalty");
  EXPECT_STREQ(status_name(SolverStatus::infeasible), "infeasible");
}
