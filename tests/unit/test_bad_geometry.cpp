// The engine's half of the bad-geometry catalogue (tests/lua/bad_geometry_spec.lua
// has the doors a user goes through): overlap detection, the messages of
// validation, mesh repair of back-to-back slivers, bare NaN in structure
// files, and analyses of structures with nothing to analyse.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "analysis/equilibrium.hpp"
#include "core/error.hpp"
#include "fea/fea.hpp"
#include "fea/fea_mesh.hpp"
#include "geometry/block_builders.hpp"
#include "io/structure_json.hpp"
#include "structure/overlap_detection.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

std::vector<BlockOverlap> overlaps_of(const std::vector<Block>& blocks, double tolerance = 1e-9) {
  std::vector<const Block*> pointers;
  for (const Block& b : blocks) pointers.push_back(&b);
  return detect_overlaps(pointers, tolerance);
}

// An L-shaped prism along y from -0.5 to 0.5: x from -1 to 1 up to z = 1,
// x from -1 to 0 up to z = 2 (its notch is x 0..1, z 1..2).
Block l_prism() {
  return make_prism({{-1, -0.5, 0}, {1, -0.5, 0}, {1, -0.5, 1}, {0, -0.5, 1}, {0, -0.5, 2}, {-1, -0.5, 2}},
                    {0, 1, 0});
}

Block unit_cube_at(const Vec3& center) { return make_box({1, 1, 1}, center); }

}  // namespace

// ---------------------------------------------------------------- overlaps

TEST(BadGeometryOverlaps, TouchingBlocksDoNotOverlap) {
  const Block base = unit_cube_at({0, 0, 0});
  EXPECT_TRUE(overlaps_of({base, unit_cube_at({1, 0, 0})}).empty());         // a face
  EXPECT_TRUE(overlaps_of({base, unit_cube_at({1, 1, 0})}).empty());         // an edge
  EXPECT_TRUE(overlaps_of({base, unit_cube_at({1, 1, 1})}).empty());         // a corner
  EXPECT_TRUE(overlaps_of({base, unit_cube_at({1 - 1e-10, 0.3, 0})}).empty());  // within the tolerance
}

TEST(BadGeometryOverlaps, InterpenetratingBoxesOverlapByTheirPenetration) {
  const std::vector<BlockOverlap> found =
      overlaps_of({unit_cube_at({0, 0, 0}), unit_cube_at({5, 0, 0}), unit_cube_at({0.75, 0.1, 0.2})});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].a, 0);
  EXPECT_EQ(found[0].b, 2);
  EXPECT_NEAR(found[0].depth, 0.25, 1e-12);
}

TEST(BadGeometryOverlaps, CrossedEdgesApartAreSeparatedByAnEdgeAxis) {
  // Two long bars crossing at right angles, each turned 45 degrees about its
  // own axis, one above the other: every face normal's projections overlap,
  // and only the cross product of the two bar axes separates them.
  const Block bar_x = make_box({4, 1, 1}, {0, 0, 0}).rotated(Vec3::UnitX(), kPi / 4, Vec3::Zero());
  const Block bar_y = make_box({1, 4, 1}, {0, 0, 0}).rotated(Vec3::UnitY(), kPi / 4, Vec3::Zero());
  const double apart = std::sqrt(2.0) + 1e-3;  // the two diamonds' half heights, and a gap
  EXPECT_TRUE(overlaps_of({bar_x, bar_y.translated({0, 0, apart})}).empty());
  const std::vector<BlockOverlap> crossing = overlaps_of({bar_x, bar_y.translated({0, 0, apart - 0.1})});
  ASSERT_EQ(crossing.size(), 1u);
  EXPECT_NEAR(crossing[0].depth, 0.1 - 1e-3, 1e-9);
}

TEST(BadGeometryOverlaps, NonConvexBlocksAreIntersectedExactly) {
  const Block l = l_prism();
  // Seated in the notch the box touches two faces of the L; no axis of
  // either block separates them, yet they only touch.
  EXPECT_TRUE(overlaps_of({l, unit_cube_at({0.5, 0, 1.5})}).empty());
  const std::vector<BlockOverlap> pushed = overlaps_of({l, unit_cube_at({0.4, 0, 1.5})});
  ASSERT_EQ(pushed.size(), 1u);
  EXPECT_NEAR(pushed[0].depth, 0.1, 1e-12);
  // Two L's, the second moved along y to overlap the first by 0.25 m.
  const std::vector<BlockOverlap> both = overlaps_of({l, l.translated({0, 0.75, 0})});
  ASSERT_EQ(both.size(), 1u);
  EXPECT_NEAR(both[0].depth, 0.25, 1e-12);
}

TEST(BadGeometryOverlaps, AnalysesRefuseOverlapsNamingThePairs) {
  Structure s;
  s.add(box({4, 2, 1}, {0, 0, -0.5}), true, "ground");
  s.add(box({1, 1, 1}, {0, 0, 0.4}), false, "sunk");
  const std::string message = error_of([&] { analyze_equilibrium(s, {}); });
  EXPECT_EQ(message,
            "analysis: block 1 ('ground') and block 2 ('sunk') overlap by 0.1 m (expected blocks "
            "that touch along faces, not interpenetrate; contact tolerance 4.86e-06 m)");
  EXPECT_THROW(analyze_equilibrium(s, {}), GeometryError);
  EXPECT_EQ(s.overlaps()->size(), 1u);
}

TEST(BadGeometryOverlaps, ModelsBuildWithoutOverlaps) {
  EXPECT_TRUE(semicircular_arch(24, 0.6).overlaps()->empty());
}

// ---------------------------------------------------------------- nothing to analyse

TEST(BadGeometryStructures, EmptyAndSupportOnlyStructuresAreRefused) {
  Structure empty;
  EXPECT_EQ(error_of([&] { analyze_equilibrium(empty, {}); }),
            "analysis: the structure is empty: expected at least one block that is not a support "
            "(add blocks with s:add)");
  Structure ground;
  ground.add(box({1, 1, 1}, {0, 0, 0}), true);
  EXPECT_EQ(error_of([&] { analyze_equilibrium(ground, {}); }),
            "analysis: all 1 blocks are supports: expected at least one block that is not a support");
  const FeaMesh mesh(ground, 1, 0.0);
  EXPECT_THROW(analyze_fea(ground, mesh, {}), InvalidArgument);
}

// ---------------------------------------------------------------- validation messages

TEST(BadGeometryValidation, SizesBeyondDoubleRangeAreRefusedBySize) {
  const Block cube = unit_cube_at({0.5, 0.5, 0.5});
  for (const double scale : {1e-200, 1e200}) {
    std::vector<Vec3> vertices = cube.vertices();
    for (Vec3& p : vertices) p *= scale;
    const std::string message = error_of([&] { Block(vertices, cube.faces(), 2400, "far"); });
    EXPECT_TRUE(contains(message, "block 'far' is not a valid block: its size (bounding-box diagonal) is "))
        << message;
    EXPECT_TRUE(contains(message, "expected 1e-30 to 1e+30 m")) << message;
  }
  for (const double scale : {1e-25, 1e25}) {
    std::vector<Vec3> vertices = cube.vertices();
    for (Vec3& p : vertices) p *= scale;
    EXPECT_NEAR(Block(vertices, cube.faces()).volume(), std::pow(scale, 3), 1e-12 * std::pow(scale, 3));
  }
}

TEST(BadGeometryValidation, UnnamedBlocksAreCalledSo) {
  std::vector<FaceLoop> faces = unit_cube_at({0, 0, 0}).faces();
  faces.pop_back();
  EXPECT_TRUE(contains(error_of([&] { Block(unit_cube_at({0, 0, 0}).vertices(), faces); }),
                       "unnamed block is not a valid block: open surface"));
}

// ---------------------------------------------------------------- mesh repair

TEST(BadGeometryMeshRepair, BackToBackSliversCloseAgainstEachOther) {
  // A cube's triangles, then a zero-area triangle (0, 1, 8) on the bottom
  // front edge with vertex 8 at its middle, then the front face fanned
  // through vertex 8, whose first triangle lies back to back with it (the
  // order of an STL file written face by face). Gluing either sliver into
  // a neighbour would open the surface.
  const Block cube = unit_cube_at({0.5, 0.5, 0.5});
  std::vector<Vec3> vertices = cube.vertices();
  vertices.push_back({0.5, 0, 0});
  std::vector<FaceLoop> triangles;
  for (const FaceLoop& face : cube.faces()) {
    if (face == FaceLoop{0, 1, 5, 4}) continue;
    for (size_t k = 1; k + 1 < face.size(); ++k) triangles.push_back({face[0], face[k], face[k + 1]});
  }
  triangles.insert(triangles.end(), {{0, 1, 8}, {0, 8, 1}, {0, 1, 5}, {0, 5, 4}});
  const Block repaired = block_from_mesh(vertices, triangles, 1e-12, {}, "slivers");
  EXPECT_NEAR(repaired.volume(), 1.0, 1e-12);
  EXPECT_EQ(repaired.faces().size(), 6u);
}

TEST(BadGeometryMeshRepair, FailuresSayWhatTheRepairDid) {
  // Two coincident triangles: welding leaves a flat soup.
  const std::vector<Vec3> vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const std::string message =
      error_of([&] { block_from_mesh(vertices, {{0, 1, 2}, {3, 5, 4}}, 1e-9, {}, "sheet"); });
  EXPECT_TRUE(contains(message, "sheet: unnamed block is not a valid block: needs at least 4 vertices, got 3; "
                                "welding vertices closer than 1e-09 m, dropping flat faces and merging "
                                "coplanar ones made the mesh's 2 faces and 6 vertices into 2 faces and 3 vertices"))
      << message;
}

// ---------------------------------------------------------------- structure files

TEST(BadGeometryStructureFiles, BareNanAndInfinityAreNamedByEntry) {
  const std::string head =
      R"({"format": "ashlar-structure", "version": 1, "blocks": [{"name": "NaN and Infinity",)";
  const std::string cube =
      R"("faces": [[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]]}]})";
  const auto vertices = [](const std::string& third) {
    return R"("vertices": [[0,0,0],[1,0,0],)" + third + R"(,[1,1,0],[0,0,1],[1,0,1],[0,1,1],[1,1,1]],)";
  };
  for (const std::string bad : {"NaN", "Infinity", "-Infinity"}) {
    const std::string message =
        error_of([&] { structure_from_json(head + vertices("[0," + bad + ",0]") + cube, "python.json"); });
    EXPECT_EQ(message, "python.json: blocks[0].vertices[2]: expected 3 finite numbers, got array [0,\"" +
                           bad + "\",0]");
  }
  // Inside strings they are text, and a valid file loads.
  EXPECT_EQ(structure_from_json(head + vertices("[0,1,0]") + cube, "python.json").name(0),
            "NaN and Infinity");
  // Where a string would pass, the syntax error stands.
  const std::string as_name = R"({"format": "ashlar-structure", "version": 1, "blocks": [{"name": NaN,)" +
                              vertices("[0,1,0]") + cube;
  EXPECT_TRUE(contains(error_of([&] { structure_from_json(as_name, "python.json"); }),
                       "python.json: not valid JSON: parse error"));
}
