// Exact constructions: blocks that touch share whole faces, and rounded
// intersection points on those faces would make slivers of zero thickness
// look like overlaps.
#include "geometry/solid_intersection.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Surface_mesh.h>

#include "geometry/cgal_surface.hpp"

namespace ashlar {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

}  // namespace

std::optional<std::vector<std::vector<Vec3>>> shared_solid_pieces(const Block& a, const Block& b) {
  Mesh mesh_a, mesh_b, shared;
  if (triangulate_surface(a, mesh_a) != SurfaceProblem::none || triangulate_surface(b, mesh_b) != SurfaceProblem::none ||
      !PMP::corefine_and_compute_intersection(mesh_a, mesh_b, shared))
    return std::nullopt;
  auto piece_of = shared.add_property_map<Mesh::Face_index, std::size_t>("f:piece").first;
  std::vector<std::vector<Vec3>> pieces(PMP::connected_components(shared, piece_of));
  for (const Mesh::Face_index f : shared.faces()) {
    for (const Mesh::Vertex_index v : CGAL::vertices_around_face(shared.halfedge(f), shared)) {
      const Kernel::Point_3& p = shared.point(v);
      pieces[piece_of[f]].emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
    }
  }
  return pieces;
}

}  // namespace ashlar
