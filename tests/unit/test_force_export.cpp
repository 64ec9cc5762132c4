// Export of analysis results: force arrows and the thrust line.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "analysis/equilibrium.hpp"
#include "core/error.hpp"
#include "geometry/block_builders.hpp"
#include "core/atomic_file.hpp"
#include "io/force_glyphs.hpp"
#include "io/mesh_io.hpp"
#include "gltf_file.hpp"
#include "test_support.hpp"

using namespace ashlar;

namespace {

// A block on the ground and a second one on it, shifted by `overhang`
// along x: it needs no tension up to 0.5, the first block's edge.
Structure overhanging_structure(double overhang) {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({4, 2, 0.5}, {0, 0, -0.25})), true, "ground");
  s.add(std::make_shared<const Block>(make_box({1, 1, 0.5}, {0, 0, 0.25})), false, "base");
  s.add(std::make_shared<const Block>(make_box({1, 1, 0.5}, {overhang, 0, 0.75})), false, "top");
  return s;
}

ExportOptions forces_and_thrust(const EquilibriumResult& result) {
  ExportOptions options;
  options.result = &result;
  options.forces = true;
  options.thrust = true;
  return options;
}


// Checks that every directed edge has its reverse exactly once (a closed,
// consistently oriented surface) and returns the enclosed volume.
double closed_volume(const GlyphFaces& faces) {
  std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> edges;
  auto key = [](const Vec3& p) { return std::array<double, 3>{p.x(), p.y(), p.z()}; };
  double volume = 0.0;
  for (const auto& face : faces) {
    for (size_t j = 0; j < face.size(); ++j) {
      const Vec3& p = face[j];
      const Vec3& q = face[(j + 1) % face.size()];
      ++edges[{key(p), key(q)}];
      if (j > 0 && j + 1 < face.size()) volume += face[0].dot(p.cross(q)) / 6.0;
    }
  }
  for (const auto& [edge, count] : edges) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(edges.count({edge.second, edge.first}), 1u);
  }
  return volume;
}

}  // namespace

TEST(ForceGlyphs, ArrowAndTubeAreClosedSolids) {
  ArrowShape shape;
  shape.shaft_radius = 0.1;
  shape.head_radius = 0.25;
  shape.head_length = 0.5;
  const GlyphFaces arrow = arrow_faces({1, 2, 3}, {1, 4, 3}, shape);  // length 2 along y
  EXPECT_EQ(arrow.size(), 1u + 3u * shape.sides);
  const double hexagon = 1.5 * std::sqrt(3.0);  // area per squared circumradius
  EXPECT_NEAR(closed_volume(arrow), hexagon * (0.01 * 1.5 + 0.0625 * 0.5 / 3.0), 1e-12);

  // An L-shaped line with a repeated point: two prisms, each closed.
  const GlyphFaces tube = tube_faces({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 0, 2}}, 0.05, 6);
  EXPECT_EQ(tube.size(), 2u * (2 + 6));
  EXPECT_NEAR(closed_volume(tube), hexagon * 0.0025 * 3.0, 1e-12);
}

TEST(MeshExport, ForceArrowsAndThrustLineAreNodes) {
  const Structure s = overhanging_structure(0.3);
  const EquilibriumResult result = analyze_equilibrium(s, {});
  ASSERT_TRUE(result.stable);
  TempDir dir;
  export_structure(s, dir.file("s.gltf"), forces_and_thrust(result));
  const GltfFile gltf(dir, "s.gltf");

  std::vector<std::string> glyphs;
  for (const auto& node : gltf.json["nodes"]) {
    const std::string name = node.value("name", "");
    if (name.rfind("force ", 0) == 0 || name == "thrust line") glyphs.push_back(name);
  }
  EXPECT_EQ(glyphs, (std::vector<std::string>{"force 1-2", "force 2-3", "thrust line"}));
  EXPECT_EQ(gltf.triangles("force 1-2"), 34);  // 4 cap + 12 shaft + 12 ring + 6 head
  EXPECT_EQ(gltf.triangles("thrust line"), 20);  // one hexagonal prism: two points

  // The arrow on the top block starts at its centre of pressure and points
  // along the resultant (the force on the top block, the one above); the
  // scale is the round number of newtons per metre (1, 2 or 5 x 10^k)
  // nearest, on a log scale, the one that draws the largest (on the base,
  // carrying both blocks) a quarter of the blocks' diagonal, 1.5 m, long.
  const InterfaceForces& top = result.interfaces[1];
  ASSERT_EQ(top.b, 2);
  Vec3 tip = top.center_of_pressure;
  for (const Vec3& p : gltf.positions("force 2-3")) {
    if ((p - top.center_of_pressure).norm() > (tip - top.center_of_pressure).norm()) tip = p;
  }
  const Vec3 arrow = tip - top.center_of_pressure;
  EXPECT_GT(arrow.normalized().dot(top.resultant.normalized()), 1 - 1e-6);
  const double largest = result.interfaces[0].resultant.norm();
  const double exact = largest / (0.25 * 1.5);  // N per m
  double newtons_per_metre = 0.0;
  for (double decade = 1.0; decade <= 1e9; decade *= 10.0) {
    for (double step : {1.0, 2.0, 5.0}) {
      const double candidate = step * decade;
      if (newtons_per_metre == 0.0 || std::abs(std::log(candidate / exact)) < std::abs(std::log(newtons_per_metre / exact))) {
        newtons_per_metre = candidate;
      }
    }
  }
  EXPECT_EQ(newtons_per_metre, 5e4);  // 2400 kg x 9.81 / 0.375 m = 62.8 kN/m
  EXPECT_NEAR(arrow.norm(), top.resultant.norm() / newtons_per_metre, 1e-6);
  EXPECT_DOUBLE_EQ(force_arrow_scale(s, forces_and_thrust(result)), 1.0 / newtons_per_metre);

  // Compression is blue; the blocks turn translucent to show the glyphs.
  EXPECT_GT(gltf.base_color("force 2-3")[2].get<double>(), gltf.base_color("force 2-3")[0]);
  EXPECT_NEAR(gltf.base_color("top")[3].get<double>(), 0.35, 1e-6);
  EXPECT_EQ(gltf.base_color("force 2-3")[3].get<double>(), 1.0);

  for (const std::string& extension : export_extensions()) {
    export_structure(s, dir.file("all" + extension), forces_and_thrust(result));
  }
  EXPECT_EQ(dir.entries().size(), 2u + 7u);  // s.gltf, s.bin; all.* with .bin and .mtl
}

// The arrow of an interface is the force on the free block, or on the
// block above, whatever the blocks' indices: a column on the ground (the
// support numbered last, as a dome's are) gets an upward reaction; in a
// stack numbered from the top every arrow points up.
TEST(ForceGlyphs, ArrowsShowTheForceOnTheFreeBlockWhateverTheIndices) {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({1, 1, 0.5}, {0, 0, 0.75})), false, "top");
  s.add(std::make_shared<const Block>(make_box({1, 1, 0.5}, {0, 0, 0.25})), false, "base");
  s.add(std::make_shared<const Block>(make_box({4, 2, 0.5}, {0, 0, -0.25})), true, "ground");
  const EquilibriumResult result = analyze_equilibrium(s, {});
  ASSERT_TRUE(result.stable);
  const auto contacts = s.interfaces({});
  ASSERT_EQ(contacts->size(), 2u);
  const double weight = 1200 * 9.81;  // each block: 0.5 m^3 x 2400 kg/m^3
  for (std::size_t k = 0; k < contacts->size(); ++k) {
    const InterfaceForces& f = result.interfaces[k];
    const ArrowForce drawn = arrow_force(s, contacts->at(k), f);
    const bool ground = f.b == 2;
    // top-base: on the top block (above), by the base; base-ground: on the base, by the ground.
    EXPECT_EQ(drawn.on, ground ? 1 : 0) << k;
    EXPECT_EQ(drawn.by, ground ? 2 : 1) << k;
    EXPECT_NEAR(drawn.force.z(), (ground ? 2 : 1) * weight, 1e-6 * weight) << k;
    EXPECT_NEAR(drawn.force.head<2>().norm(), 0.0, 1e-6 * weight) << k;
  }

  // The exported arrows rise from their centres of pressure.
  TempDir dir;
  ExportOptions options = forces_and_thrust(result);
  options.thrust = false;
  export_structure(s, dir.file("s.gltf"), options);
  const GltfFile gltf(dir, "s.gltf");
  for (const auto& [name, k] : {std::pair<std::string, int>{"force 1-2", 0}, {"force 2-3", 1}}) {
    const Vec3& start = result.interfaces[k].center_of_pressure;
    double highest = -1e9, lowest = 1e9;
    for (const Vec3& p : gltf.positions(name)) {
      highest = std::max(highest, p.z());
      lowest = std::min(lowest, p.z());
    }
    const double length = force_arrow_scale(s, options) * result.interfaces[k].resultant.norm();
    EXPECT_NEAR(highest, start.z() + length, 1e-6) << name;
    EXPECT_NEAR(lowest, start.z(), 1e-6) << name;
  }
}

TEST(MeshExport, CablesAreTubesBetweenTheirEnds) {
  Structure s = overhanging_structure(0.3);
  Cable cable;
  cable.from = {0, {1.5, 0, 0}};
  cable.to = {2, {0.3, 0, 1.0}};
  s.add_cable(cable);
  TempDir dir;
  export_structure(s, dir.file("s.gltf"), {});  // cables need no result
  const GltfFile gltf(dir, "s.gltf");
  EXPECT_EQ(gltf.triangles("cable 1"), 20);  // one hexagonal prism
  // Every tube vertex lies at the cable's radius from its axis, between
  // its ends: 2% of the mean free-block size (diagonal 1.5 m).
  const Vec3 axis = (cable.to.point - cable.from.point).normalized();
  const double radius = 0.02 * 1.5;
  for (const Vec3& p : gltf.positions("cable 1")) {
    const Vec3 offset = p - cable.from.point;
    const double along = offset.dot(axis);
    EXPECT_NEAR((offset - along * axis).norm(), radius, 1e-6);
    EXPECT_GT(along, -1e-6);
    EXPECT_LT(along, (cable.to.point - cable.from.point).norm() + 1e-6);
  }
  EXPECT_LT(gltf.base_color("cable 1")[0].get<double>(), 0.3);  // dark, opaque
  EXPECT_EQ(gltf.base_color("cable 1")[3].get<double>(), 1.0);
}

TEST(MeshExport, TensionGetsARedArrow) {
  const Structure s = overhanging_structure(0.7);
  const EquilibriumResult result = analyze_equilibrium(s, {});
  ASSERT_FALSE(result.stable);
  ASSERT_GT(result.interfaces[1].tension, 0.0);
  TempDir dir;
  ExportOptions options = forces_and_thrust(result);
  options.block_opacity = 1.0;
  export_structure(s, dir.file("s.gltf"), options);
  const GltfFile gltf(dir, "s.gltf");
  EXPECT_GT(gltf.base_color("force 2-3")[0].get<double>(), gltf.base_color("force 2-3")[2]);
  EXPECT_EQ(gltf.base_color("top")[3].get<double>(), 1.0);
}

TEST(MeshExport, ForcesNeedAResultOfThisStructure) {
  TempDir dir;
  const Structure s = overhanging_structure(0.3);
  ExportOptions options;
  options.forces = true;
  std::string message = error_of([&] { export_structure(s, dir.file("s.glb"), options); });
  EXPECT_TRUE(contains(message, "forces needs the result")) << message;
  options.forces = false;
  options.thrust = true;
  message = error_of([&] { export_structure(s, dir.file("s.glb"), options); });
  EXPECT_TRUE(contains(message, "thrust needs the result")) << message;

  Structure fewer;
  fewer.add(std::make_shared<const Block>(s.block(0)), true);
  fewer.add(std::make_shared<const Block>(s.block(1)));
  const EquilibriumResult of_fewer = analyze_equilibrium(fewer, {});
  message = error_of([&] { export_structure(s, dir.file("s.glb"), forces_and_thrust(of_fewer)); });
  EXPECT_TRUE(contains(message, "2 blocks, this one has 3")) << message;

  // As many blocks, but the third lifted off: other interfaces.
  Structure lifted = fewer;
  lifted.add(std::make_shared<const Block>(make_box({1, 1, 0.5}, {0, 0, 2})));
  const EquilibriumResult of_lifted = analyze_equilibrium(lifted, {});
  message = error_of([&] { export_structure(s, dir.file("s.glb"), forces_and_thrust(of_lifted)); });
  EXPECT_TRUE(contains(message, "interfaces")) << message;
  EXPECT_TRUE(dir.entries().empty());
}

// ---------------------------------------------------------------------------
// Colour maps
