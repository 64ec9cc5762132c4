// Flat-shaded triangle meshes of planar polygons: what every export that
// draws geometry (assimp's files, the HTML viewer) turns blocks, contact
// polygons and glyphs into.
#pragma once

#include <array>
#include <vector>

#include "core/types.hpp"
#include "geometry/block.hpp"
#include "io/color.hpp"

namespace ashlar {

// A flat-shaded triangle mesh: each polygon has its own copies of its
// vertices, carrying its normal, so that edges stay sharp in any viewer.
struct FlatMesh {
  std::vector<Vec3> positions;                     // m
  std::vector<Vec3> normals;                       // unit, one per position
  std::vector<std::array<unsigned, 3>> triangles;  // counter-clockwise seen from outside
  // Vertex colours: one per position, or empty for the material's colour
  // alone. glTF multiplies them by the material's colour; give white then.
  std::vector<Rgb> colors;

  // Adds one planar polygon (convex or not, collinear runs allowed),
  // ear-clipped in its plane, with its own vertices; `flip` shows its back.
  // Adds no colours.
  void add_polygon(const std::vector<Vec3>& loop, const Vec3& normal, bool flip);
};

// The faces of a block, flat-shaded.
FlatMesh block_mesh(const Block& block);

}  // namespace ashlar
