// What an export of a structure draws, as named flat-shaded objects: the
// blocks, contact polygons, force arrows, thrust line, cables, load traces
// and edges that ExportOptions asks for. The mesh files (mesh_export.cpp,
// through assimp) and the HTML viewer (viewer_page.hpp) write these same
// objects, so a picture means the same in either.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "io/flat_mesh.hpp"
#include "io/mesh_io.hpp"

namespace ashlar {

// Which kind of thing an object draws: the HTML viewer switches each on and
// off.
enum class SceneLayer { blocks, interfaces, forces, thrust, edges, cables, traces, limit };

inline constexpr EnumNames<SceneLayer, 8> kSceneLayerNames{{{{SceneLayer::blocks, "blocks"},
                                                             {SceneLayer::interfaces, "interfaces"},
                                                             {SceneLayer::forces, "forces"},
                                                             {SceneLayer::thrust, "thrust"},
                                                             {SceneLayer::edges, "edges"},
                                                             {SceneLayer::cables, "cables"},
                                                             {SceneLayer::traces, "traces"},
                                                             {SceneLayer::limit, "limit"}}}};

struct SceneObject {
  SceneLayer layer = SceneLayer::blocks;
  std::string name;  // "voussoir 3", "interface 2-3", "force 2-3", "thrust line", ...
  FlatMesh mesh;     // m
  Rgb color;
  double opacity = 1.0;  // in [0, 1], multiplies color.a
  bool two_sided = false;
  int block = -1;      // blocks: the block (0-based)
  int interface = -1;  // interfaces, forces: index into structure.interfaces(options.contact)
  // blocks: every edge of the block as drawn (displaced by a mechanism too).
  std::vector<std::array<Vec3, 2>> outline;
};

// Checks `options` against the structure (InvalidArgument, messages
// beginning "export: "), then builds the objects: one per block, then one
// per contact polygon (`interfaces`), then the glyphs of force_glyphs.hpp.
std::vector<SceneObject> structure_scene(const Structure& structure, const ExportOptions& options);

}  // namespace ashlar
