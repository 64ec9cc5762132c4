// Constructors of common block shapes. Each returns a validated Block and
// throws InvalidArgument / GeometryError with a message naming the defect.
#pragma once

#include <string>
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
// into polygons, then validates. `what` names the source in messages.
Block block_from_mesh(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                      double weld_tolerance, const BlockStyle& style, const std::string& what);

}  // namespace ashlar
