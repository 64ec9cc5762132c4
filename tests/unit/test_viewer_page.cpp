// The HTML viewer's page: the scene objects it shares with the mesh files,
// and the page itself read back as a browser would read its JSON.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "analysis/equilibrium.hpp"
#include "core/atomic_file.hpp"
#include "core/error.hpp"
#include "dynamics/simulation.hpp"
#include "geometry/block_builders.hpp"
#include "io/color_map.hpp"
#include "io/mesh_io.hpp"
#include "io/simulation_export.hpp"
#include "io/structure_scene.hpp"
#include "io/viewer_page.hpp"
#include "io/web_assets.hpp"
#include "test_support.hpp"

using namespace ashlar;
using nlohmann::json;

namespace {

// Ground, a block on it and a second block shifted along x on that one; the
// top block's name would end a <script> element if written as it is.
Structure stack() {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({4, 2, 0.5}, {0, 0, -0.25})), true, "ground");
  s.add(std::make_shared<const Block>(make_box({1, 1, 0.5}, {0, 0, 0.25})), false, "base");
  s.add(std::make_shared<const Block>(make_box({1, 1, 0.5}, {0.3, 0, 0.75})), false, "</script><!-- top");
  return s;
}

// The text of the <script type="application/json"> element with this id.
std::string script_text(const std::string& page, const std::string& id) {
  const std::string open = "<script type=\"application/json\" id=\"" + id + "\">";
  const auto start = page.find(open);
  EXPECT_NE(start, std::string::npos) << id;
  const auto end = page.find("</script>", start);
  return page.substr(start + open.size(), end - start - open.size());
}

// Runs `call`, which must throw E with `part` in its message.
template <class E, class Call>
void expect_error(Call call, const std::string& part) {
  try {
    call();
    ADD_FAILURE() << "no error; expected one with: " << part;
  } catch (const E& error) {
    EXPECT_NE(std::string(error.what()).find(part), std::string::npos) << error.what();
  }
}

int count(const std::string& text, const std::string& part) {
  int n = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

}  // namespace

TEST(StructureScene, ObjectsCarryTheirLayerAndWhatTheyDraw) {
  const Structure s = stack();
  const EquilibriumResult result = analyze_equilibrium(s, {});
  ASSERT_TRUE(result.stable);
  ExportOptions options;
  options.result = &result;
  options.forces = true;
  options.thrust = true;
  options.interfaces = true;
  const std::vector<SceneObject> objects = structure_scene(s, options);

  std::vector<std::string> names;
  for (const SceneObject& object : objects) names.push_back(object.name);
  EXPECT_EQ(names, (std::vector<std::string>{"ground", "base", "</script><!-- top", "interface 1-2", "interface 2-3",
                                             "force 1-2", "force 2-3", "thrust line"}));
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(objects[i].layer, SceneLayer::blocks);
    EXPECT_EQ(objects[i].block, i);
    EXPECT_EQ(objects[i].outline.size(), 12u);  // a box's edges
    EXPECT_EQ(objects[i].mesh.triangles.size(), 12u);
    EXPECT_NEAR(objects[i].opacity, 0.35, 1e-12);  // glyphs inside
  }
  // Interfaces and arrows name the interface they draw.
  for (int k = 0; k < 2; ++k) {
    EXPECT_EQ(objects[3 + k].layer, SceneLayer::interfaces);
    EXPECT_EQ(objects[5 + k].layer, SceneLayer::forces);
    EXPECT_EQ(objects[3 + k].interface, k);
    EXPECT_EQ(objects[5 + k].interface, k);
    EXPECT_EQ(result.interfaces[k].a, k);
  }
  EXPECT_EQ(objects[7].layer, SceneLayer::thrust);
}

TEST(ViewerPage, HoldsTheSceneAndEveryScriptWhateverTheNames) {
  const Structure s = stack();
  const EquilibriumResult result = analyze_equilibrium(s, {});
  ExportOptions options;
  options.result = &result;
  options.forces = true;
  options.thrust = true;
  options.edges = false;
  options.color_scale = ColorScale{{0.0, 1.0, 3.0}, 0.0, 2.0, "coolwarm", "load (kN)"};
  options.block_colors = map_colors(options.color_scale->values, 0.0, 2.0, "coolwarm");
  options.title = "a <stack> & more";
  TempDir dir;
  export_structure(s, dir.file("stack.html"), options);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"stack.html"});
  const std::string page = read_file(dir.file("stack.html"));

  // Only the page's own three scripts end an element; the block's name is
  // in the JSON as \u003c.
  EXPECT_EQ(count(page, "</script>"), 3);
  EXPECT_EQ(count(page, "<!--"), 1);  // the page's own comment
  EXPECT_NE(page.find("<title>a &lt;stack&gt; &amp; more</title>"), std::string::npos);
  EXPECT_EQ(page.find('@' + std::string("SCENE@")), std::string::npos);

  const json scene = json::parse(script_text(page, "ashlar-scene"));
  EXPECT_EQ(scene["title"], "a <stack> & more");
  EXPECT_EQ(scene["summary"], "3 blocks: stable (equilibrium method, solver converged)");
  std::vector<std::string> layers;
  for (const json& layer : scene["layers"]) {
    layers.push_back(layer["name"]);
    EXPECT_EQ(layer["visible"], layer["name"] != "edges");  // edges = false: outlines hidden at first
  }
  EXPECT_EQ(layers, (std::vector<std::string>{"blocks", "forces", "thrust", "edges"}));
  EXPECT_EQ(scene["outline"].size(), 3u * 12u * 2u * 3u);  // 3 boxes, 12 edges, 2 points, xyz
  EXPECT_DOUBLE_EQ(scene["opacity"].get<double>(), 0.35);
  EXPECT_TRUE(scene["animation"].is_null());  // a still: no player

  const json& top = scene["objects"][2];
  EXPECT_EQ(top["name"], "</script><!-- top");
  EXPECT_EQ(top["layer"], "blocks");
  EXPECT_EQ(top["positions"].size(), 3u * 24u);  // 6 quads, 4 corners each
  EXPECT_EQ(top["triangles"].size(), 3u * 12u);
  const Rgb expected = options.block_colors[2];
  EXPECT_EQ(top["color"], json({expected.r, expected.g, expected.b, expected.a}));
  EXPECT_EQ(top["info"][0], json({"block", "3 of 3"}));
  EXPECT_EQ(top["info"][1], json({"kind", "free block"}));
  EXPECT_EQ(top["info"][2], json({"mass", "1200 kg"}));
  EXPECT_EQ(top["info"][3], json({"load (kN)", "3"}));

  // The arrow on the top block reads its interface's forces.
  const json& arrow = scene["objects"][4];
  EXPECT_EQ(arrow["name"], "force 2-3");
  EXPECT_EQ(arrow["info"][0], json({"between", "base and </script><!-- top"}));
  EXPECT_EQ(arrow["info"][2][0], "normal force");
  EXPECT_EQ(arrow["info"][2][1], "11.77 kN (compression)");  // 1200 kg x 9.81
  EXPECT_EQ(arrow["info"][3], json({"resultant", "11.77 kN on </script><!-- top by base"}));
  // It is held as its ends and proportions (the page builds its facets):
  // from the centre of pressure, 11.77 kN at 50 kN per m up, its shaft 6 %
  // of the largest arrow's length (23.54 kN: 0.4709 m) wide, 6 sides.
  ASSERT_EQ(arrow["arrow"].size(), 10u);
  EXPECT_FALSE(arrow.contains("positions"));
  const InterfaceForces& upper = result.interfaces[1];
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(arrow["arrow"][axis].get<double>(), upper.center_of_pressure[axis], 1e-5);
    EXPECT_NEAR(arrow["arrow"][3 + axis].get<double>(),
                upper.center_of_pressure[axis] + upper.resultant[axis] / 5e4, 1e-5);
  }
  EXPECT_NEAR(arrow["arrow"][6].get<double>(), 0.06 * 2 * 1200 * 9.81 / 5e4, 1e-5);
  EXPECT_EQ(arrow["arrow"][9], 6);

  // The key names the colour of each role drawn; the scale bar's scale:
  // 2400 kg x 9.81 on the ground, about a quarter of the blocks'
  // diagonal (1.5 m) long: 62.8 kN/m, rounded to 50 kN per metre.
  std::vector<std::string> roles;
  for (const json& entry : scene["key"]) roles.push_back(entry["label"]);
  EXPECT_EQ(roles, (std::vector<std::string>{"compression", "tension", "thrust line"}));
  EXPECT_EQ(scene["key"][0]["color"],
            json({options.compression_color.r, options.compression_color.g, options.compression_color.b}));
  EXPECT_NEAR(scene["force_scale"].get<double>(), 2e-5, 1e-17);
  EXPECT_EQ(scene["planar"], false);

  // The legend: the map sampled from lo to hi.
  const json& legend = scene["legend"];
  EXPECT_EQ(legend["label"], "load (kN)");
  EXPECT_EQ(legend["lo"], "0");
  EXPECT_EQ(legend["hi"], "2");
  ASSERT_EQ(legend["stops"].size(), 33u);
  const Rgb low = map_colors({0.0}, 0.0, 1.0, "coolwarm")[0], high = map_colors({1.0}, 0.0, 1.0, "coolwarm")[0];
  EXPECT_EQ(legend["stops"][0], json({low.r, low.g, low.b}));
  EXPECT_EQ(legend["stops"][32], json({high.r, high.g, high.b}));

  // The scripts come back exactly as embedded.
  const json modules = json::parse(script_text(page, "ashlar-modules"));
  EXPECT_EQ(modules["three.core"].get<std::string>(), web_asset(WebAsset::three_core));
  EXPECT_EQ(modules["three.module"].get<std::string>(), web_asset(WebAsset::three_module));
  EXPECT_EQ(modules["OrbitControls"].get<std::string>(), web_asset(WebAsset::orbit_controls));
  EXPECT_EQ(modules["viewer"].get<std::string>(), web_asset(WebAsset::viewer_script));
  EXPECT_GT(web_asset(WebAsset::three_core).size(), 100000u);
}

TEST(ViewerPage, RefusesBadOptionsAndLeavesNoFile) {
  const Structure s = stack();
  TempDir dir;
  ExportOptions options;
  options.color_scale = ColorScale{{1.0, 2.0}, 0.0, 1.0, "viridis", ""};
  expect_error<InvalidArgument>([&] { write_viewer_page(s, dir.file("a.html"), options); },
                                "export: color_scale needs one value per block (3), got 2");
  options.color_scale = ColorScale{{1.0, 2.0, 3.0}, 0.0, 1.0, "rainbow", ""};
  EXPECT_THROW(write_viewer_page(s, dir.file("a.html"), options), InvalidArgument);
  options.color_scale.reset();
  options.forces = true;
  EXPECT_THROW(write_viewer_page(s, dir.file("a.html"), options), InvalidArgument);  // no result
  EXPECT_THROW(write_viewer_page(s, dir.file("missing/a.html"), ExportOptions{}), IoError);
  EXPECT_TRUE(dir.entries().empty());
  expect_error<InvalidArgument>([&] { export_structure(s, dir.file("a.htm"), ExportOptions{}); },
                                "use one of: .glb, .gltf, .obj, .ply, .stl, .html");
}

namespace {

// Ground and a block 0.3 m above it, falling freely for 0.2 s (0.196 m).
Structure drop() {
  Structure s;
  s.add(std::make_shared<const Block>(make_box({4, 2, 0.5}, {0, 0, -0.25})), true, "ground");
  s.add(std::make_shared<const Block>(make_box({1, 1, 0.5}, {0.5, 0, 0.55})), false, "falling");
  return s;
}

SimulationResult fall(const Structure& s) {
  SimulationOptions options;
  options.duration = 0.2;
  return simulate(s, options);
}

// Track k's pose at key frame f equals `pose` to single precision.
void expect_pose(const json& track, std::size_t f, const RigidPose& pose) {
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(track["positions"][3 * f + axis].get<double>(), pose.position[axis], 1e-6);
  }
  const double q[4] = {pose.rotation.x(), pose.rotation.y(), pose.rotation.z(), pose.rotation.w()};
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(track["rotations"][4 * f + c].get<double>(), q[c], 1e-6);
}

}  // namespace

TEST(ViewerPage, AnimationTracksHoldTheSimulationsKeyFrames) {
  const Structure s = drop();
  const SimulationResult r = fall(s);
  ASSERT_TRUE(r.moved);
  ExportOptions options;
  options.edges = true;
  TempDir dir;
  for (double fps : {30.0, 0.0}) {
    write_viewer_page(s, r, fps, dir.file("drop.html"), options);
    const json scene = json::parse(script_text(read_file(dir.file("drop.html")), "ashlar-scene"));
    const json& animation = scene["animation"];
    EXPECT_EQ(animation["autoplay"], true);  // the default: it plays as it opens
    const AnimationFrames frames = animation_frames(r, fps);
    const std::size_t n = frames.times.size();
    // 30 fps: 0, 1/30, ..., then the end; 0: every recorded frame.
    EXPECT_EQ(n, fps > 0 ? 7u : r.times.size()) << fps;
    ASSERT_EQ(animation["times"].size(), n);
    EXPECT_EQ(animation["times"][0], 0.0);
    EXPECT_NEAR(animation["times"][n - 1].get<double>(), r.time, 1e-7);

    // One track, the free block's; the ground stands still.
    ASSERT_EQ(animation["tracks"].size(), 1u);
    const json& track = animation["tracks"][0];
    EXPECT_EQ(track["objects"], json({1}));  // its block, which carries nothing else
    EXPECT_EQ(scene["objects"][1]["name"], "falling");
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_NEAR(track["centroid"][axis].get<double>(), Vec3(0.5, 0.0, 0.55)[axis], 1e-12);
    }
    EXPECT_EQ(track["outline"], json({24, 48}));  // after the ground's 12 edges, its own 12
    ASSERT_EQ(track["positions"].size(), 3 * n);
    ASSERT_EQ(track["rotations"].size(), 4 * n);
    expect_pose(track, 0, r.poses.front()[1]);
    expect_pose(track, n - 1, r.poses.back()[1]);
    for (std::size_t f = 0; f < n; ++f) expect_pose(track, f, frames.poses[f][1]);
    // Free fall: z drops by g t^2 / 2 (to the time step's accuracy).
    EXPECT_NEAR(track["positions"][3 * n - 1].get<double>(), 0.55 - 0.5 * 9.81 * 0.04, 2e-3);
    EXPECT_NE(scene["summary"].get<std::string>().find("2 blocks, simulated for 0.2 s: moved"), std::string::npos)
        << scene["summary"];
  }
}

TEST(ViewerPage, AnimatedPageRefusesStillsOptionsAndOtherStructures) {
  const Structure s = drop();
  const SimulationResult r = fall(s);
  TempDir dir;
  ExportOptions options;
  options.interfaces = true;
  expect_error<InvalidArgument>([&] { write_viewer_page(s, r, 30.0, dir.file("a.html"), options); },
                                "export: an animated page draws the blocks and their edges");
  expect_error<InvalidArgument>([&] { write_viewer_page(s, r, -1.0, dir.file("a.html"), ExportOptions{}); },
                                "export: fps must be a number of frames per second > 0 (0: the recorded "
                                "frames), got -1");
  expect_error<InvalidArgument>([&] { write_viewer_page(stack(), r, 30.0, dir.file("a.html"), ExportOptions{}); },
                                "export: the simulation is of a structure with 2 blocks, this one has 3");
  EXPECT_TRUE(dir.entries().empty());
}
