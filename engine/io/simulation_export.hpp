// A simulation as an animated glTF 2.0 binary (.glb): the blocks moving as
// the run recorded them, playable in any glTF viewer.
#pragma once

#include <string>
#include <vector>

#include "dynamics/simulation.hpp"
#include "io/color.hpp"
#include "structure/structure.hpp"

namespace ashlar {

struct AnimationOptions {
  // One colour per block (size() == structure.size()), or empty for the
  // default grey.
  std::vector<Rgb> block_colors;
  // Key frames per second of simulated time (> 0), each pose interpolated
  // between the recorded frames (poses_at); 0: the recorded frames as they are.
  double fps = 0.0;
};

// Throws InvalidArgument (messages beginning "export: ") when `result` is
// not a simulation of `structure` (other block count) or fps is not a
// number >= 0.
void check_animation(const Structure& structure, const SimulationResult& result, double fps);

// The key frames of an animation: times (s of simulated time), strictly
// increasing in single precision, and every block's pose at each. fps > 0:
// k / fps for every k up to the end, then the last recorded frame, each
// interpolated between the recorded frames around it (poses_at); 0: the
// recorded frames as they are. The .glb and the HTML viewer's player both
// play these.
struct AnimationFrames {
  std::vector<float> times;
  std::vector<std::vector<RigidPose>> poses;
};
AnimationFrames animation_frames(const SimulationResult& result, double fps);

// Writes `result`, a simulation of `structure`, to `path` (.glb): one node
// per block, named after it, holding its flat-shaded mesh about its centroid;
// one animation "simulation" with a translation and a rotation channel per
// free block (linear interpolation, times in seconds of simulated time).
// glTF is +Y up: coordinates turn (x, y, z) -> (x, z, -y), as the static
// exports do. Single-precision floats. Written atomically.
// Throws InvalidArgument for another extension, a result of another
// structure (other block count), bad colours or fps; IoError on failure.
void export_animation(const Structure& structure, const SimulationResult& result, const std::string& path,
                      const AnimationOptions& options);

}  // namespace ashlar
