// The pictures of issue 53 that the engine builds: the thrust network of
// vaults and domes, the per-vertex force arrows (normal and friction parts)
// and the viewer page that plays a collapse mechanism.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "analysis/equilibrium.hpp"
#include "analysis/mechanism.hpp"
#include "core/atomic_file.hpp"
#include "geometry/block_builders.hpp"
#include "io/force_glyphs.hpp"
#include "io/mesh_io.hpp"
#include "io/structure_scene.hpp"
#include "io/viewer_page.hpp"
#include "structure/structure_transform.hpp"
#include "test_support.hpp"

using namespace ashlar;
using nlohmann::json;

namespace {

// Ground and three free blocks in a row along x (the forces below are set
// by hand: the network only reads them).
Structure row_of_blocks() {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({4, 1, 0.5}, {0, 0, -0.25})), true, "ground");
  for (int i = 0; i < 3; ++i) {
    s.add(std::make_shared<const Block>(make_box({1, 1, 1}, {i - 1.0, 0, 0.5})), false, "block " + std::to_string(i));
  }
  return s;
}

InterfaceForces joint(int a, int b, double normal_force, const Vec3& resultant, const Vec3& center) {
  InterfaceForces f;
  f.a = a;
  f.b = b;
  f.normal_force = normal_force;
  f.compression = normal_force;
  f.resultant = resultant;
  f.center_of_pressure = center;
  return f;
}

Interface facing(const Vec3& normal) {
  Interface contact;
  contact.normal = normal.normalized();
  return contact;
}

std::string read_page(const std::string& path) { return read_file(path); }

bool same_color(const Rgb& x, const Rgb& y) { return x.r == y.r && x.g == y.g && x.b == y.b && x.a == y.a; }

json scene_of(const std::string& page) {
  const std::string open = "<script type=\"application/json\" id=\"ashlar-scene\">";
  const auto start = page.find(open) + open.size();
  return json::parse(page.substr(start, page.find("</script>", start) - start));
}

}  // namespace

TEST(ThrustNetwork, TubesRunFromCentroidsToCentresOfPressureAsThickAsTheForce) {
  const Structure s = row_of_blocks();
  EquilibriumResult result;
  // Ground under block 1 with 4 N, blocks 1-2 with 1 N, blocks 2-3 merely touching.
  result.interfaces = {joint(0, 1, 4.0, {0, 0, 4}, {-1, 0, 0}), joint(1, 2, 1.0, {1, 0, 0}, {-0.5, 0, 0.5}),
                       joint(2, 3, 1e-6, {1e-6, 0, 0}, {0.5, 0, 0.5})};
  const std::vector<TubeSegment> tubes = thrust_network(s, result, 0.2);
  // The ground's joint: one tube (the ground has no centroid in the network);
  // the joint between two free blocks: one from each; the third: none.
  ASSERT_EQ(tubes.size(), 3u);
  EXPECT_EQ(tubes[0].from, s.block(1).centroid());
  EXPECT_EQ(tubes[0].to, Vec3(-1, 0, 0));
  EXPECT_DOUBLE_EQ(tubes[0].radius, 0.2);  // the largest force
  EXPECT_EQ(tubes[1].from, s.block(1).centroid());
  EXPECT_EQ(tubes[2].from, s.block(2).centroid());
  for (const int k : {1, 2}) {
    EXPECT_EQ(tubes[k].to, Vec3(-0.5, 0, 0.5));
    // A quarter of the force: a quarter of the cross-section, half the radius.
    EXPECT_DOUBLE_EQ(tubes[k].radius, 0.1);
  }
}

TEST(ThrustNetwork, JointsFacingOneVerticalPlaneKeepTheLine) {
  const Structure s = row_of_blocks();
  EquilibriumResult result;
  const Vec3 center = Vec3::Zero();
  result.interfaces = {joint(0, 1, 1.0, {0, 0, 1}, center), joint(1, 2, 1.0, {1, 0, 1}, center),
                       joint(2, 3, 1.0, {-1, 0, 1}, center)};
  // Level, and leaning in the x-z plane: an arch.
  std::vector<Interface> contacts = {facing({0, 0, 1}), facing({1, 0, 1}), facing({-1, 0, 1})};
  EXPECT_TRUE(thrust_in_one_plane(s, contacts, result));
  // A joint in compression leaning along y too: a vault.
  contacts[2] = facing({0, 1, 1});
  EXPECT_FALSE(thrust_in_one_plane(s, contacts, result));
  // Unless it carries nothing.
  result.interfaces[2].normal_force = 0.0;
  EXPECT_TRUE(thrust_in_one_plane(s, contacts, result));
  // A planar structure always keeps its line.
  result.interfaces[2].normal_force = 1.0;
  Structure planar = row_of_blocks();
  planar.set_planar(true);
  EXPECT_TRUE(thrust_in_one_plane(planar, contacts, result));
}

// A block on a table tilted by 0.2 rad (friction 0.7 > tan 0.2: it stands):
// the normal parts of its joint's vertex forces add up to m g cos(theta),
// the friction parts to m g sin(theta) up the slope, all on the block.
TEST(VertexForces, NormalAndFrictionPartsBalanceTheWeightOnASlope) {
  Structure flat;
  flat.add(std::make_shared<const Block>(make_box({3, 2, 0.5}, {0, 0, -0.25})), true, "table");
  flat.add(std::make_shared<const Block>(make_box({1, 1, 0.6}, {0, 0, 0.3})), false, "block");
  const double theta = 0.2;
  const Structure s = rotated(flat, Vec3::UnitY(), theta, base_center(flat));
  const EquilibriumResult result = analyze_equilibrium(s, with_friction(0.7));
  ASSERT_TRUE(result.stable);
  ExportOptions options;
  options.result = &result;
  options.forces = true;
  options.force_mode = ForceMode::vertices;
  const double weight = s.block(1).mass() * kGravity;
  Vec3 normal = Vec3::Zero(), friction = Vec3::Zero();
  int normal_arrows = 0, friction_arrows = 0;
  for (const SceneObject& object : structure_scene(s, options)) {
    if (object.layer != SceneLayer::forces) continue;
    ASSERT_TRUE(object.arrow.has_value()) << object.name;
    // The arrow is the force it draws, at the scale of the page.
    EXPECT_NEAR((object.arrow->tip - object.arrow->tail - force_arrow_scale(s, options) * object.arrow->force).norm(),
                0.0, 1e-12);
    if (object.name.rfind("friction 1-2 vertex ", 0) == 0) {
      friction += object.arrow->force;
      ++friction_arrows;
      EXPECT_TRUE(same_color(object.color, options.friction_color)) << object.name;
    } else {
      EXPECT_EQ(object.name.rfind("force 1-2 vertex ", 0), 0u) << object.name;
      normal += object.arrow->force;
      ++normal_arrows;
      EXPECT_TRUE(same_color(object.color, options.compression_color)) << object.name;
    }
  }
  EXPECT_GE(normal_arrows, 3);
  EXPECT_GE(friction_arrows, 1);
  // The slope's normal and its upward direction (gravity along -z).
  const Vec3 up_normal(std::sin(theta), 0.0, std::cos(theta));
  const Vec3 up_slope(-std::cos(theta), 0.0, std::sin(theta));
  EXPECT_NEAR(normal.dot(up_normal), weight * std::cos(theta), 1e-5 * weight);
  EXPECT_NEAR(friction.dot(up_slope), weight * std::sin(theta), 1e-5 * weight);
  EXPECT_NEAR((normal + friction - Vec3(0, 0, weight)).norm(), 0.0, 1e-5 * weight);
}

// A mechanism's page: the blocks drawn where they stand and a track per
// free block, rest - extreme - rest, the extreme the rigid motion that
// moves the fastest centroid `scale` metres (a quaternion of half the angle).
TEST(ViewerPage, PlaysTheMechanismFromRestToItsExtreme) {
  const Structure s = row_of_blocks();
  std::vector<BlockMotion> mechanism(s.size());
  mechanism[1].velocity = Vec3(1, 0, 0);
  mechanism[2].velocity = Vec3(0.5, 0, -0.5);
  mechanism[2].rotation = Vec3(0, 2, 0);
  std::vector<LimitInterface> limit(1);
  const auto contacts = s.interfaces(ContactOptions{});
  for (std::size_t k = 0; k < contacts->size(); ++k) {
    if ((*contacts)[k].a == 0 && (*contacts)[k].b == 2) limit[0].interface = static_cast<int>(k);
  }
  limit[0].pivot = Vec3(-0.5, 0, 0);
  const TempDir dir;
  ExportOptions options;
  options.mechanism = &mechanism;
  options.limit = &limit;
  options.mechanism_scale = 0.3;
  options.autoplay = false;
  const std::string path = dir.path() + "/mechanism.html";
  write_viewer_page(s, path, options);
  const json scene = scene_of(read_page(path));
  const json& animation = scene["animation"];
  EXPECT_EQ(animation["times"], json({0.0, 1.0, 2.0}));
  EXPECT_EQ(animation["start"], 1.0);
  EXPECT_EQ(animation["mechanism"], 0.3);
  EXPECT_EQ(animation["autoplay"], false);
  ASSERT_EQ(animation["tracks"].size(), 3u);
  const json& objects = scene["objects"];
  for (int i = 1; i <= 3; ++i) {
    const json& track = animation["tracks"][i - 1];
    const Vec3 centroid = s.block(i).centroid();
    // Its own block first; block 2 also carries the hinge on its ground joint.
    EXPECT_EQ(objects[track["objects"][0].get<int>()]["name"], s.name(i));
    EXPECT_EQ(track["objects"].size(), i == 2 ? 2u : 1u);
    if (i == 2) {
      EXPECT_EQ(objects[track["objects"][1].get<int>()]["name"], "hinge 1-3");
    }
    const Vec3 moved = centroid + 0.3 * mechanism[i].velocity;
    const double half = 0.3 * mechanism[i].rotation.norm() / 2.0;
    const std::vector<double> positions = track["positions"], rotations = track["rotations"];
    ASSERT_EQ(positions.size(), 9u);
    ASSERT_EQ(rotations.size(), 12u);
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(positions[axis], centroid[axis], 1e-6);
      EXPECT_NEAR(positions[3 + axis], moved[axis], 1e-6);
      EXPECT_NEAR(positions[6 + axis], centroid[axis], 1e-6);
    }
    // (x y z w) at the extreme: about +y by 0.3 x |rotation|.
    EXPECT_NEAR(rotations[4 + 1], i == 2 ? std::sin(half) : 0.0, 1e-6);
    EXPECT_NEAR(rotations[4 + 3], std::cos(half), 1e-6);
    EXPECT_NEAR(rotations[3], 1.0, 1e-7);  // rest
  }
  // Drawn where they stand: every outline point within the structure's bounds.
  const std::vector<double> outline = scene["outline"];
  const Box3 bounds = s.bounds();
  for (std::size_t k = 0; k < outline.size(); ++k) {
    EXPECT_GE(outline[k], bounds.lo[k % 3] - 1e-6);
    EXPECT_LE(outline[k], bounds.hi[k % 3] + 1e-6);
  }
  // The automatic extreme: 5 % of the structure's size.
  options.mechanism_scale = 0.0;
  write_viewer_page(s, path, options);
  EXPECT_NEAR(scene_of(read_page(path))["animation"]["mechanism"].get<double>(), 0.05 * s.bounds().diagonal(), 1e-12);
  // Not played: a still.
  options.animate_mechanism = false;
  write_viewer_page(s, path, options);
  EXPECT_TRUE(scene_of(read_page(path))["animation"].is_null());
}
