// Mesh files through assimp: import objects as blocks, export structures.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.hpp"
#include "geometry/block.hpp"
#include "geometry/block_builders.hpp"
#include "io/color.hpp"
#include "structure/structure.hpp"

namespace ashlar {

struct EquilibriumResult;
struct BlockMotion;
struct LimitInterface;

struct ImportOptions {
  double density = kDefaultDensity;  // kg/m^3 for every imported block
  // Vertices closer than this fraction of the scene's bounding-box diagonal
  // are welded (files such as STL repeat each vertex per triangle).
  double relative_weld_tolerance = 1e-9;
  // Accepted warp of each polygon face (quads of CAD and remeshed models),
  // a fraction of the face's size; see Block.
  double planarity = 0.0;
  // Whether the importer may open a file: the mesh itself and the files it
  // names (OBJ materials, glTF buffers, ...). Empty: any file. A refused
  // file is as if it did not exist.
  std::function<bool(const std::string& path)> may_open;
};

struct ImportedBlock {
  std::string name;  // node name, made unique ("name#2") when repeated
  Block block;
  // An open planar surface's outline (open_planar_outline): the object is
  // a support, and block its support_plate, facing the other blocks.
  std::vector<Vec3> surface;
};

// The object's block (block_from_mesh), or, for an open planar surface, a
// support plate facing the outline's own normal until
// face_plates_to_blocks turns it. Throws block_from_mesh's GeometryError
// for anything else, naming vertices and faces as `numbering` does (the
// file's own numbering).
ImportedBlock import_object(const std::string& name, const std::vector<Vec3>& vertices,
                            const std::vector<FaceLoop>& faces, double weld_tolerance,
                            const BlockStyle& style, const std::string& what,
                            const MeshNumbering& numbering);

// Turns every support plate of `blocks` to face the centroid of the blocks
// that are not plates (by volume), where the blocks it bears are.
void face_plates_to_blocks(std::vector<ImportedBlock>& blocks);

// Every node that carries meshes becomes one block (its meshes joined, in
// world coordinates). Throws IoError for unreadable files and GeometryError
// naming the object when a mesh is not a closed solid.
std::vector<ImportedBlock> import_blocks(const std::string& path, const ImportOptions& options);

// The values that block colours were mapped from (map_colors), kept for
// the HTML viewer: its legend and each block's read-out.
struct ColorScale {
  std::vector<double> values;  // one per block
  double lo = 0.0, hi = 1.0;   // the values mapped onto the map's ends (hi < lo reverses it)
  std::string map = "viridis";
  std::string label;  // what the values mean, with units; may be empty
};

// What the force arrows of an export draw: one arrow per interface, its
// resultant at its centre of pressure ("resultants", the engineer's usual
// picture), or the forces at each contact vertex, split into a normal arrow
// (compression or tension) and a friction arrow ("vertices": how the
// solver spread the force over the joint).
enum class ForceMode { resultants, vertices };
inline constexpr EnumNames<ForceMode, 2> kForceModeNames{
    {{{ForceMode::resultants, "resultants"}, {ForceMode::vertices, "vertices"}}}};

struct ExportOptions {
  // One colour per block (size() == structure.size()), or empty for the
  // default grey.
  std::vector<Rgb> block_colors;
  // HTML viewer only: the values block_colors came from, if any.
  std::optional<ColorScale> color_scale;
  // HTML viewer only, a simulation's or a mechanism's page: it plays as it
  // opens (false: paused at the frame it opens at).
  bool autoplay = true;
  // HTML viewer only: a page with a mechanism (`mechanism`, or an unstable
  // result's) plays it (viewer_page.hpp), the blocks drawn where they stand
  // and moved by the player, the fastest centroid mechanism_scale metres at
  // the extreme (0: kAutomaticMechanismOfSize, viewer_page.hpp, of the
  // structure's size).
  // False: a still, the blocks drawn moved by mechanism_scale as in the mesh
  // files.
  bool animate_mechanism = true;
  // HTML viewer only: the page's title; empty: the file's name.
  std::string title;
  bool interfaces = false;  // also write each contact polygon as a node
  // Colours of the roles, from colour-blind-safe palettes (Paul Tol's
  // "vibrant" for the arrows, saturated enough to read through translucent
  // blocks; Okabe-Ito's orange for the thrust line), none
  // shared: interfaces a light neutral that leaves the arrows the eye.
  Rgb interface_color{0.87, 0.84, 0.74};
  ContactOptions contact;

  // An analysis of this very structure (same blocks, and interfaces found
  // with the same `contact` options), needed by `forces` and `thrust`; not
  // owned, it must outlive the call.
  const EquilibriumResult* result = nullptr;
  // One arrow per interface, node "force a-b" (1-based blocks): from the
  // centre of pressure along the force on one of its blocks (arrow_force
  // in force_glyphs.hpp: on the free block at a support, else on the
  // block above), its length proportional to the resultant's size. Interfaces whose resultant is
  // below `negligible_force` of the largest get none.
  bool forces = false;
  // What the arrows draw when `forces` is set (ForceMode above). With
  // vertices, arrows "force a-b vertex j" (the normal part of the force at
  // the joint's j-th contact vertex, 1-based, on the same block as the
  // resultant's arrow) and "friction a-b vertex j" (its tangential part),
  // from the vertex.
  ForceMode force_mode = ForceMode::resultants;
  // The thrust (thrust_network in force_glyphs.hpp): for a structure in one
  // vertical plane, the thrust line, every branch of it
  // (thrust_polylines(structure, *result)), as thin tubes in one node
  // "thrust line"; for a vault or a dome, the thrust network, one node
  // "thrust network" of tubes from each free block's centroid to the centres
  // of pressure of its compressed joints, each as thick as its joint's
  // force. None when there is nothing to draw.
  bool thrust = false;
  // Arrow length per newton (m/N); 0: a round number of newtons per metre
  // that draws the largest arrow about a quarter of the mean size
  // (bounding-box diagonal) of the free blocks (force_arrow_scale). Give a
  // value to compare arrows across several exports.
  double force_scale = 0.0;
  // Fraction of the largest resultant below which an interface gets no
  // arrow and a tension counts as none (solver round-off).
  double negligible_force = 1e-3;
  Rgb compression_color{0.0, 0.467, 0.733};  // arrows of interfaces in compression only (Tol blue)
  Rgb tension_color{0.8, 0.2, 0.067};        // arrows of interfaces carrying tension (Tol red)
  // Friction arrows (force_mode vertices): Tol vibrant magenta, apart from
  // both arrow colours for every kind of colour vision.
  Rgb friction_color{0.933, 0.2, 0.467};
  Rgb thrust_color{0.902, 0.624, 0.0};         // Okabe-Ito orange
  Rgb cable_color{0.2, 0.2, 0.22};  // cables are always drawn, as thin tubes
  // Load traces (ForceFlow::polylines of trace_loads, m), drawn as thin
  // tubes merged into one node "load traces": hundreds of traces as nodes
  // of their own would bloat files and slow viewers for no use. Like the
  // force glyphs they run inside the blocks; set block_opacity to see them.
  std::vector<std::vector<Vec3>> traces;
  Rgb trace_color{0.1, 0.6, 0.25};
  // Opacity of the blocks in [0, 1] (glTF and OBJ; PLY and STL have no
  // materials). Unset: opaque, except 0.35 when forces, the thrust line or
  // load traces are drawn, since they run inside the blocks.
  std::optional<double> block_opacity;
  // Every block edge as a thin dark tube (radius 0.4 % of the mean free
  // block's size), in one node "edges": blocks read as masonry in viewers
  // that draw no outlines. With a mechanism, the edges stay where the
  // blocks stand. The HTML viewer always holds every block's outline as
  // lines (as drawn, displaced by a mechanism too); this says whether they
  // show when the page opens.
  bool edges = false;
  Rgb edge_color{0.12, 0.12, 0.12};
  // How the result's mechanism moves the blocks: each free block drawn
  // displaced by its virtual motion (a rigid motion: rotation about its
  // centroid, then translation), scaled so that the fastest centroid moves
  // this far (m). 0: blocks where they are. Needs a mechanism: `mechanism`,
  // or an unstable result's.
  double mechanism_scale = 0.0;
  // A collapse mechanism that is not the result's (ashlar.load_factor's,
  // whose `result` is the equilibrium at its factor): one motion per block;
  // not owned. Null: the result's own, if any.
  const std::vector<BlockMotion>* mechanism = nullptr;
  // ashlar.load_factor's factor when `result` is the equilibrium at it: the
  // viewer's summary then says the structure is at that limit, not
  // "stable".
  std::optional<double> load_factor;
  // The interfaces at their limit (indices into
  // structure.interfaces(contact)), marked in a layer "limit": a hinge as a
  // rod along its axis (the blocks' relative rotation) across the joint,
  // node "hinge a-b"; a sliding or separating joint as a flat disc on the
  // joint at its centre, node "sliding a-b" or "separation a-b"
  // (hinge_sliding gets both). Radii 4 % (rod) and 15 % (disc) of the mean
  // free-block size. Not owned; null or empty: none.
  const std::vector<LimitInterface>* limit = nullptr;
  Rgb hinge_color{0.05, 0.05, 0.05};
  Rgb sliding_color{0.1, 0.45, 0.95};
};

// Format from the extension: .glb, .gltf (glTF 2.0), .obj, .ply, .stl, or
// .html (the interactive viewer, viewer_page.hpp). Each block is a node
// named after it, each cable a tube "cable c" (structure_scene.hpp); every
// file is written atomically.
// Throws InvalidArgument for an unknown extension, bad options (forces or
// thrust without a result, a result of another structure), IoError on
// failure.
void export_structure(const Structure& structure, const std::string& path,
                      const ExportOptions& options);

// Names of the supported mesh-file extensions (.glb, .gltf, .obj, .ply,
// .stl; export_structure also writes .html), for error messages.
const std::vector<std::string>& export_extensions();

// The extension of path after its last dot, lower case, without the dot;
// empty when there is none.
std::string file_extension(const std::string& path);

// True for files whose format is +Y up by specification (glTF); ashlar is
// +Z up, so import and export rotate their coordinates.
bool is_y_up_file(const std::string& path);

}  // namespace ashlar
