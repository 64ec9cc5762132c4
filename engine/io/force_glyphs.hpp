// Solid glyphs that draw forces and lines of thrust in exported meshes.
//
// Glyphs are closed polyhedra given as planar polygons facing outwards, so
// that every viewer shades them like the blocks and none needs lines (which
// most mesh formats and renderers draw one pixel wide, if at all).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"
#include "io/mesh_io.hpp"
#include "io/structure_scene.hpp"

namespace ashlar {

struct InterfaceForces;

// Planar faces of one or more closed solids, each counter-clockwise seen
// from outside.
using GlyphFaces = std::vector<std::vector<Vec3>>;

// One closed solid from tail to tip: a prism shaft, then a pyramid head
// whose base is joined to the shaft by a flat ring. The tip is the apex.
GlyphFaces arrow_faces(const Vec3& tail, const Vec3& tip, const ArrowShape& shape);

// A tube of `sides`-gonal prisms, one closed prism per segment of the
// polyline; consecutive prisms keep their orientation about the line so
// that their edges meet at gentle bends. A point within a thousandth of
// the radius of the previous one is skipped.
GlyphFaces tube_faces(const std::vector<Vec3>& points, double radius, int sides);

// The mean bounding-box diagonal of the free blocks (m), or of the whole
// structure when none is free: the size glyphs are drawn in proportion to.
double mean_free_block_size(const Structure& structure);

// Every edge of a block once, as its two end points.
std::vector<std::array<Vec3, 2>> block_edges(const Block& block);

// What a force arrow draws for an interface: the force exerted on block
// `on` by block `by` (N). `on` is the free block when the other is a
// support (the support's reaction on it); between two free blocks (or two
// supports) it is the block above the joint: the one the interface's
// normal points into once turned upward (z > 0; for a vertical joint
// +x, then +y). The same whatever the blocks' indices: in compression the
// arrow, drawn from the centre of pressure, points into block `on`.
struct ArrowForce {
  int on = -1;
  int by = -1;
  Vec3 force = Vec3::Zero();
};
ArrowForce arrow_force(const Structure& structure, const Interface& contact, const InterfaceForces& forces);

// Arrow length per newton (m/N) of the force arrows options ask for:
// options.force_scale when given, else the round scale (1, 2 or 5 x 10^k N
// per metre of arrow) nearest (on a log scale) the one that draws the
// largest arrow (resultant, or with ForceMode::vertices the normal or
// friction part at a vertex) a quarter of the mean free-block size long: it
// is then 0.16 to 0.35 of that size. 0 when options.result holds no finite
// non-zero force to draw. Needs options.result.
double force_arrow_scale(const Structure& structure, const ExportOptions& options);

// Whether the thrust is drawn as a line (thrust_polylines) rather than a
// network: the structure is planar (Structure::planar), or the normal of
// every joint in compression lies in one vertical plane (an arch, an
// arcade, a wall one block thick, a column), so that the line through the
// centres of pressure is the picture of its thrust. Otherwise (a vault, a
// dome) the thrust network. `result` is an analysis of the structure whose
// interfaces are `contacts`.
bool thrust_in_one_plane(const Structure& structure, const std::vector<Interface>& contacts,
                         const EquilibriumResult& result);

// The thrust network of a vault or a dome: per free block, a tube from its
// centroid to the centre of pressure of each joint of it in compression
// (normal force over 1e-3 of the largest), so that tubes meet at the
// joints and run along the load paths from block to block down to the
// supports. A tube's cross-section is in proportion to its joint's
// resultant: the largest has radius `largest_radius` (m), radius
// largest_radius * sqrt(|R| / |R|max).
std::vector<TubeSegment> thrust_network(const Structure& structure, const EquilibriumResult& result,
                                        double largest_radius);

struct NamedGlyph {
  std::string name;
  GlyphFaces faces;
  Rgb color;
  SceneLayer layer;
  int interface = -1;  // forces: the arrow's interface (index into result.interfaces)
  std::optional<ArrowGlyph> arrow = std::nullopt;  // forces: what `faces` draws
  int block = -1;                                  // limit: the block the marker moves with
  std::vector<TubeSegment> tubes = {};             // thrust network: what `faces` draws
};

// Every cable as a tube, node "cable c" (1-based), the load traces as one
// node "load traces", then the force arrows and the thrust line or network
// that `options` asks for (see ExportOptions). Expects options already checked against
// the structure: options.result set when forces or thrust are.
std::vector<NamedGlyph> equilibrium_glyphs(const Structure& structure,
                                           const ExportOptions& options);

}  // namespace ashlar
