// Each defect is rejected with a message that names it.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "geometry/block.hpp"

using namespace ashlar;

namespace {

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<FaceLoop> faces;
};

Mesh unit_cube() {
  Mesh m;
  for (int k = 0; k < 8; ++k) m.vertices.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  m.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return m;
}

std::string error_of(const Mesh& m) {
  try {
    Block(m.vertices, m.faces, kDefaultDensity, "test");
  } catch (const GeometryError& e) {
    return e.what();
  }
  return "";
}

void expect_error(const Mesh& m, const std::string& fragment) {
  const std::string message = error_of(m);
  EXPECT_NE(message.find("block 'test'"), std::string::npos) << message;
  EXPECT_NE(message.find(fragment), std::string::npos) << "message: " << message;
}

}  // namespace

TEST(BlockValidation, ValidCubeIsAccepted) {
  const Mesh m = unit_cube();
  const Block cube(m.vertices, m.faces);
  EXPECT_DOUBLE_EQ(cube.volume(), 1.0);
  EXPECT_TRUE(cube.convex());
}

TEST(BlockValidation, OpenSurface) {
  Mesh m = unit_cube();
  m.faces.pop_back();
  expect_error(m, "open surface");
}

TEST(BlockValidation, Inverted) {
  Mesh m = unit_cube();
  for (FaceLoop& f : m.faces) std::reverse(f.begin(), f.end());
  expect_error(m, "inverted");
}

TEST(BlockValidation, InconsistentOrientation) {
  Mesh m = unit_cube();
  std::reverse(m.faces[2].begin(), m.faces[2].end());
  expect_error(m, "inconsistent face orientation");
}

TEST(BlockValidation, NonPlanarFace) {
  Mesh m = unit_cube();
  m.vertices[7] += Vec3(0.0, 0.0, 0.01);
  expect_error(m, "not planar");
}

TEST(BlockValidation, WarpedFacesNeedAPlanarityAndThenBoundTheSolidOfTheirCentreFans) {
  // Vertex 8 (1, 1, 1) raised by h: the top face is warped, its vertices
  // h / 4 off its best-fit plane, whose size is sqrt(2 + h^2).
  const double h = 0.02;
  Mesh m = unit_cube();
  m.vertices[7].z() += h;
  expect_error(m, "face 2 is not planar: its vertex 5 is");
  expect_error(m, "this face needs at least 0.0036");
  try {
    Block(m.vertices, m.faces, kDefaultDensity, "test", 0.003);
    ADD_FAILURE() << "accepted beyond its planarity";
  } catch (const GeometryError& e) {
    EXPECT_NE(std::string(e.what()).find("face 2 is warped beyond planarity 0.003"), std::string::npos) << e.what();
  }
  const Block b(m.vertices, m.faces, kDefaultDensity, "test", 0.004);
  // The top's fan about its centre (0.5, 0.5, 1 + h / 4): four triangles
  // over quarters of the unit square, with heights f above z = 1 of
  // (h/4, 0, 0), (h/4, 0, h), (h/4, h, 0), (h/4, 0, 0) at their corners.
  // The volume above z = 1 is the integral of f, h / 4; its moment about
  // z = 0 adds the integral of f + f^2 / 2, h / 4 + 11 h^2 / 192 (for a
  // linear f over a triangle of area A, the integral of f^2 is A (a^2 + b^2
  // + c^2 + ab + bc + ca) / 6). The raised side faces (x = 1, y = 1) stay
  // planar.
  const double volume = 1 + h / 4;
  EXPECT_NEAR(b.volume(), volume, 1e-14);
  EXPECT_NEAR(b.centroid().z(), (0.5 + h / 4 + 11 * h * h / 192) / volume, 1e-14);
  EXPECT_NEAR(b.warp(), h / 4, 1e-4 * h);
  EXPECT_TRUE(b.convex());
  EXPECT_THROW(Block(m.vertices, m.faces, kDefaultDensity, "test", 0.3), InvalidArgument);
}

TEST(BlockValidation, CoincidentVertices) {
  Mesh m = unit_cube();
  m.vertices[7] = m.vertices[6];
  expect_error(m, "coincide");
}

TEST(BlockValidation, NanCoordinate) {
  Mesh m = unit_cube();
  m.vertices[3].y() = std::nan("");
  expect_error(m, "NaN");
}

TEST(BlockValidation, IndexOutOfRangeAndRepeats) {
  Mesh m = unit_cube();
  m.faces[0][1] = 8;
  expect_error(m, "refers to vertex 9");
  m = unit_cube();
  m.faces[0] = {0, 2, 2, 1};
  expect_error(m, "uses vertex 3 twice");
}

TEST(BlockValidation, TooFewFaces) {
  Mesh m = unit_cube();
  m.faces.resize(3);
  expect_error(m, "at least 4 faces");
}

TEST(BlockValidation, FlatSolidHasZeroVolume) {
  // A "tetrahedron" whose four points are coplanar: closed, but flat.
  Mesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  const std::string message = error_of(m);
  EXPECT_TRUE(message.find("zero") != std::string::npos ||
              message.find("degenerate") != std::string::npos)
      << message;
}

TEST(BlockValidation, SurfaceInSeparatePieces) {
  // Two overlapping cubes written as one closed, consistently oriented surface.
  Mesh a = unit_cube();
  Mesh m = a;
  for (const Vec3& p : a.vertices) m.vertices.push_back(p + Vec3(0.5, 0.5, 0.5));
  for (FaceLoop f : a.faces) {
    for (int& i : f) i += 8;
    m.faces.push_back(f);
  }
  expect_error(m, "its surface is in separate pieces (face 1 and face 7 are not joined");
}

TEST(BlockValidation, SelfIntersectingSurface) {
  // The top replaced by a tent whose apex is pushed down through the bottom.
  Mesh m = unit_cube();
  m.vertices.emplace_back(0.5, 0.5, -0.5);
  m.faces[1] = {4, 5, 8};
  m.faces.insert(m.faces.end(), {{5, 7, 8}, {7, 6, 8}, {6, 4, 8}});
  expect_error(m, "self-intersecting: faces 1 and 2 cross each other");
}

TEST(BlockValidation, NonPositiveDensity) {
  const Mesh m = unit_cube();
  EXPECT_THROW(Block(m.vertices, m.faces, -1.0), InvalidArgument);
  EXPECT_THROW(Block(m.vertices, m.faces, std::nan("")), InvalidArgument);
}
