#include <gtest/gtest.h>

#include "core/error.hpp"
#include "geometry/block_builders.hpp"

using namespace ashlar;

TEST(BlockBuilders, BoxFacesPointOutward) {
  const Block box = make_box({1, 2, 3}, {0, 0, 0});
  ASSERT_EQ(box.faces().size(), 6u);
  for (size_t f = 0; f < box.faces().size(); ++f) {
    const Vec3 on_face = box.vertices()[box.faces()[f][0]];
    EXPECT_GT(box.face_planes()[f].normal.dot(on_face - box.centroid()), 0.0);
  }
}

TEST(BlockBuilders, PrismAcceptsEitherOrientationAndDirection) {
  const std::vector<Vec3> ccw = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  const std::vector<Vec3> cw(ccw.rbegin(), ccw.rend());
  for (const auto& polygon : {ccw, cw}) {
    for (double dz : {0.5, -0.5}) {
      const Block prism = make_prism(polygon, {0.1, 0.0, dz});
      EXPECT_NEAR(prism.volume(), 1.0, 1e-14);
      EXPECT_EQ(prism.faces().size(), 6u);
    }
  }
}

TEST(BlockBuilders, PrismOfBowTieIsRejected) {
  const std::vector<Vec3> bow_tie = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_THROW(make_prism(bow_tie, {0, 0, 1}), Error);
}

TEST(BlockBuilders, BadArgumentsNameTheProblem) {
  EXPECT_THROW(make_box({1, -1, 1}, {0, 0, 0}), InvalidArgument);
  const std::vector<Vec3> square = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  try {
    make_prism(square, {1, 0, 0});
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("lies in the polygon's plane"), std::string::npos);
  }
  const std::vector<Vec3> triangle = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  EXPECT_THROW(make_loft(square, triangle), InvalidArgument);
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  EXPECT_THROW(make_prism(line, {0, 0, 1}), InvalidArgument);
}

TEST(BlockBuilders, TwistedLoftSplitsSideQuads) {
  // Top square rotated by 30 degrees: side quads are not planar.
  std::vector<Vec3> bottom, top;
  for (int i = 0; i < 4; ++i) {
    const double t = M_PI / 2 * i, s = t + M_PI / 6;
    bottom.emplace_back(std::cos(t), std::sin(t), 0.0);
    top.emplace_back(std::cos(s), std::sin(s), 1.0);
  }
  const Block twisted = make_loft(bottom, top);
  EXPECT_EQ(twisted.faces().size(), 2u + 8u);
  EXPECT_GT(twisted.volume(), 0.0);
  EXPECT_LT(twisted.volume(), 2.0);  // less than the prism of the bottom square
}

TEST(BlockBuilders, VoussoirLoftHasPlanarFaces) {
  // A wedge between two radial joints of an arch (x-z plane, depth along y).
  auto joint = [](double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return std::vector<Vec3>{{4.7 * c, 0, 4.7 * s}, {5.3 * c, 0, 5.3 * s},
                             {5.3 * c, 1, 5.3 * s}, {4.7 * c, 1, 4.7 * s}};
  };
  const Block voussoir = make_loft(joint(0.2), joint(0.3));
  EXPECT_EQ(voussoir.faces().size(), 6u);
  EXPECT_NEAR(voussoir.volume(), 0.5 * (5.3 * 5.3 - 4.7 * 4.7) * 0.1 * 1.0 *
                                     (std::sin(0.1) / 0.1),  // chord wedge, not sector
              1e-12);
}
