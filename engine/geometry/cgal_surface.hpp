// A block's surface as a triangulated CGAL Surface_mesh, for the .cpp files
// that already include CGAL (split, solid intersection): CGAL's headers stay
// out of every other file.
#pragma once

#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include <vector>

#include "geometry/block.hpp"

namespace ashlar {

enum class SurfaceProblem { none, not_manifold, not_triangulable };

// Fills `mesh` (empty) with the block's faces, triangulated. A valid block
// never has a problem; the caller words the message for the ones it meets.
template <class Mesh>
SurfaceProblem triangulate_surface(const Block& block, Mesh& mesh) {
  using Vertex = typename Mesh::Vertex_index;
  std::vector<Vertex> handles;
  handles.reserve(block.vertices().size());
  for (const Vec3& p : block.vertices()) handles.push_back(mesh.add_vertex({p.x(), p.y(), p.z()}));
  std::vector<Vertex> loop;
  for (const FaceLoop& face : block.faces()) {
    loop.clear();
    for (int index : face) loop.push_back(handles[index]);
    if (mesh.add_face(loop) == Mesh::null_face()) return SurfaceProblem::not_manifold;
  }
  return CGAL::Polygon_mesh_processing::triangulate_faces(mesh) ? SurfaceProblem::none
                                                                 : SurfaceProblem::not_triangulable;
}

}  // namespace ashlar
