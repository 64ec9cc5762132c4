// Writes sample.glb and sample.gltf (with its sample.bin) into the folder
// given as the only argument, for the gltf.validator test, which runs the
// Khronos glTF Validator on them. The sample exercises what the exporter
// does: coloured translucent blocks, convex and non-convex faces,
// interfaces, force arrows in compression and tension, a thrust line; and
// sample_animation.glb, a simulation of the same structure (the overhang
// topples) as an animated glTF, with a translucent block.
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "analysis/equilibrium.hpp"
#include "geometry/block_builders.hpp"
#include "io/color_map.hpp"
#include "io/simulation_export.hpp"
#include "io/mesh_io.hpp"

using namespace ashlar;

namespace {

Structure sample_structure() {
  Structure s;
  auto add = [&](Block block, bool support, const std::string& name) {
    s.add(std::make_shared<const Block>(std::move(block)), support, name);
  };
  add(make_box({6, 2, 0.5}, {0, 0, -0.25}), true, "ground");
  // A small stack with overlapping joints: each contact is a partial face.
  for (int course = 0; course < 3; ++course) {
    const double shift = course % 2 == 0 ? 0.0 : 0.25;
    add(make_box({1.0, 0.5, 0.4}, {-2.0 + shift, 0, 0.2 + 0.4 * course}), false,
        "stack " + std::to_string(course + 1));
  }
  // Non-convex top and bottom faces: the exporter must ear-clip them.
  add(make_prism({{0, -0.5, 0}, {2, -0.5, 0}, {2, 0, 0}, {1, 0, 0}, {1, 0.5, 0}, {0, 0.5, 0}},
                 {0, 0, 0.8}),
      false, "L block");
  add(make_box({1.0, 0.5, 0.3}, {1.5, 0.0, 0.95}), false, "lintel");
  add(make_hull({{2.5, -0.5, 0}, {3, -0.5, 0}, {3, 0.5, 0}, {2.5, 0.5, 0}, {2.75, 0, 0.6}}), false,
      "pyramid");
  // Overhanging its support by more than half: its interface needs tension.
  add(make_box({1.0, 0.5, 0.2}, {-1.3, 0, 1.3}), false, "overhang");
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUTPUT_FOLDER\n", argv[0]);
    return 2;
  }
  try {
    const Structure structure = sample_structure();
    std::vector<double> heights;
    for (int i = 0; i < structure.size(); ++i) heights.push_back(structure.block(i).centroid().z());
    ExportOptions options;
    options.block_colors = map_colors(heights, -0.25, 1.0, "viridis");
    options.interfaces = true;
    const EquilibriumResult result = analyze_equilibrium(structure, {});
    options.result = &result;
    options.forces = true;
    options.thrust = true;
    const std::string folder = argv[1];
    for (const char* name : {"sample.glb", "sample.gltf"}) {
      export_structure(structure, folder + "/" + name, options);
      std::printf("wrote %s/%s (%d blocks, %zu interfaces)\n", folder.c_str(), name,
                  structure.size(), structure.interfaces(options.contact)->size());
    }
    SimulationOptions run;
    run.duration = 0.3;
    const SimulationResult simulation = simulate(structure, run);
    AnimationOptions animation;
    animation.block_colors = options.block_colors;
    animation.block_colors[1].a = 0.5;
    animation.fps = 30;
    export_animation(structure, simulation, folder + "/sample_animation.glb", animation);
    std::printf("wrote %s/sample_animation.glb (%zu frames, largest displacement %.3g m)\n", folder.c_str(),
                simulation.times.size(), simulation.max_displacement);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "export_gltf_sample: %s\n", e.what());
    return 1;
  }
  return 0;
}
