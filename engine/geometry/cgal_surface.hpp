// A block's surface as a triangulated CGAL Surface_mesh, for the .cpp files
// that already include CGAL (split, solid intersection): CGAL's headers stay
// out of every other file.
#pragma once

#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/block.hpp"

namespace ashlar {

enum class SurfaceProblem { none, not_manifold, not_triangulable };

// Fills `mesh` (empty) with the block's faces, triangulated: planar faces
// as CGAL triangulates them, warped ones as the fan of Block's surface. A
// valid block never has a problem; the caller words the message for the
// ones it meets.
template <class Mesh>
SurfaceProblem triangulate_surface(const Block& block, Mesh& mesh) {
  using Vertex = typename Mesh::Vertex_index;
  std::vector<Vertex> handles;
  handles.reserve(block.vertices().size());
  for (const Vec3& p : block.vertices()) handles.push_back(mesh.add_vertex({p.x(), p.y(), p.z()}));
  const double flat = kWarpedFace * block.bounds().diagonal();
  std::vector<Vertex> loop;
  for (size_t f = 0; f < block.faces().size(); ++f) {
    const FaceLoop& face = block.faces()[f];
    const FacePlane& plane = block.face_planes()[f];
    const bool warped = face.size() > 3 && std::any_of(face.begin(), face.end(), [&](int index) {
      return std::abs(plane.normal.dot(block.vertices()[index]) - plane.offset) > flat;
    });
    if (!warped) {
      loop.clear();
      for (int index : face) loop.push_back(handles[index]);
      if (mesh.add_face(loop) == Mesh::null_face()) return SurfaceProblem::not_manifold;
      continue;
    }
    const Vec3 c = face_centre(block.vertices(), face);
    const Vertex centre = mesh.add_vertex({c.x(), c.y(), c.z()});
    for (size_t i = 0; i < face.size(); ++i) {
      if (mesh.add_face(centre, handles[face[i]], handles[face[(i + 1) % face.size()]]) == Mesh::null_face()) {
        return SurfaceProblem::not_manifold;
      }
    }
  }
  return CGAL::Polygon_mesh_processing::triangulate_faces(mesh) ? SurfaceProblem::none
                                                                 : SurfaceProblem::not_triangulable;
}

}  // namespace ashlar
