// Mass properties against closed forms, to 1e-12 relative.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "core/error.hpp"
#include "geometry/block_builders.hpp"

using namespace ashlar;

namespace {

constexpr double kRel = 1e-12;

void expect_rel(double actual, double expected, double rel = kRel) {
  EXPECT_NEAR(actual, expected, rel * std::abs(expected)) << "expected " << expected;
}

void expect_vec(const Vec3& actual, const Vec3& expected, double scale) {
  EXPECT_LE((actual - expected).norm(), kRel * scale) << actual.transpose() << " vs "
                                                      << expected.transpose();
}

std::vector<Vec3> regular_polygon(int n, double radius, double z) {
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * M_PI * i / n;
    points.emplace_back(radius * std::cos(t), radius * std::sin(t), z);
  }
  return points;
}

}  // namespace

TEST(MassProperties, BoxVolumeMassCentroid) {
  const Block box = make_box({2.0, 3.0, 0.5}, {1.0, -2.0, 0.25}, {2000.0, "b"});
  expect_rel(box.volume(), 3.0);
  expect_rel(box.mass(), 6000.0);
  expect_vec(box.centroid(), {1.0, -2.0, 0.25}, 3.0);
}

TEST(MassProperties, FarFromOriginKeepsDigits) {
  const Vec3 center(1e6, -3e6, 2e5);
  const Block box = make_box({0.3, 0.2, 0.1}, center);
  // The corners themselves are rounded at 1e6 m; the reference is the box
  // they span, whose extents are exact differences of doubles.
  const Vec3 extent = box.bounds().hi - box.bounds().lo;
  expect_rel(box.volume(), extent.x() * extent.y() * extent.z());
  expect_vec(box.centroid(), 0.5 * (box.bounds().hi + box.bounds().lo), center.norm());
}

TEST(MassProperties, RegularPrism) {
  const int n = 17;
  const double r = 0.7, h = 1.3;
  const Block prism = make_prism(regular_polygon(n, r, 0.0), {0.0, 0.0, h});
  expect_rel(prism.volume(), 0.5 * n * r * r * std::sin(2.0 * M_PI / n) * h);
  expect_vec(prism.centroid(), {0.0, 0.0, h / 2}, 1.0);
}

TEST(MassProperties, NonConvexLPrism) {
  // L: 3x3 square minus the 2x2 square at its upper right; area 5.
  const std::vector<Vec3> l = {{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
  const Block prism = make_prism(l, {0.0, 0.0, 2.0});
  EXPECT_FALSE(prism.convex());
  expect_rel(prism.volume(), 10.0);
  // Centroid: (9 * 1.5 - 4 * 2) / 5 in x and y.
  expect_vec(prism.centroid(), {1.1, 1.1, 1.0}, 3.0);
}

TEST(MassProperties, Tetrahedron) {
  const std::vector<Vec3> v = {{0.1, 0.2, 0.3}, {1.7, 0.1, 0.2}, {0.4, 2.3, 0.1}, {0.5, 0.6, 1.9}};
  const Block tet = make_hull(v);
  const double expected = std::abs((v[1] - v[0]).dot((v[2] - v[0]).cross(v[3] - v[0]))) / 6.0;
  expect_rel(tet.volume(), expected);
  expect_vec(tet.centroid(), (v[0] + v[1] + v[2] + v[3]) / 4.0, 3.0);
}

TEST(MassProperties, FrustumLoft) {
  // Square frustum: V = h/3 (A1 + A2 + sqrt(A1 A2)).
  const std::vector<Vec3> bottom = {{-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const std::vector<Vec3> top = {{-0.5, -0.5, 3}, {0.5, -0.5, 3}, {0.5, 0.5, 3}, {-0.5, 0.5, 3}};
  const Block frustum = make_loft(bottom, top);
  expect_rel(frustum.volume(), 3.0 / 3.0 * (4.0 + 1.0 + 2.0));
  // Centroid height of a frustum: h (A1 + 2 sqrt(A1 A2) + 3 A2) / (4 (A1 + sqrt(A1 A2) + A2)).
  expect_vec(frustum.centroid(), {0.0, 0.0, 3.0 * (4.0 + 4.0 + 3.0) / (4.0 * 7.0)}, 3.0);
}

TEST(MassProperties, RigidMotionsMoveTheCentroidOnly) {
  const Block box = make_box({1.0, 2.0, 3.0}, {0.5, 0.5, 0.5});
  const Vec3 axis = Vec3(1.0, 2.0, -0.5).normalized();
  const double angle = 0.73;
  const Vec3 origin(3.0, -1.0, 2.0);
  const Block moved = box.rotated(axis, angle, origin).translated({10.0, 0.0, -4.0});
  expect_rel(moved.volume(), box.volume());
  const Vec3 expected = origin + Eigen::AngleAxisd(angle, axis) * (box.centroid() - origin) +
                        Vec3(10.0, 0.0, -4.0);
  expect_vec(moved.centroid(), expected, 10.0);
}

namespace {

// Central differences of mass_properties against mass_properties_gradient
// at every vertex and axis, after a fixed pseudo-random warp of the
// vertices (faces bent out of their planes: the derivatives follow the
// same fan triangulation, so they must hold there too).
void expect_gradient_matches_differences(const Block& block, double warp) {
  std::vector<Vec3> vertices = block.vertices();
  for (size_t k = 0; k < vertices.size(); ++k) {
    vertices[k] += warp * Vec3(std::sin(3.1 * k + 1), std::cos(1.7 * k), std::sin(0.9 * k + 2));
  }
  const std::vector<FaceLoop>& faces = block.faces();
  const MassPropertiesGradient gradient = mass_properties_gradient(vertices, faces);
  const double h = 1e-6;
  const double size = block.bounds().diagonal();
  for (size_t k = 0; k < vertices.size(); ++k) {
    for (int j = 0; j < 3; ++j) {
      std::vector<Vec3> plus = vertices, minus = vertices;
      plus[k](j) += h;
      minus[k](j) -= h;
      const MassProperties p = mass_properties(plus, faces), m = mass_properties(minus, faces);
      const double d_volume = (p.volume - m.volume) / (2 * h);
      const Vec3 d_centroid = (p.centroid - m.centroid) / (2 * h);
      EXPECT_NEAR(gradient.volume[k](j), d_volume, 1e-7 * size * size) << "vertex " << k << " axis " << j;
      EXPECT_LE((gradient.centroid[k].col(j) - d_centroid).norm(), 1e-7)
          << "vertex " << k << " axis " << j;
    }
  }
  // Moving every vertex together translates the block: the volume stays,
  // the centroid follows.
  Vec3 volume_sum = Vec3::Zero();
  Mat3 centroid_sum = Mat3::Zero();
  for (size_t k = 0; k < vertices.size(); ++k) {
    volume_sum += gradient.volume[k];
    centroid_sum += gradient.centroid[k];
  }
  EXPECT_LE(volume_sum.norm(), 1e-12 * size * size);
  EXPECT_LE((centroid_sum - Mat3::Identity()).norm(), 1e-12);
}

}  // namespace

TEST(MassPropertiesGradient, MatchesCentralDifferencesOnBoxPrismAndLoft) {
  expect_gradient_matches_differences(make_box({2.0, 3.0, 0.5}, {1.0, -2.0, 0.25}), 0.0);
  expect_gradient_matches_differences(make_box({2.0, 3.0, 0.5}, {100.0, -200.0, 50.0}), 0.05);
  expect_gradient_matches_differences(make_prism(regular_polygon(7, 0.7, 0.0), {0.1, 0.0, 1.3}), 0.02);
  expect_gradient_matches_differences(
      make_loft(regular_polygon(5, 1.0, 0.0), regular_polygon(5, 0.6, 1.0)), 0.03);
}

TEST(MassPropertiesGradient, MatchesCentralDifferencesOnANonConvexBlock) {
  const std::vector<Vec3> l = {{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
  expect_gradient_matches_differences(make_prism(l, {0.0, 0.0, 2.0}), 0.0);
  expect_gradient_matches_differences(make_prism(l, {0.0, 0.0, 2.0}), 0.05);
}

TEST(MassPropertiesGradient, MovingABoxFaceOutAddsItsArea) {
  // How the fan splits a face among its corners is the triangulation's
  // choice; moving the whole +x face out by h adds b c h whatever it is.
  const double a = 2.0, b = 3.0, c = 0.5;
  const Block box = make_box({a, b, c}, {0.0, 0.0, 0.0});
  const MassPropertiesGradient gradient = mass_properties_gradient(box.vertices(), box.faces());
  double plus_x = 0.0;
  for (size_t k = 0; k < box.vertices().size(); ++k) {
    if (box.vertices()[k].x() > 0) plus_x += gradient.volume[k].x();
  }
  EXPECT_NEAR(plus_x, b * c, 1e-12);
}

TEST(MassPropertiesGradient, ZeroVolumeIsAnError) {
  const std::vector<Vec3> flat = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}};
  const std::vector<FaceLoop> faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  EXPECT_THROW(mass_properties_gradient(flat, faces), InvalidArgument);
}
