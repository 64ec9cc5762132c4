// What an export of a structure draws, as named flat-shaded objects: the
// blocks, contact polygons, force arrows, thrust line, cables, load traces
// and edges that ExportOptions asks for. The mesh files (mesh_export.cpp,
// through assimp) and the HTML viewer (viewer_page.hpp) write these same
// objects, so a picture means the same in either.
#pragma once

#include <array>
#include <optional>
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

struct ArrowShape {
  double shaft_radius = 0.0;  // m
  double head_radius = 0.0;   // m, larger than shaft_radius
  double head_length = 0.0;   // m, at most the arrow's length
  int sides = 6;              // of the shaft prism and the head pyramid, >= 3
};

// A force arrow as arrow_faces (force_glyphs.hpp) draws it.
struct ArrowGlyph {
  Vec3 tail = Vec3::Zero(), tip = Vec3::Zero();  // m
  ArrowShape shape;
  Vec3 force = Vec3::Zero();  // N: the force it draws
};

// One straight tube of a thrust network, as tube_faces draws it with
// kGlyphSides sides.
struct TubeSegment {
  Vec3 from = Vec3::Zero(), to = Vec3::Zero();  // m
  double radius = 0.0;                           // m
};

struct SceneObject {
  SceneLayer layer = SceneLayer::blocks;
  std::string name;  // "voussoir 3", "interface 2-3", "force 2-3", "thrust line", ...
  FlatMesh mesh;     // m
  Rgb color;
  double opacity = 1.0;  // in [0, 1], multiplies color.a
  bool two_sided = false;
  int block = -1;      // blocks: the block (0-based); limit: the block it moves with (-1: none)
  int interface = -1;  // interfaces, forces: index into structure.interfaces(options.contact)
  // blocks: every edge of the block as drawn (displaced by a mechanism too).
  std::vector<std::array<Vec3, 2>> outline;
  // forces: the arrow `mesh` holds, for a viewer that builds it itself.
  std::optional<ArrowGlyph> arrow;
  // thrust network: the tubes `mesh` holds, likewise.
  std::vector<TubeSegment> tubes;
};

// Checks `options` against the structure (InvalidArgument, messages
// beginning "export: "), then builds the objects: one per block, then one
// per contact polygon (`interfaces`), then the glyphs of force_glyphs.hpp.
std::vector<SceneObject> structure_scene(const Structure& structure, const ExportOptions& options);

}  // namespace ashlar
