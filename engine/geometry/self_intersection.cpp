// The CGAL half of block validation: do two faces of a closed surface cross?
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <iterator>
#include <utility>

#include "geometry/block_validation.hpp"

namespace ashlar {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using FaceSource = Mesh::Property_map<Mesh::Face_index, int>;

// Gives the triangles a face is cut into the face's index, so that a
// crossing of triangles can be reported as a crossing of the user's faces.
class KeepFaceSource : public PMP::Triangulate_faces::Default_visitor<Mesh> {
public:
  explicit KeepFaceSource(FaceSource source) : source_(source) {}
  void before_subface_creations(Mesh::Face_index split) { current_ = source_[split]; }
  void after_subface_created(Mesh::Face_index created) { source_[created] = current_; }

private:
  FaceSource source_;
  int current_ = -1;
};

std::string face_pair(int a, int b, const MeshNumbering& numbering) {
  return numbering.faces(std::min(a, b), std::max(a, b));
}

}  // namespace

std::optional<std::string> surface_self_intersection(const std::vector<Vec3>& vertices,
                                                     const std::vector<FaceLoop>& faces,
                                                     const MeshNumbering& numbering) {
  Mesh mesh;
  FaceSource source = mesh.add_property_map<Mesh::Face_index, int>("f:source", -1).first;
  std::vector<Mesh::Vertex_index> handles;
  handles.reserve(vertices.size());
  for (const Vec3& p : vertices) handles.push_back(mesh.add_vertex({p.x(), p.y(), p.z()}));
  std::vector<Mesh::Vertex_index> loop;
  for (size_t f = 0; f < faces.size(); ++f) {
    loop.clear();
    for (int index : faces[f]) loop.push_back(handles[index]);
    // Surface_mesh refuses a face that would make a vertex non-manifold: two
    // sheets of the surface meet at that vertex, so the surface touches itself.
    const Mesh::Face_index added = mesh.add_face(loop);
    if (added == Mesh::null_face()) {
      return numbering.face(static_cast<int>(f)) +
             " meets the rest of the surface at a vertex where two sheets of it touch";
    }
    source[added] = static_cast<int>(f);
  }
  // A face that cannot be triangulated folds over itself in its own plane.
  const std::vector<Mesh::Face_index> polygons(mesh.faces().begin(), mesh.faces().end());
  for (const Mesh::Face_index face : polygons) {
    if (!PMP::triangulate_face(face, mesh, CGAL::parameters::visitor(KeepFaceSource(source)))) {
      return numbering.face(source[face]) + " folds over itself";
    }
  }
  if (!PMP::does_self_intersect(mesh)) return std::nullopt;
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> crossings;
  PMP::self_intersections(mesh, std::back_inserter(crossings));
  for (const auto& [x, y] : crossings) {
    if (source[x] != source[y]) return face_pair(source[x], source[y], numbering) + " cross each other";
  }
  return numbering.face(source[crossings.front().first]) + " crosses itself";
}

}  // namespace ashlar
