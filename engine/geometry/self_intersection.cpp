// The CGAL half of block validation: do two faces of a closed surface cross?
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include "geometry/block_validation.hpp"

namespace ashlar {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

}  // namespace

bool surface_self_intersects(const std::vector<Vec3>& vertices,
                             const std::vector<FaceLoop>& faces) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  Mesh mesh;
  std::vector<Mesh::Vertex_index> handles;
  handles.reserve(vertices.size());
  for (const Vec3& p : vertices) handles.push_back(mesh.add_vertex({p.x(), p.y(), p.z()}));
  std::vector<Mesh::Vertex_index> loop;
  for (const FaceLoop& face : faces) {
    loop.clear();
    for (int index : face) loop.push_back(handles[index]);
    // Surface_mesh refuses a face that would make a vertex non-manifold: two
    // sheets of the surface meet at that vertex, so the surface touches itself.
    if (mesh.add_face(loop) == Mesh::null_face()) return true;
  }
  // A face that cannot be triangulated folds over itself in its own plane.
  if (!PMP::triangulate_faces(mesh)) return true;
  return PMP::does_self_intersect(mesh);
}

}  // namespace ashlar
