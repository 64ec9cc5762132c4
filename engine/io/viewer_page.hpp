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
#pragma once

#include <string>

#include "dynamics/simulation.hpp"
#include "io/mesh_io.hpp"

namespace ashlar {

// Writes the page to `path` atomically, whatever its extension. Checks the
// options as export_structure does (InvalidArgument); IoError on failure.
void write_viewer_page(const Structure& structure, const std::string& path, const ExportOptions& options);

// The page of `result`, a simulation of `structure`: the blocks (drawn as
// `options` says) and their outlines move through the key frames of
// animation_frames(result, fps) (simulation_export.hpp), which the scene's
// "animation" holds: "times" (s) and per free block a track, "object" (its
// index in "objects", the block's own), "centroid" (m, where the block was
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
