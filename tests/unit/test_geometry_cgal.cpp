// The CGAL-backed geometry: hulls, polygon booleans, self-intersection,
// mesh repair and splitting. Suites are named Cgal* for --gtest_filter.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <random>
#include <regex>
#include <string>

#include "core/error.hpp"
#include "geometry/block.hpp"
#include "geometry/block_builders.hpp"
#include "geometry/block_validation.hpp"
#include "geometry/polygon_boolean.hpp"

namespace ashlar {
namespace {

struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<FaceLoop> faces;
};

double shoelace(const Loop2& loop) {
  double twice = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Vec2& a = loop[i];
    const Vec2& b = loop[(i + 1) % loop.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * twice;
}

// A counter-clockwise polygon in the xy plane extruded along +z.
Mesh prism_mesh(const Loop2& polygon, double height) {
  Mesh mesh;
  const int n = static_cast<int>(polygon.size());
  for (const Vec2& p : polygon) mesh.vertices.emplace_back(p.x(), p.y(), 0.0);
  for (const Vec2& p : polygon) mesh.vertices.emplace_back(p.x(), p.y(), height);
  FaceLoop bottom, top;
  for (int i = 0; i < n; ++i) {
    bottom.push_back(n - 1 - i);
    top.push_back(n + i);
    const int j = (i + 1) % n;
    mesh.faces.push_back({i, j, n + j, n + i});
  }
  mesh.faces.push_back(bottom);
  mesh.faces.push_back(top);
  return mesh;
}

// What a mesh file holds: every face fan-triangulated, every triangle with
// its own copies of its vertices.
Mesh triangle_soup(const Mesh& mesh) {
  Mesh soup;
  for (const FaceLoop& face : mesh.faces) {
    for (size_t i = 1; i + 1 < face.size(); ++i) {
      const int first = static_cast<int>(soup.vertices.size());
      for (int index : {face[0], face[i], face[i + 1]}) soup.vertices.push_back(mesh.vertices[index]);
      soup.faces.push_back({first, first + 1, first + 2});
    }
  }
  return soup;
}

Mesh unit_cube() { return prism_mesh({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, 1.0); }

const Loop2 kLShape = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};  // area 3

size_t count_faces_along(const Block& block, const Vec3& direction) {
  size_t count = 0;
  for (const FacePlane& plane : block.face_planes()) {
    if (plane.normal.dot(direction.normalized()) > 1.0 - 1e-9) ++count;
  }
  return count;
}

// ---------------------------------------------------------------- hull

TEST(CgalHull, BoxCornersGiveSixQuads) {
  std::vector<Vec3> points;
  for (double x : {-1.0, 1.0})
    for (double y : {-1.5, 1.5})
      for (double z : {-2.0, 2.0}) points.emplace_back(x, y, z);
  points.emplace_back(0.1, 0.2, 0.3);   // inside
  points.emplace_back(0.0, 0.0, 2.0);   // centre of the top face
  points.emplace_back(1.0, 0.0, 0.0);   // centre of a side face
  const Block hull = make_hull(points, {1000.0, "box"});
  EXPECT_EQ(hull.faces().size(), 6u);
  EXPECT_EQ(hull.vertices().size(), 8u);
  for (const FaceLoop& face : hull.faces()) EXPECT_EQ(face.size(), 4u);
  EXPECT_NEAR(hull.volume(), 24.0, 1e-12 * 24.0);
  EXPECT_NEAR(hull.centroid().norm(), 0.0, 1e-12);
  EXPECT_TRUE(hull.convex());
  EXPECT_EQ(hull.name(), "box");
  EXPECT_EQ(hull.density(), 1000.0);
}

TEST(CgalHull, RotatedBoxCornersStillGiveSixQuads) {
  // Rotation rounds the corners off their exact planes.
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  std::vector<Vec3> points;
  for (double x : {-1.0, 1.0})
    for (double y : {-1.5, 1.5})
      for (double z : {-2.0, 2.0}) points.push_back(rotation * Vec3(x, y, z) + Vec3(5, 6, 7));
  const Block hull = make_hull(points);
  EXPECT_EQ(hull.faces().size(), 6u);
  EXPECT_NEAR(hull.volume(), 24.0, 1e-12 * 24.0);
}

TEST(CgalHull, RandomPointsOnSphereMatchDirectVolume) {
  std::mt19937 random(20240611);
  std::normal_distribution<double> gaussian;
  const double radius = 2.5;
  std::vector<Vec3> points;
  for (int i = 0; i < 500; ++i) {
    const Vec3 direction(gaussian(random), gaussian(random), gaussian(random));
    points.push_back(radius * direction.normalized());
  }
  const Block hull = make_hull(points);
  // Points on a sphere are all extreme and in general position: a triangulated
  // sphere with V vertices has 2V - 4 triangles.
  EXPECT_EQ(hull.vertices().size(), 500u);
  EXPECT_EQ(hull.faces().size(), 996u);
  // Direct volume: pyramids from the sphere's centre, (1/3) area * height.
  double direct = 0.0;
  for (const FaceLoop& face : hull.faces()) {
    const Vec3& a = hull.vertices()[face[0]];
    const Vec3& b = hull.vertices()[face[1]];
    const Vec3& c = hull.vertices()[face[2]];
    const Vec3 twice_area_normal = (b - a).cross(c - a);
    EXPECT_GT(twice_area_normal.dot(a), 0.0);  // outward
    direct += twice_area_normal.dot(a) / 6.0;
  }
  EXPECT_NEAR(hull.volume(), direct, 1e-12 * direct);
  const double sphere = 4.0 / 3.0 * M_PI * radius * radius * radius;
  EXPECT_LT(hull.volume(), sphere);
  EXPECT_GT(hull.volume(), 0.95 * sphere);
  for (const Vec3& p : points) {  // every point inside or on the hull
    for (const FacePlane& plane : hull.face_planes()) {
      EXPECT_LE(plane.normal.dot(p) - plane.offset, 1e-12);
    }
  }
}

TEST(CgalHull, RejectsCoplanarFewAndNonFinitePoints) {
  std::vector<Vec3> flat;
  for (int i = 0; i < 10; ++i) {
    const double x = std::cos(i), y = std::sin(3.0 * i);
    flat.emplace_back(x, y, 0.5 * x - 2.0 * y + 1.0);
  }
  try {
    make_hull(flat);
    FAIL() << "coplanar points accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("coplanar"), std::string::npos) << error.what();
  }
  const std::vector<Vec3> collinear = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {3, 3, 3}, {0, 0, 0}};
  EXPECT_THROW(make_hull(collinear), InvalidArgument);
  EXPECT_THROW(make_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}), InvalidArgument);
  EXPECT_THROW(make_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, NAN}}), InvalidArgument);
}

// ---------------------------------------------------------------- polygon booleans

TEST(CgalPolygonBoolean, LShapeAndSquare) {
  const Loop2 square = {{0.5, 0.5}, {0.5, 1.5}, {1.5, 1.5}, {1.5, 0.5}};  // clockwise
  const auto pieces = intersect_polygon_sets({kLShape}, {square});
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_DOUBLE_EQ(shoelace(pieces[0].outer), 0.75);  // the square less its corner in the notch
  EXPECT_EQ(pieces[0].outer.size(), 6u);
  EXPECT_TRUE(pieces[0].holes.empty());
}

TEST(CgalPolygonBoolean, SeveralPieces) {
  const Loop2 u_shape = {{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  const Loop2 bar = {{-1, 2}, {4, 2}, {4, 2.5}, {-1, 2.5}};
  const auto pieces = intersect_polygon_sets({u_shape}, {bar});
  ASSERT_EQ(pieces.size(), 2u);
  for (const PolygonWithHoles2& piece : pieces) {
    EXPECT_DOUBLE_EQ(shoelace(piece.outer), 0.5);
    EXPECT_TRUE(piece.holes.empty());
  }
  // Overlapping loops of one operand count once (union).
  const Loop2 left = {{0, 0}, {2, 0}, {2, 2}, {0, 2}}, right = {{1, 0}, {3, 0}, {3, 2}, {1, 2}};
  const Loop2 all = {{-5, -5}, {5, -5}, {5, 5}, {-5, 5}};
  const auto joined = intersect_polygon_sets({left, right}, {all});
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_DOUBLE_EQ(shoelace(joined[0].outer), 6.0);
  const Loop2 far = {{10, 10}, {11, 10}, {11, 11}, {10, 11}};
  EXPECT_TRUE(intersect_polygon_sets({left}, {far}).empty());
}

TEST(CgalPolygonBoolean, HoleFromFrameOfLoops) {
  const Loop2 big = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  const std::vector<Loop2> frame = {{{1, 1}, {9, 1}, {9, 3}, {1, 3}},
                                    {{1, 7}, {9, 7}, {9, 9}, {1, 9}},
                                    {{1, 3}, {3, 3}, {3, 7}, {1, 7}},
                                    {{7, 3}, {9, 3}, {9, 7}, {7, 7}}};
  const auto pieces = intersect_polygon_sets({big}, frame);
  ASSERT_EQ(pieces.size(), 1u);
  EXPECT_DOUBLE_EQ(shoelace(pieces[0].outer), 64.0);
  ASSERT_EQ(pieces[0].holes.size(), 1u);
  EXPECT_DOUBLE_EQ(shoelace(pieces[0].holes[0]), -16.0);  // clockwise
}

TEST(CgalPolygonBoolean, SimpleLoops) {
  EXPECT_FALSE(is_simple_loop({{0, 0}, {1, 1}, {1, 0}, {0, 1}}));  // bow-tie
  EXPECT_TRUE(is_simple_loop(kLShape));
  EXPECT_TRUE(is_simple_loop({{0, 0}, {0, 1}, {1, 1}, {1, 0}}));  // clockwise is fine
  EXPECT_FALSE(is_simple_loop({{0, 0}, {1, 0}}));
  EXPECT_FALSE(is_simple_loop({{0, 0}, {1, 0}, {1, 0}, {1, 1}}));  // repeated point
  EXPECT_FALSE(is_simple_loop({{0, 0}, {1, 0}, {NAN, 1}}));
  EXPECT_THROW(intersect_polygon_sets({{{0, 0}, {1, 1}, {1, 0}, {0, 1}}}, {kLShape}),
               InvalidArgument);
}

// ---------------------------------------------------------------- self intersection

TEST(CgalSelfIntersection, ValidNonConvexBlockDoesNotIntersect) {
  const Mesh l_prism = prism_mesh(kLShape, 1.0);  // non-convex hexagons top and bottom
  EXPECT_FALSE(surface_self_intersection(l_prism.vertices, l_prism.faces));
  const Block block(l_prism.vertices, l_prism.faces);
  EXPECT_FALSE(block.convex());
  EXPECT_DOUBLE_EQ(block.volume(), 3.0);
}

TEST(CgalSelfIntersection, InterpenetratingCubesIntersect) {
  // One closed, outward-oriented surface made of two overlapping cubes.
  Mesh both = unit_cube();
  const Mesh cube = unit_cube();
  const int offset = static_cast<int>(both.vertices.size());
  for (const Vec3& p : cube.vertices) both.vertices.push_back(p + Vec3(0.5, 0.5, 0.5));
  for (FaceLoop face : cube.faces) {
    for (int& index : face) index += offset;
    both.faces.push_back(face);
  }
  // A face of the first cube (1-6) crosses one of the second (7-12).
  const std::optional<std::string> crossing = surface_self_intersection(both.vertices, both.faces);
  ASSERT_TRUE(crossing);
  EXPECT_TRUE(std::regex_match(*crossing, std::regex("faces [1-6] and ([7-9]|1[0-2]) cross each other")))
      << *crossing;
  EXPECT_THROW(Block(both.vertices, both.faces), GeometryError);
}

// ---------------------------------------------------------------- mesh repair

TEST(CgalMeshRepair, TriangleSoupCubeBecomesSixFaces) {
  const Mesh soup = triangle_soup(unit_cube());
  ASSERT_EQ(soup.faces.size(), 12u);
  ASSERT_EQ(soup.vertices.size(), 36u);
  const Block block = block_from_mesh(soup.vertices, soup.faces, 1e-6, {2000.0, "cube"}, "cube.stl");
  EXPECT_EQ(block.faces().size(), 6u);
  EXPECT_EQ(block.vertices().size(), 8u);
  for (const FaceLoop& face : block.faces()) EXPECT_EQ(face.size(), 4u);
  EXPECT_DOUBLE_EQ(block.volume(), 1.0);
  EXPECT_DOUBLE_EQ(block.mass(), 2000.0);
  EXPECT_EQ(block.name(), "cube");
}

TEST(CgalMeshRepair, NoisyDuplicatesWeldWithinTolerance) {
  Mesh soup = triangle_soup(unit_cube());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> noise(-1e-8, 1e-8);
  for (Vec3& p : soup.vertices) p += Vec3(noise(random), noise(random), noise(random));
  const Block block = block_from_mesh(soup.vertices, soup.faces, 1e-6, {}, "noisy.stl");
  EXPECT_EQ(block.vertices().size(), 8u);
  // Faces 1e-8 out of plane are not merged (merging would make the volume
  // depend on the triangulation): they stay triangles.
  EXPECT_GE(block.faces().size(), 6u);
  EXPECT_LE(block.faces().size(), 12u);
  EXPECT_NEAR(block.volume(), 1.0, 1e-7);
}

TEST(CgalMeshRepair, FanCentresMidpointsAndSliversAreRemoved) {
  // Top face fanned around its centre 8; vertex 9 splits the front top edge
  // 4-5 and is stitched to the front face by a zero-area sliver triangle.
  Mesh mesh = unit_cube();  // vertices 0-3 bottom, 4-7 top; faces 0-3 sides, 4 bottom, 5 top
  mesh.vertices.emplace_back(0.5, 0.5, 1.0);  // 8
  mesh.vertices.emplace_back(0.5, 0.0, 1.0);  // 9
  mesh.faces.pop_back();
  mesh.faces.push_back({4, 9, 8});
  mesh.faces.push_back({9, 5, 8});
  mesh.faces.push_back({5, 6, 8});
  mesh.faces.push_back({6, 7, 8});
  mesh.faces.push_back({7, 4, 8});
  mesh.faces.push_back({4, 5, 9});  // the sliver: edges 4-5, 5-9, 9-4
  const Block block = block_from_mesh(mesh.vertices, mesh.faces, 0.0, {}, "fan.obj");
  EXPECT_EQ(block.faces().size(), 6u);
  EXPECT_EQ(block.vertices().size(), 8u);
  EXPECT_DOUBLE_EQ(block.volume(), 1.0);
}

TEST(CgalMeshRepair, CoplanarPatchWithHoleStaysTriangles) {
  // A square frame with a square through-hole: its top and bottom are annuli.
  Mesh frame;
  const Loop2 outer = {{0, 0}, {3, 0}, {3, 3}, {0, 3}}, inner = {{1, 1}, {2, 1}, {2, 2}, {1, 2}};
  for (double z : {0.0, 1.0}) {
    for (const Vec2& p : outer) frame.vertices.emplace_back(p.x(), p.y(), z);
    for (const Vec2& p : inner) frame.vertices.emplace_back(p.x(), p.y(), z);
  }
  const auto o = [](int k, int level) { return 8 * level + k % 4; };
  const auto i = [](int k, int level) { return 8 * level + 4 + k % 4; };
  for (int k = 0; k < 4; ++k) {
    frame.faces.push_back({o(k, 1), o(k + 1, 1), i(k + 1, 1), i(k, 1)});  // top
    frame.faces.push_back({i(k, 0), i(k + 1, 0), o(k + 1, 0), o(k, 0)});  // bottom
    frame.faces.push_back({o(k, 0), o(k + 1, 0), o(k + 1, 1), o(k, 1)});  // outside
    frame.faces.push_back({i(k + 1, 0), i(k, 0), i(k, 1), i(k + 1, 1)});  // inside the hole
  }
  const Mesh soup = triangle_soup(frame);
  const Block block = block_from_mesh(soup.vertices, soup.faces, 1e-9, {}, "frame.stl");
  // 8 triangles on top, 8 below, 8 side quads merged back.
  EXPECT_EQ(block.faces().size(), 24u);
  EXPECT_EQ(block.vertices().size(), 16u);
  EXPECT_DOUBLE_EQ(block.volume(), 8.0);
}

TEST(CgalMeshRepair, OpenMeshIsReportedWithItsSource) {
  Mesh soup = triangle_soup(unit_cube());
  soup.faces.pop_back();
  try {
    block_from_mesh(soup.vertices, soup.faces, 1e-6, {}, "part 'lid' of box.stl");
    FAIL() << "open mesh accepted";
  } catch (const GeometryError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("part 'lid' of box.stl"), std::string::npos) << message;
    EXPECT_NE(message.find("open"), std::string::npos) << message;
  }
}

TEST(CgalMeshRepair, DefectsAreNamedInTheInputsNumbering) {
  // A cube as 12 triangles of 3 vertices each, the two triangles of its
  // last face (the top: 10 and 11) both turned over. The repair welds the
  // 36 vertices into 8 and merges each face's pair into a quad; the
  // defect is named by the input: the quad by both its triangles, a corner
  // by the first of the input vertices welded into it.
  Mesh soup = triangle_soup(unit_cube());
  ASSERT_EQ(soup.faces.size(), 12u);
  for (int t : {10, 11}) std::reverse(soup.faces[t].begin(), soup.faces[t].end());
  MeshNumbering input;
  input.vertex_name = [](int index) { return "v" + std::to_string(index); };
  input.face_name = [](int index) { return "t" + std::to_string(index); };
  const std::string message = [&] {
    try {
      block_from_mesh(soup.vertices, soup.faces, 1e-9, {}, "top.stl", input);
    } catch (const GeometryError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  }();
  // The first edge in order of its welded corners that breaks: the side
  // face 0's (triangles 0 = v0 v1 v2 and 1 = v3 v4 v5) top edge from
  // (1, 0, 1), first seen as v2, to (0, 0, 1), first seen as v5.
  EXPECT_NE(message.find("inconsistent face orientation: t0 (merged with t1) and t10 (merged with t11) run the "
                         "edge between v2 and v5 in the same direction"),
            std::string::npos)
      << message;
}

TEST(CgalMeshRepair, RejectsBadIndicesAndTolerance) {
  const Mesh cube = unit_cube();
  std::vector<FaceLoop> faces = cube.faces;
  faces[0][0] = 99;
  EXPECT_THROW(block_from_mesh(cube.vertices, faces, 0.0, {}, "bad.obj"), GeometryError);
  EXPECT_THROW(block_from_mesh(cube.vertices, cube.faces, -1.0, {}, "bad.obj"), InvalidArgument);
  EXPECT_THROW(block_from_mesh(cube.vertices, cube.faces, NAN, {}, "bad.obj"), InvalidArgument);
}

// ---------------------------------------------------------------- split

void expect_parts_add_up(const Block& block, const SplitResult& parts) {
  ASSERT_TRUE(parts.below && parts.above);
  EXPECT_NEAR(parts.below->volume() + parts.above->volume(), block.volume(),
              1e-12 * block.volume());
  const Vec3 moment = parts.below->volume() * parts.below->centroid() +
                      parts.above->volume() * parts.above->centroid();
  EXPECT_LT((moment / block.volume() - block.centroid()).norm(), 1e-12 * block.bounds().diagonal());
}

TEST(CgalSplit, BoxCutObliquely) {
  const Block box = make_box({2, 3, 4}, {0, 0, 0}, {1800.0, "pier"});
  const Vec3 normal(1, 2, 3);  // crosses the four vertical edges only
  const SplitResult parts = split_block(box, Vec3::Zero(), normal);
  expect_parts_add_up(box, parts);
  EXPECT_NEAR(parts.below->volume(), 12.0, 1e-12 * 12.0);  // symmetric about the centre
  EXPECT_EQ(parts.below->faces().size(), 6u);
  EXPECT_EQ(parts.above->faces().size(), 6u);
  EXPECT_EQ(count_faces_along(*parts.below, normal), 1u);  // the cut is one polygon
  EXPECT_EQ(count_faces_along(*parts.above, -normal), 1u);
  EXPECT_EQ(parts.below->name(), "pier below");
  EXPECT_EQ(parts.above->name(), "pier above");
  EXPECT_EQ(parts.below->density(), 1800.0);
  EXPECT_EQ(parts.above->density(), 1800.0);
  EXPECT_GT(parts.above->centroid().dot(normal), 0.0);
}

TEST(CgalSplit, CubeCutThroughAHexagon) {
  const Block cube = make_box({2, 2, 2}, {0, 0, 0});
  const Vec3 normal(1, 1, 1);
  const SplitResult parts = split_block(cube, {0.3, 0, 0}, normal);
  expect_parts_add_up(cube, parts);
  // Volume of x + y + z <= s in [-1, 1]^3 for 1 <= s + 3 <= 4, t = s + 3:
  // (t^3 - 3 (t - 2)^3) / 6.
  const double t = 3.3, below = (t * t * t - 3.0 * std::pow(t - 2.0, 3)) / 6.0;
  EXPECT_NEAR(parts.below->volume(), below, 1e-12 * below);
  EXPECT_EQ(parts.below->faces().size(), 7u);
  EXPECT_EQ(parts.above->faces().size(), 7u);
  for (const auto& part : {parts.below, parts.above}) {
    size_t hexagons = 0;
    for (const FaceLoop& face : part->faces()) hexagons += face.size() == 6 ? 1 : 0;
    EXPECT_EQ(hexagons, 1u);
    EXPECT_TRUE(part->name().empty());
  }
}

TEST(CgalSplit, NonConvexLPrism) {
  const Mesh mesh = prism_mesh(kLShape, 1.0);
  const Block l_prism(mesh.vertices, mesh.faces, 2400.0, "L");

  const SplitResult oblique = split_block(l_prism, {1, 1, 0.5}, {1, 1, 0.3});
  expect_parts_add_up(l_prism, oblique);

  // x = 1.5 cuts the foot off: the rest stays non-convex.
  const SplitResult foot = split_block(l_prism, {1.5, 0, 0}, {1, 0, 0});
  expect_parts_add_up(l_prism, foot);
  EXPECT_NEAR(foot.below->volume(), 2.5, 1e-12);
  EXPECT_NEAR(foot.above->volume(), 0.5, 1e-12);
  EXPECT_EQ(foot.below->faces().size(), 8u);
  EXPECT_FALSE(foot.below->convex());
  EXPECT_EQ(foot.above->faces().size(), 6u);

  // y = 1 contains the inner face of the foot: the cut face joins it.
  const SplitResult flush = split_block(l_prism, {0, 1, 0}, {0, 1, 0});
  expect_parts_add_up(l_prism, flush);
  EXPECT_NEAR(flush.below->volume(), 2.0, 1e-12);
  EXPECT_EQ(flush.below->faces().size(), 6u);
  EXPECT_EQ(flush.below->vertices().size(), 8u);
  EXPECT_EQ(flush.above->faces().size(), 6u);
}

TEST(CgalSplit, PlaneMissingTheBlock) {
  const Block box = make_box({1, 1, 1}, {0, 0, 0}, {2400.0, "b"});
  const SplitResult over = split_block(box, {0, 0, 2}, {0, 0, 1});
  ASSERT_TRUE(over.below);
  EXPECT_FALSE(over.above);
  EXPECT_EQ(over.below->name(), "b");
  EXPECT_DOUBLE_EQ(over.below->volume(), 1.0);
  const SplitResult on_top = split_block(box, {0, 0, 0.5}, {0, 0, -1});  // touches a face
  EXPECT_FALSE(on_top.below);
  ASSERT_TRUE(on_top.above);
  EXPECT_DOUBLE_EQ(on_top.above->volume(), 1.0);
}

TEST(CgalSplit, RejectsDegenerateNormal) {
  const Block box = make_box({1, 1, 1}, {0, 0, 0});
  EXPECT_THROW(split_block(box, Vec3::Zero(), Vec3::Zero()), InvalidArgument);
  EXPECT_THROW(split_block(box, Vec3::Zero(), Vec3(NAN, 0, 1)), InvalidArgument);
  EXPECT_THROW(split_block(box, Vec3(0, INFINITY, 0), Vec3(0, 0, 1)), InvalidArgument);
}

}  // namespace
}  // namespace ashlar
