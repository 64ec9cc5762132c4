// Checks that a vertex/face description is a valid block. Used by the Block
// constructor; exposed so importers can report defects before building.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/types.hpp"

namespace ashlar {

// How messages name a block's vertices and faces, given their 0-based
// indices in the lists the block is built from. Without names they are
// numbered from 1 in those lists ("vertex 3", "face 2"); an importer whose
// repair renumbered a file's mesh names them as the file does.
struct MeshNumbering {
  std::function<std::string(int)> vertex_name;
  std::function<std::string(int)> face_name;

  std::string vertex(int index) const;
  std::string face(int index) const;
  // Two of them: "vertices 4 and 8" unnamed, else "<name> and <name>".
  std::string vertices(int a, int b) const;
  std::string faces(int a, int b) const;
};

// Throws GeometryError naming the first defect found, in this order:
//  - fewer than 4 vertices or 4 faces, non-finite coordinates;
//  - a size (bounding-box diagonal) of zero or outside 1e-30 to 1e30 m;
//  - a face with fewer than 3 vertices, an index out of range, or a repeated
//    vertex;
//  - coincident vertices (closer than 1e-9 of the block's size);
//  - open surface (an edge used by one face only) or inconsistent
//    orientation (an edge used twice in the same direction) or an edge
//    shared by more than two faces (non-manifold), or a surface in
//    separate pieces;
//  - degenerate (zero-area) face; a face with a vertex off its best-fit
//    plane by more than `planarity` times the face's size (bounding-box
//    diagonal), or 1e-6 of the block's size if that is more; a face whose
//    outline, projected on that plane, crosses itself;
//  - zero volume, or negative volume (inverted: faces point inward);
//  - faces that intersect each other (non-convex blocks only: a closed,
//    outward-oriented convex polyhedron cannot self-intersect).
// `what` names the block in messages, e.g. "block 'pier 2'"; `numbering`
// its vertices and faces.
void validate_block(const std::vector<Vec3>& vertices,
                    const std::vector<FaceLoop>& faces, const std::string& what,
                    double planarity = 0.0, const MeshNumbering& numbering = {});

// The CGAL part of validation: where the (triangulated) surface crosses or
// touches itself, e.g. "face 2 and face 7 cross each other" (faces named by
// `numbering`), or nothing when it does not. Only called for non-convex
// blocks.
std::optional<std::string> surface_self_intersection(const std::vector<Vec3>& vertices,
                                                     const std::vector<FaceLoop>& faces,
                                                     const MeshNumbering& numbering = {});

}  // namespace ashlar
