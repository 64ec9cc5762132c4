// Convex hull blocks (CGAL quickhull). CGAL returns triangles; block_from_mesh
// merges the coplanar ones, so the hull of a box's corners has 6 quads.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <string>

#include "core/error.hpp"
#include "geometry/block_builders.hpp"

namespace ashlar {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

// Hull vertices closer than this (of the hull's size) would fail the block's
// coincident-vertex check, so they are welded instead.
constexpr double kWeld = 1e-9;
// A hull thinner than this (volume over size^3) is flat: the same threshold
// as a block's zero-volume check.
constexpr double kFlatVolume = 1e-12;

// True unless all points lie in one plane (exact predicates).
bool spans_volume(const std::vector<Point>& points) {
  const Point& a = points[0];
  size_t i = 1;
  while (i < points.size() && points[i] == a) ++i;
  if (i == points.size()) return false;
  const Point& b = points[i];
  while (i < points.size() && CGAL::collinear(a, b, points[i])) ++i;
  if (i == points.size()) return false;
  const Point& c = points[i];
  while (i < points.size() && CGAL::coplanar(a, b, c, points[i])) ++i;
  return i < points.size();
}

}  // namespace

Block make_hull(const std::vector<Vec3>& points, const BlockStyle& style) {
  const std::string what = style.name.empty() ? "hull" : "hull '" + style.name + "'";
  const std::string flat = what + ": points are coplanar: a hull needs volume";
  if (points.size() < 4) {
    throw InvalidArgument(what + ": needs at least 4 points (not all in one plane), got " +
                          std::to_string(points.size()));
  }
  std::vector<Point> input;
  input.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw InvalidArgument(what + ": point " + std::to_string(i + 1) +
                            " has a NaN or infinite coordinate");
    }
    input.emplace_back(points[i].x(), points[i].y(), points[i].z());
  }
  if (!spans_volume(input)) throw InvalidArgument(flat);

  Mesh hull;
  CGAL::convex_hull_3(input.begin(), input.end(), hull);
  std::vector<Vec3> vertices;
  vertices.reserve(hull.number_of_vertices());
  for (Mesh::Vertex_index v : hull.vertices()) {
    const Point& p = hull.point(v);
    vertices.emplace_back(p.x(), p.y(), p.z());
  }
  std::vector<FaceLoop> triangles;
  triangles.reserve(hull.number_of_faces());
  for (Mesh::Face_index f : hull.faces()) {
    FaceLoop triangle;
    for (Mesh::Vertex_index v : hull.vertices_around_face(hull.halfedge(f))) {
      triangle.push_back(static_cast<int>(v.idx()));  // a fresh mesh numbers vertices 0..n-1
    }
    triangles.push_back(std::move(triangle));
  }

  Box3 box;
  for (const Vec3& p : vertices) box.add(p);
  const double size = box.diagonal();
  if (mass_properties(vertices, triangles).volume <= kFlatVolume * size * size * size) {
    throw InvalidArgument(flat);
  }
  return block_from_mesh(vertices, triangles, kWeld * size, style, what);
}

}  // namespace ashlar
