// Exact constructions: blocks that touch share whole faces, and rounded
// intersection points on those faces would make slivers of zero thickness
// look like overlaps.
#include "geometry/solid_intersection.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

namespace ashlar {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

// A valid block is a closed, oriented manifold, so every face is accepted.
Mesh triangulated_surface(const Block& block) {
  Mesh mesh;
  std::vector<Mesh::Vertex_index> handles;
  handles.reserve(block.vertices().size());
  for (const Vec3& p : block.vertices()) handles.push_back(mesh.add_vertex({p.x(), p.y(), p.z()}));
  std::vector<Mesh::Vertex_index> loop;
  for (const FaceLoop& face : block.faces()) {
    loop.clear();
    for (int index : face) loop.push_back(handles[index]);
    mesh.add_face(loop);
  }
  PMP::triangulate_faces(mesh);
  return mesh;
}

}  // namespace

std::optional<std::vector<Vec3>> shared_solid_vertices(const Block& a, const Block& b) {
  Mesh mesh_a = triangulated_surface(a), mesh_b = triangulated_surface(b), shared;
  if (!PMP::corefine_and_compute_intersection(mesh_a, mesh_b, shared)) return std::nullopt;
  std::vector<Vec3> points;
  points.reserve(shared.number_of_vertices());
  for (const Mesh::Vertex_index v : shared.vertices()) {
    const Kernel::Point_3& p = shared.point(v);
    points.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  }
  return points;
}

}  // namespace ashlar
