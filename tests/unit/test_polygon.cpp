#include <gtest/gtest.h>

#include "geometry/polygon.hpp"

using namespace ashlar;

TEST(Polygon, NewellNormalIsTwiceTheArea) {
  const std::vector<Vec3> square = {{0, 0, 5}, {2, 0, 5}, {2, 2, 5}, {0, 2, 5}};
  EXPECT_TRUE(newell_normal(square).isApprox(Vec3(0, 0, 8)));
}

TEST(Polygon, FrameRoundTrip) {
  const PlaneFrame frame = PlaneFrame::from_normal({1, 2, 3}, {0.3, -0.4, 0.5});
  EXPECT_NEAR(frame.e1.cross(frame.e2).dot(frame.normal), 1.0, 1e-15);
  const Vec3 p = frame.lift({0.7, -1.1});
  EXPECT_NEAR(frame.distance(p), 0.0, 1e-14);
  EXPECT_TRUE(frame.project(p).isApprox(Vec2(0.7, -1.1)));
}

TEST(Polygon, AreaCentroidConvexity) {
  const Loop2 l = {{0, 0}, {3, 0}, {3, 1}, {1, 1}, {1, 3}, {0, 3}};
  EXPECT_DOUBLE_EQ(signed_area(l), 5.0);
  EXPECT_TRUE(area_centroid(l).isApprox(Vec2(1.1, 1.1)));
  EXPECT_FALSE(is_convex(l));
  const Loop2 square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_TRUE(is_convex(square));
  const Loop2 clockwise = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  EXPECT_FALSE(is_convex(clockwise));
  EXPECT_DOUBLE_EQ(signed_area(clockwise), -1.0);
}

TEST(Polygon, ClipConvexOverlapAndMiss) {
  const Loop2 a = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  const Loop2 b = {{1, 1}, {3, 1}, {3, 3}, {1, 3}};
  const Loop2 overlap = clip_convex(a, b);
  EXPECT_DOUBLE_EQ(signed_area(overlap), 1.0);
  EXPECT_TRUE(area_centroid(overlap).isApprox(Vec2(1.5, 1.5)));
  const Loop2 far = {{5, 5}, {6, 5}, {6, 6}, {5, 6}};
  EXPECT_TRUE(clip_convex(a, far).empty());
}
