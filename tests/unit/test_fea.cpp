// The FEA against closed-form elasticity: the patch test, an axial bar, a
// cantilever as the mesh refines; contact ties and constraint relaxation.
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "core/interrupt.hpp"
#include "fea/fea.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

FeaResult run_fea(const Structure& s, int refine, double poisson = 0.0, bool relax = true) {
  FeaSettings settings;
  settings.material.poisson = poisson;
  settings.relax = relax;
  return analyze_fea(s, FeaMesh(s, refine), settings);
}

// Mean z displacement of the nodes at height z.
double mean_uz_at(const FeaMesh& mesh, const FeaResult& r, double z) {
  double sum = 0;
  int count = 0;
  for (size_t n = 0; n < mesh.nodes().size(); ++n)
    if (std::abs(mesh.nodes()[n].z() - z) < 1e-9) {
      sum += r.displacements[n].z();
      ++count;
    }
  return sum / count;
}

// A column of `blocks` boxes 0.5 x 0.5 x 1 m standing on a support slab.
Structure stacked_boxes(int blocks) {
  Structure s;
  s.add(box({2, 2, 1}, {0, 0, -0.5}), true);
  for (int k = 0; k < blocks; ++k) s.add(box({0.5, 0.5, 1}, {0, 0, k + 0.5}));
  return s;
}

// Planar faces (the top is a scaled copy of the bottom) but no parallel
// opposite faces.
Block skewed_frustum() {
  const std::vector<Vec3> bottom = {{0, 0, 0}, {2, 0, 0}, {2.4, 1.8, 0}, {-0.2, 1.5, 0}};
  std::vector<Vec3> top;
  for (const Vec3& p : bottom) top.push_back(Vec3(0.3, 0.4, 1.5) + 0.6 * p);
  return make_loft(bottom, top);
}

}  // namespace

TEST(HexElement, PatchTestReproducesAConstantStressOnADistortedMesh) {
  // A skewed frustum on an irregular quadrilateral, refined: no element is a
  // parallelepiped.
  Structure s;
  s.add(std::make_shared<const Block>(skewed_frustum()));
  const FeaMesh mesh(s, 3);
  const Elasticity material{20e9, 0.2};
  const int n = static_cast<int>(mesh.nodes().size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(3 * n, 3 * n);
  for (int e = 0; e < static_cast<int>(mesh.elements().size()); ++e) {
    const HexStiffness ke = hex_stiffness(mesh.element_nodes(e), material);
    for (int a = 0; a < 24; ++a)
      for (int b = 0; b < 24; ++b)
        k(3 * mesh.elements()[e][a / 3] + a % 3, 3 * mesh.elements()[e][b / 3] + b % 3) += ke(a, b);
  }
  // A linear displacement field: constant strain, so constant stress.
  Mat3 gradient;
  gradient << 1e-4, 2e-5, -3e-5, 4e-5, -2e-4, 1e-5, 3e-5, 5e-5, 1.5e-4;
  Eigen::VectorXd u(3 * n);
  for (int i = 0; i < n; ++i) u.segment<3>(3 * i) = gradient * mesh.nodes()[i];
  const Eigen::VectorXd f = k * u;
  const std::vector<int> surface = mesh.surface_nodes(0);
  const double scale = f.cwiseAbs().maxCoeff();
  for (int i = 0; i < n; ++i)
    if (std::find(surface.begin(), surface.end(), i) == surface.end()) {
      EXPECT_LT(f.segment<3>(3 * i).norm(), 1e-10 * scale) << "interior node " << i;
    }
  HexVector ue;
  for (int a = 0; a < 8; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * mesh.elements()[0][a]);
  const Stress reference = hex_stress(mesh.element_nodes(0), ue, material);
  for (int e = 0; e < static_cast<int>(mesh.elements().size()); ++e)
    for (const auto& corner : kHexCorners) {
      for (int a = 0; a < 8; ++a) ue.segment<3>(3 * a) = u.segment<3>(3 * mesh.elements()[e][a]);
      const Stress s = hex_stress(mesh.element_nodes(e), ue, material, Vec3(corner[0], corner[1], corner[2]) * 0.5);
      EXPECT_LT((s - reference).norm(), 1e-9 * reference.norm());
    }
}

TEST(HexElement, BodyLoadSumsToTheWeight) {
  // With planar faces the trilinear map fills the polyhedron exactly.
  const Block block = skewed_frustum();
  const HexVector f = hex_body_load(hexahedron_corners(block, "frustum"), Vec3(0, 0, -10));
  double total = 0;
  for (int a = 0; a < 8; ++a) total += f(3 * a + 2);
  EXPECT_NEAR(total, -10 * block.volume(), 1e-12 * 10 * block.volume());
}

TEST(Fea, AxialBarUnderItsWeightMatchesClosedFormAtEveryNode) {
  // Poisson 0 makes the bar one-dimensional: u_z = -rho g (L z - z^2 / 2) / E,
  // which linear elements with consistent loads reproduce at the nodes.
  const Structure s = stacked_boxes(3);
  for (int refine : {1, 2, 4}) {
    const FeaMesh mesh(s, refine);
    FeaSettings settings;
      settings.material.poisson = 0;
    const FeaResult r = analyze_fea(s, mesh, settings);
    ASSERT_EQ(r.status, FeaStatus::CompressionOnly);
    const double rho_g = 2400 * 9.81, e = 20e9, length = 3;
    for (double z : {1.0, 2.0, 3.0})
      EXPECT_NEAR(mean_uz_at(mesh, r, z), -rho_g * (length * z - z * z / 2) / e, 1e-9 * rho_g * 9 / e)
          << "refine " << refine << " z " << z;
  }
}

TEST(Fea, ContactForcesBalanceTheWeight) {
  const Structure s = stacked_boxes(2);
  const FeaResult r = run_fea(s, 2);
  const std::shared_ptr<const std::vector<Interface>> faces_list = s.interfaces();
  const std::vector<Interface>& faces = *faces_list;
  for (size_t k = 0; k < faces.size(); ++k) {
    // The weight above each bed joint.
    const double above = faces[k].a == 0 ? 2 * 0.25 * 2400 * 9.81 : 0.25 * 2400 * 9.81;
    EXPECT_NEAR(r.interfaces[k].compression, above, 1e-8 * above) << "interface " << k;
    EXPECT_NEAR(r.interfaces[k].tension, 0.0, 1e-8 * above);
    EXPECT_NEAR(r.interfaces[k].resultant.z(), above, 1e-8 * above);
  }
}

TEST(Fea, EndLoadedBarShortensByFLOverEA) {
  // Nearly weightless blocks; the load at the top centre spreads evenly over
  // the top corners, so the stress is uniform: delta = F L / (E A).
  Structure s;
  s.add(box({2, 2, 1}, {0, 0, -0.5}), true);
  for (int k = 0; k < 2; ++k)
    s.add(std::make_shared<const Block>(make_box({0.5, 0.5, 1}, {0, 0, k + 0.5}).with_density(1e-9)));
  const double force = 1e6, expected = force * 2 / (20e9 * 0.25);
  s.add_load({2, Vec3(0, 0, -force), Vec3(0, 0, 2)});
  const FeaMesh mesh(s, 1);
  FeaSettings settings;
  settings.material.poisson = 0;
  const FeaResult r = analyze_fea(s, mesh, settings);
  EXPECT_NEAR(mean_uz_at(mesh, r, 2.0), -expected, 1e-9 * expected);
  EXPECT_NEAR(mean_uz_at(mesh, r, 1.0), -expected / 2, 1e-9 * expected);
}

namespace {

// A cantilever of `blocks` cubes (side h = 0.2 m) along +x from a support
// wall at x = 0: matching meshes tie the cubes into one beam, clamped at
// the wall, under its own weight.
Structure cantilever(int blocks) {
  Structure s;
  s.add(box({1, 1, 1}, {-0.5, 0, 0.5}), true);
  for (int k = 0; k < blocks; ++k) s.add(box({0.2, 0.2, 0.2}, {0.1 + 0.2 * k, 0, 0.5}));
  return s;
}

// Timoshenko beam, uniform load q: w = q L^4 / (8 E I) + q L^2 / (2 kappa G A).
double cantilever_tip_deflection(double length, double side, double young, double poisson) {
  const double q = 2400 * 9.81 * side * side, inertia = std::pow(side, 4) / 12;
  const double shear_modulus = young / (2 * (1 + poisson)), kappa = 5.0 / 6.0;
  return q * std::pow(length, 4) / (8 * young * inertia) + q * length * length / (2 * kappa * shear_modulus * side * side);
}

}  // namespace

TEST(Fea, CantileverTipDeflectionConvergesToBeamTheory) {
  // Trilinear elements under full integration lock in bending, so the coarse
  // beam is too stiff; the error falls as h^2 (measured 0.332, 0.112,
  // 0.031, 0.008 at refine 1, 2, 4, 8).
  const Structure s = cantilever(10);
  const double reference = cantilever_tip_deflection(2.0, 0.2, 20e9, 0.0);
  std::vector<double> errors;
  for (int refine : {1, 2, 4, 8}) {
    const FeaMesh mesh(s, refine);
    FeaSettings settings;
      settings.material.poisson = 0;
    settings.relax = false;  // the clamp carries tension at its top: that is what a clamp does
    const FeaResult r = analyze_fea(s, mesh, settings);
    EXPECT_EQ(r.status, FeaStatus::Tension);
    double tip = 0;
    int count = 0;
    for (size_t n = 0; n < mesh.nodes().size(); ++n)
      if (std::abs(mesh.nodes()[n].x() - 2.0) < 1e-9) {
        tip += r.displacements[n].z();
        ++count;
      }
    errors.push_back(std::abs(-tip / count - reference) / reference);
  }
  for (size_t i = 1; i < errors.size(); ++i) EXPECT_LT(errors[i], errors[i - 1]);
  EXPECT_LT(errors.back(), 0.01);
  const double rate = std::log2(errors[2] / errors[3]);
  EXPECT_GT(rate, 1.7);
  EXPECT_LT(rate, 2.3);
}

TEST(Fea, RelaxationChangesNothingWhenEveryContactIsInCompression) {
  const Structure s = stacked_boxes(3);
  const FeaResult relaxed = run_fea(s, 2, 0.2, true), plain = run_fea(s, 2, 0.2, false);
  EXPECT_EQ(relaxed.status, FeaStatus::CompressionOnly);
  EXPECT_EQ(plain.status, FeaStatus::CompressionOnly);
  EXPECT_EQ(relaxed.iterations, 0);
  ASSERT_EQ(relaxed.displacements.size(), plain.displacements.size());
  for (size_t n = 0; n < plain.displacements.size(); ++n)
    EXPECT_EQ(relaxed.displacements[n], plain.displacements[n]);
}

TEST(Fea, ABlockHeldOnlyByAWallHangsInTensionAndRelaxationFindsAMechanism) {
  const Structure s = cantilever(1);
  const FeaResult held = run_fea(s, 1, 0.2, false);
  EXPECT_EQ(held.status, FeaStatus::Tension);
  ASSERT_EQ(held.history.size(), 1u);
  EXPECT_EQ(held.history[0].tensile, 2);  // the top corners pull on the wall
  EXPECT_GT(held.interfaces[0].tension, 0);
  const FeaResult relaxed = run_fea(s, 1, 0.2, true);
  EXPECT_EQ(relaxed.status, FeaStatus::Mechanism);  // nothing holds it once they let go
  EXPECT_EQ(relaxed.iterations, 1);
}

TEST(Fea, RejectsBlocksThatAreNotHexahedraCablesAndBadSettings) {
  Structure wedge;
  wedge.add(box({2, 2, 1}, {0, 0, -0.5}), true);
  wedge.add(std::make_shared<const Block>(make_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}})));
  EXPECT_TRUE(contains(error_of([&] { FeaMesh(wedge, 1); }), "block 2 is not a hexahedron (4 vertices)"));
  const Structure s = stacked_boxes(1);
  EXPECT_TRUE(contains(error_of([&] { FeaMesh(s, 0); }), "refine: expected a whole number from 1 to 64"));
  FeaSettings settings;
  settings.material.poisson = 0.5;
  EXPECT_TRUE(contains(error_of([&] { analyze_fea(s, FeaMesh(s, 1), settings); }), "poisson"));
  Structure cabled = stacked_boxes(1);
  Cable cable;
  cable.from = {0, Vec3(0.9, 0, 0)};
  cable.to = {1, Vec3(0.25, 0, 0.5)};
  cabled.add_cable(cable);
  EXPECT_TRUE(contains(error_of([&] { analyze_fea(cabled, FeaMesh(cabled, 1), FeaSettings{}); }),
                       "does not model cables"));
}

namespace {

// A block 1 m long (x), 0.5 m deep, 2 m high on a support slab, pushed
// along +x by `push` N at its top centre.
Structure pushed_block(double push) {
  Structure s;
  s.add(box({3, 2, 1}, {0, 0, -0.5}), true);
  s.add(box({1, 0.5, 2}, {0, 0, 1}));
  s.add_load({1, Vec3(push, 0, 0), Vec3(0, 0, 2)});
  return s;
}

}  // namespace

TEST(FeaUnilateral, ABlockPushedSidewaysLiftsItsHeelAndOverturnsAtTheClosedForm) {
  // Statics: the ground's vertical reaction W acts at x = 2 H / W (moments
  // about the base centre), whatever the elasticity; past x = 0.5 (the toe)
  // nothing holds the block: H = W / 4 overturns it.
  const double weight = 2400 * kGravity * 1.0, overturning = weight / 4;
  FeaSettings settings;
  const Structure standing = pushed_block(0.9 * overturning);
  const FeaMesh mesh(standing, 4);
  const FeaResult r = analyze_fea(standing, mesh, settings);
  ASSERT_EQ(r.status, FeaStatus::CompressionOnly);
  ASSERT_EQ(r.interfaces.size(), 1u);
  EXPECT_NEAR(r.interfaces[0].center_of_pressure.x(), 2 * 0.9 * overturning / weight, 1e-8);
  EXPECT_NEAR(r.interfaces[0].resultant.z(), weight, 1e-8 * weight);
  EXPECT_NEAR(r.interfaces[0].resultant.x(), -0.9 * overturning, 1e-8 * weight);
  // With the resultant at 0.45 m of the 0.5 m half-length the heel lifts:
  // open nodes there, carrying nothing, none overlapping; closed ones press.
  int open = 0;
  for (const FeaContact& c : r.contacts) {
    if (c.released) {
      ++open;
      EXPECT_LT(mesh.nodes()[c.node].x(), 0.45);
      EXPECT_NEAR(c.normal_force, 0, 1e-9 * weight);
      EXPECT_GT(c.opening, -1e-6 * r.max_displacement);
    } else {
      EXPECT_GT(c.normal_force, -1e-6 * weight / r.contacts.size());
    }
  }
  EXPECT_GT(open, 0);
  const Structure toppling = pushed_block(1.1 * overturning);
  const FeaResult fallen = analyze_fea(toppling, FeaMesh(toppling, 4), settings);
  EXPECT_EQ(fallen.status, FeaStatus::Mechanism);
  EXPECT_TRUE(std::isnan(fallen.max_displacement));
}

TEST(FeaUnilateral, AnInterruptedOrUnfinishedAnalysisHasNoVerdict) {
  const Structure s = pushed_block(0.9 * 2400 * kGravity / 4);
  const FeaMesh mesh(s, 2);
  FeaSettings settings;
  settings.max_relax_iterations = 0;  // the heel needs a second solve
  const FeaResult unfinished = analyze_fea(s, mesh, settings);
  EXPECT_EQ(unfinished.status, FeaStatus::IterationLimit);
  EXPECT_FALSE(unfinished.compression_only);
  EXPECT_TRUE(std::isnan(unfinished.max_displacement));
  interrupt_requested() = true;
  const FeaResult interrupted = analyze_fea(s, mesh, FeaSettings{});
  interrupt_requested() = false;
  EXPECT_EQ(interrupted.status, FeaStatus::Interrupted);
  EXPECT_FALSE(interrupted.compression_only);
  EXPECT_TRUE(std::isnan(interrupted.max_displacement));
  // What it has can still be exported: every node with a displacement.
  EXPECT_EQ(interrupted.displacements.size(), mesh.nodes().size());
}
