// The interactive HTML viewer: ashlar.export to a .html file.
//
// One self-contained page that opens offline in any browser with WebGL:
// web/viewer.html with the scene (the objects of structure_scene.hpp, the
// very ones the mesh files hold, as JSON) and every script inlined: the
// viewer (web/viewer.js) and three.js with its OrbitControls, embedded in
// the engine at build time from web/node_modules (web_assets.hpp). The page
// turns and zooms, draws block outlines, colours blocks with a legend when
// options.color_scale says what the colours mean, shows the name and values
// of the block, arrow or interface under the pointer, and switches each
// layer (blocks, edges, interfaces, forces, thrust, cables, traces) on and
// off. The scene also holds "key" (the colour of each role drawn, with its
// label), "force_scale" (the arrows' metres per newton, force_arrow_scale
// in force_glyphs.hpp, for the page's scale bar; null without arrows) and
// "planar" (the structure lies in the x-z plane: the page opens in the
// front view, orthographic). The page of a simulation also plays it, from
// the moment it opens unless options.autoplay is false: play and pause, a
// time slider, the time, and looping.
//
// The page of a still whose options hold a collapse mechanism
// (options.mechanism, or an unstable result's) plays it too, unless
// options.animate_mechanism is false: the scene is drawn with the blocks
// where they stand (options.mechanism_scale does not move them), and the
// "animation" (as a simulation's, below) moves every free block, its
// outline and the limit markers it carries rigidly through three key
// frames at times 0, 1, 2: rest, the mechanism's extreme (turned about the
// centroid by s |rotation|, shifted by s velocity, s = mechanism_scale or
// kAutomaticMechanismOfSize of the structure's size), rest. Its "start"
// (1: the page opens at the extreme) and "mechanism" (s, m) tell the player
// so; the summary states s.
#pragma once

#include <string>

#include "dynamics/simulation.hpp"
#include "io/mesh_io.hpp"

namespace ashlar {

// A mechanism's page moves the fastest centroid this fraction of the
// structure's size (bounding-box diagonal) unless options say how far:
// plainly visible, yet small enough that the blocks still read as the
// structure.
inline constexpr double kAutomaticMechanismOfSize = 0.05;

// Writes the page to `path` atomically, whatever its extension. Checks the
// options as export_structure does (InvalidArgument); IoError on failure.
void write_viewer_page(const Structure& structure, const std::string& path, const ExportOptions& options);

// The page of `result`, a simulation of `structure`: the blocks (drawn as
// `options` says) and their outlines move through the key frames of
// animation_frames(result, fps) (simulation_export.hpp), which the scene's
// "animation" holds: "times" (s) and per free block a track, "objects" (the
// indices in "objects" of what moves with it: the block's own, then the
// limit markers it carries), "centroid" (m, where the block was
// built), "outline" (its vertices [first, last) in "outline"), and per key
// frame its pose, "positions" (centroid, m: x y z) and "rotations" (unit
// quaternion from the built block: x y z w), single precision. The player
// interpolates between key frames (linear; slerp) as glTF viewers do.
// Throws InvalidArgument as check_animation does, and when options ask for
// interfaces, forces, the thrust line, load traces or a mechanism (they
// belong to one frame's structure); IoError on failure.
void write_viewer_page(const Structure& structure, const SimulationResult& result, double fps,
                       const std::string& path, const ExportOptions& options);

}  // namespace ashlar
