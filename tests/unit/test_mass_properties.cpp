// Mass properties against closed forms, to 1e-12 relative.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

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
