// Rigid rotation of a whole structure (the tilt table): vertex positions
// against the closed-form rotation, everything else carried over, loads kept
// vertical, and the planar flag kept only by rotations that keep the x-z plane.
#include <gtest/gtest.h>

#include <cmath>

#include "structure/structure_transform.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// A box on a support, a point load on the box and a cable from the support
// to the box's top corner.
Structure loaded_box() {
  Structure s;
  s.add(box({1, 2, 3}, {0.5, 0, 1.5}), false, "box");
  s.add(box({4, 2, 1}, {0, 0, -0.5}), true, "ground");
  s.add_load({0, Vec3(0, 0, -100), Vec3(0.25, 0.5, 2)});
  Cable cable;
  cable.from = {1, Vec3(-2, -1, 0)};
  cable.to = {0, Vec3(1, 1, 3)};
  cable.mass_per_length = 2.5;
  cable.max_tension = 1e4;
  s.add_cable(cable);
  return s;
}

// p rotated by angle about the y axis through origin, right-handed: +z
// turns towards +x.
Vec3 about_y(const Vec3& p, double angle, const Vec3& origin) {
  const Vec3 d = p - origin;
  const double c = std::cos(angle), s = std::sin(angle);
  return origin + Vec3(c * d.x() + s * d.z(), d.y(), -s * d.x() + c * d.z());
}

void expect_near(const Vec3& actual, const Vec3& expected, double tolerance) {
  EXPECT_LT((actual - expected).lpNorm<Eigen::Infinity>(), tolerance)
      << "actual (" << actual.transpose() << "), expected (" << expected.transpose() << ")";
}

}  // namespace

TEST(StructureTransform, BaseCenterIsTheMiddleOfTheBoundingBoxBottom) {
  const Structure s = loaded_box();
  EXPECT_EQ(base_center(s), Vec3(0, 0, -1));
  EXPECT_EQ(base_center(Structure()), Vec3::Zero());
}

TEST(StructureTransform, RotatesEveryVertexAboutTheAxisThroughTheOrigin) {
  const Structure s = loaded_box();
  const Vec3 origin(0.3, -0.2, -1);
  for (double angle : {0.2, -0.7, 2.5}) {
    const Structure t = rotated(s, Vec3(0, 2, 0), angle, origin);
    ASSERT_EQ(t.size(), s.size());
    for (int i = 0; i < s.size(); ++i) {
      const std::vector<Vec3>& before = s.block(i).vertices();
      const std::vector<Vec3>& after = t.block(i).vertices();
      ASSERT_EQ(after.size(), before.size());
      for (size_t k = 0; k < before.size(); ++k) {
        expect_near(after[k], about_y(before[k], angle, origin), 1e-12);
      }
      EXPECT_EQ(t.block(i).faces(), s.block(i).faces());
    }
  }
}

TEST(StructureTransform, PositiveAngleAboutYTurnsUpTowardsPlusX) {
  // The sign convention the tilt table documents: gravity, seen in the
  // tilted structure's frame, acts along (sin a, 0, -cos a).
  Structure s;
  s.add(box({1, 1, 1}, {0, 0, 0.5}));
  const double angle = 0.3;
  const Structure t = rotated(s, Vec3::UnitY(), angle, Vec3::Zero());
  // The block's top centre (0, 0, 1) moves to (sin a, 0, cos a).
  Vec3 top = Vec3::Zero();
  for (const Vec3& p : t.block(0).vertices()) top += p;
  top /= 8.0;
  expect_near(2.0 * top, Vec3(std::sin(angle), 0, std::cos(angle)), 1e-12);
}

TEST(StructureTransform, KeepsNamesSupportsLoadsAndCables) {
  const Structure s = loaded_box();
  const Vec3 axis(1, 2, -0.5), origin(1, 2, 3);
  const double angle = 0.4;
  const Structure t = rotated(s, axis, angle, origin);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  auto move = [&](const Vec3& p) -> Vec3 { return origin + r * (p - origin); };
  for (int i = 0; i < s.size(); ++i) {
    EXPECT_EQ(t.name(i), s.name(i));
    EXPECT_EQ(t.is_support(i), s.is_support(i));
    EXPECT_EQ(t.block(i).density(), s.block(i).density());
    EXPECT_NEAR(t.block(i).volume(), s.block(i).volume(), 1e-12);
    expect_near(t.block(i).centroid(), move(s.block(i).centroid()), 1e-12);
  }
  ASSERT_EQ(t.loads().size(), 1u);
  EXPECT_EQ(t.loads()[0].block, 0);
  expect_near(t.loads()[0].at, move(s.loads()[0].at), 1e-12);
  // A dead load still hangs vertically.
  EXPECT_EQ(t.loads()[0].force, s.loads()[0].force);
  ASSERT_EQ(t.cables().size(), 1u);
  const Cable& c = t.cables()[0];
  EXPECT_EQ(c.from.block, 1);
  EXPECT_EQ(c.to.block, 0);
  expect_near(c.from.point, move(s.cables()[0].from.point), 1e-12);
  expect_near(c.to.point, move(s.cables()[0].to.point), 1e-12);
  EXPECT_EQ(c.mass_per_length, 2.5);
  EXPECT_EQ(c.max_tension, 1e4);
  // The input is untouched.
  expect_near(s.block(0).centroid(), Vec3(0.5, 0, 1.5), 1e-15);
}

TEST(StructureTransform, KeepsThePlanarFlagOnlyForRotationsAboutY) {
  Structure s = semicircular_arch(6, 1.0);
  s.set_planar(true);
  EXPECT_TRUE(rotated(s, Vec3(0, 1, 0), 0.1, Vec3(1, 5, 2)).planar());
  EXPECT_TRUE(rotated(s, Vec3(0, -3, 0), 0.1, Vec3::Zero()).planar());
  EXPECT_TRUE(rotated(s, Vec3(1, 0, 0), 0.0, Vec3::Zero()).planar());
  EXPECT_FALSE(rotated(s, Vec3(1, 0, 0), 0.1, Vec3::Zero()).planar());
  EXPECT_FALSE(rotated(s, Vec3(0, 1, 1e-9), 0.1, Vec3::Zero()).planar());
  s.set_planar(false);
  EXPECT_FALSE(rotated(s, Vec3(0, 1, 0), 0.1, Vec3::Zero()).planar());
}

TEST(StructureTransform, RejectsBadArguments) {
  const Structure s = loaded_box();
  EXPECT_TRUE(contains(error_of([&] { rotated(s, Vec3::Zero(), 0.1, Vec3::Zero()); }),
                       "axis must not be zero"));
  EXPECT_TRUE(contains(error_of([&] { rotated(s, Vec3::UnitY(), NAN, Vec3::Zero()); }),
                       "angle must be finite"));
  EXPECT_TRUE(contains(error_of([&] { rotated(Structure(), Vec3::UnitY(), INFINITY, Vec3::Zero()); }),
                       "angle must be finite"));
  EXPECT_TRUE(contains(error_of([&] { rotated(s, Vec3::UnitY(), 0.1, Vec3(0, NAN, 0)); }),
                       "origin must be finite"));
}
