// Constructors of common block shapes. Each returns a validated Block and
// throws InvalidArgument / GeometryError with a message naming the defect.
#pragma once

#include <string>
#include <optional>
#include <vector>

#include "geometry/block.hpp"

namespace ashlar {

struct BlockStyle {
  double density = kDefaultDensity;  // kg/m^3
  std::string name;                  // empty: unnamed
  double planarity = 0.0;            // accepted warp of faces, a fraction of each face's size (see Block)
};

// Axis-aligned box; size components > 0 (m).
Block make_box(const Vec3& size, const Vec3& center, const BlockStyle& style = {});

// Convex hull of at least 4 non-coplanar points. Coplanar hull facets are
// merged into one polygon face.
Block make_hull(const std::vector<Vec3>& points, const BlockStyle& style = {});

// Extrusion of a simple planar polygon (convex or not, either orientation)
// along `direction`, which must not lie in the polygon's plane.
Block make_prism(const std::vector<Vec3>& polygon, const Vec3& direction,
                 const BlockStyle& style = {});

// Solid between two simple planar polygons with equal vertex counts, vertex i
// of one joined to vertex i of the other. Side quads that are not planar are
// split into two triangles.
Block make_loft(const std::vector<Vec3>& polygon_a, const std::vector<Vec3>& polygon_b,
                const BlockStyle& style = {});

// Cuts a block by the plane through `point` with normal `normal`.
// `below` is the part on the side opposite the normal; either part is empty
// (std::nullopt) when the plane does not cut the block.
struct SplitResult {
  std::optional<Block> below, above;
};
SplitResult split_block(const Block& block, const Vec3& point, const Vec3& normal);

// Builds a Block from a polygon soup that describes a closed surface
// (e.g. triangles from a mesh file): welds vertices closer than
// `weld_tolerance`, drops degenerate faces and merges adjacent coplanar faces
// into polygons, then validates. `what` names the source in messages, and
// `numbering` how the source numbers `vertices` and `faces`: a defect is
// named by the input vertices and faces it is made of (a merged face by all
// of them), not by the repaired mesh's.
Block block_from_mesh(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                      double weld_tolerance, const BlockStyle& style, const std::string& what,
                      const MeshNumbering& numbering = {});

// The outline (m) of a polygon soup that is an open planar surface (a
// ground plane or a bearing surface given as one polygon, or as facets on
// one plane): after block_from_mesh's welding and merging it is one simple
// polygon face, planar within `planarity` of its size (or 1e-6 of it).
// Projected onto its best-fit plane, counter-clockwise about the normal of
// the given winding. Nothing for anything else (a closed or a bent surface,
// or input block_from_mesh refuses).
std::optional<std::vector<Vec3>> open_planar_outline(const std::vector<Vec3>& vertices,
                                                     const std::vector<FaceLoop>& faces,
                                                     double weld_tolerance, double planarity);

// A plate's thickness as a fraction of its outline's size (bounding-box
// diagonal): a support has no equations, so only its face on the outline
// matters.
constexpr double kSupportPlateThickness = 0.05;

// The support block of an open planar surface: the prism of `outline`
// (open_planar_outline's) extruded away from `toward` (m) by
// kSupportPlateThickness of its size, so that its face on the outline's
// plane faces `toward`, where the blocks it bears are.
Block support_plate(const std::vector<Vec3>& outline, const Vec3& toward, const BlockStyle& style);

}  // namespace ashlar
