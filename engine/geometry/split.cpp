// Cutting a block in two by a plane (CGAL clip of the triangulated surface,
// closed again with the cut face; block_from_mesh restores polygon faces).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/clip.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "geometry/cgal_surface.hpp"
#include "geometry/block_builders.hpp"

namespace ashlar {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;

// Fractions of the block's bounding-box diagonal.
//
// A vertex this close to the plane counts as on it: the cut points on its
// edges move onto it, and a side with nothing deeper is empty (the plane
// misses the block). A plane "through a vertex" computed in floating point
// misses it by rounding, and would leave faces too small to be valid. The
// moved points stay on their edges, so the block is still tiled exactly,
// but the two parts may triangulate the bent cut face differently: keeping
// this tiny keeps that volume mismatch below 1e-10.
constexpr double kOnPlane = 1e-10;
// Farther than kOnPlane but closer than this, a vertex leaves slivers that
// validation may reject; the error message then says so.
constexpr double kNearVertex = 1e-5;
// Points closer than this would fail validation as coincident: weld them.
constexpr double kWeld = 1e-9;

Vec3 to_vec(const Kernel::Point_3& p) { return {p.x(), p.y(), p.z()}; }

Mesh triangulated_surface(const Block& block, const std::string& what) {
  Mesh mesh;
  switch (triangulate_surface(block, mesh)) {
    case SurfaceProblem::not_manifold:
      throw GeometryError(what + ": its surface is not a manifold CGAL can cut");
    case SurfaceProblem::not_triangulable:
      throw GeometryError(what + ": a face could not be triangulated for cutting");
    case SurfaceProblem::none:
      break;
  }
  return mesh;
}

// Moves cut points onto the near-plane vertex of the edge they lie on.
class CutSnapper {
public:
  CutSnapper(const Mesh& surface, const Vec3& point, const Vec3& unit_normal, double size)
      : on_line_(kWeld * size) {
    const double near = kOnPlane * size;
    for (Mesh::Edge_index e : surface.edges()) {
      const Mesh::Halfedge_index h = surface.halfedge(e);
      const Vec3 a = to_vec(surface.point(surface.source(h)));
      const Vec3 b = to_vec(surface.point(surface.target(h)));
      if (std::abs(unit_normal.dot(a - point)) <= near) {
        edges_.emplace_back(a, b);
      } else if (std::abs(unit_normal.dot(b - point)) <= near) {
        edges_.emplace_back(b, a);
      }
    }
  }

  Vec3 operator()(const Vec3& p) const {
    for (const auto& [vertex, other] : edges_) {
      const Vec3 along = other - vertex;
      const double t = along.dot(p - vertex) / along.squaredNorm();
      if (t > 0.0 && t < 1.0 && (vertex + t * along - p).norm() <= on_line_) return vertex;
    }
    return p;
  }

private:
  double on_line_;
  std::vector<std::pair<Vec3, Vec3>> edges_;  // (near-plane vertex, other end)
};

// The part of `surface` on the negative side of `plane`, as a block. Both
// parts snap and weld their cut points identically (block vertices first,
// then cut points in coordinate order), so their cut faces have the same
// outline and their volumes add up to the block's.
Block clipped_part(const Mesh& surface, const Kernel::Plane_3& plane, const CutSnapper& snap,
                   const Block& block, const std::string& part_name, const std::string& what) {
  Mesh part = surface;
  if (!PMP::clip(part, plane, CGAL::parameters::clip_volume(true)) || part.is_empty() ||
      !CGAL::is_closed(part)) {
    throw GeometryError(what + ": CGAL could not clip the surface into a closed part");
  }
  part.collect_garbage();  // numbers the remaining vertices 0..n-1
  std::vector<Mesh::Vertex_index> order(part.vertices().begin(), part.vertices().end());
  std::sort(order.begin(), order.end(), [&part](Mesh::Vertex_index a, Mesh::Vertex_index b) {
    return part.point(a) < part.point(b);
  });
  std::vector<Vec3> soup = block.vertices();
  std::vector<int> soup_index(order.size());
  for (Mesh::Vertex_index v : order) {
    soup_index[v.idx()] = static_cast<int>(soup.size());
    soup.push_back(snap(to_vec(part.point(v))));
  }
  std::vector<FaceLoop> triangles;
  triangles.reserve(part.number_of_faces());
  for (Mesh::Face_index f : part.faces()) {
    FaceLoop triangle;
    for (Mesh::Vertex_index v : part.vertices_around_face(part.halfedge(f))) {
      triangle.push_back(soup_index[v.idx()]);
    }
    triangles.push_back(std::move(triangle));
  }
  BlockStyle style;
  style.density = block.density();
  style.planarity = block.planarity();
  style.name = block.name().empty() ? std::string() : block.name() + " " + part_name;
  return block_from_mesh(soup, triangles, kWeld * block.bounds().diagonal(), style,
                         what + " (" + part_name + " part)");
}

// Names the vertex a failed cut went through or grazed, if any: the likely
// cause (a part pinched at that vertex, or slivers beside it).
std::string near_vertex_hint(const Block& block, const Vec3& point, const Vec3& unit_normal) {
  const double size = block.bounds().diagonal();
  double closest = std::numeric_limits<double>::infinity();
  size_t closest_index = 0;
  for (size_t i = 0; i < block.vertices().size(); ++i) {
    const double distance = std::abs(unit_normal.dot(block.vertices()[i] - point));
    if (distance < closest) {
      closest = distance;
      closest_index = i;
    }
  }
  std::ostringstream hint;
  if (closest <= kOnPlane * size) {
    hint << " (the cut plane passes through vertex " << closest_index + 1
         << " of the block; a part that would touch itself there cannot be one block)";
  } else if (closest < kNearVertex * size) {
    hint << " (the cut plane passes " << closest << " m from vertex " << closest_index + 1
         << " of the block; put the plane through that vertex or farther from it)";
  }
  return hint.str();
}

}  // namespace

SplitResult split_block(const Block& block, const Vec3& point, const Vec3& normal) {
  const std::string what = "split of " + block_label(block.name());
  if (!point.allFinite()) throw InvalidArgument(what + ": the plane's point must be finite");
  if (!normal.allFinite() || normal.norm() == 0.0) {
    throw InvalidArgument(what + ": the plane's normal must be a finite, non-zero vector");
  }
  const Vec3 unit = normal.normalized();
  const double size = block.bounds().diagonal();
  double depth_below = -std::numeric_limits<double>::infinity();
  double depth_above = -std::numeric_limits<double>::infinity();
  for (const Vec3& p : block.vertices()) {
    const double distance = unit.dot(p - point);
    depth_below = std::max(depth_below, -distance);
    depth_above = std::max(depth_above, distance);
  }
  if (depth_below <= kOnPlane * size) return {std::nullopt, block};
  if (depth_above <= kOnPlane * size) return {block, std::nullopt};

  const Mesh surface = triangulated_surface(block, what);
  const CutSnapper snap(surface, point, unit, size);
  const Kernel::Point_3 origin(point.x(), point.y(), point.z());
  const Kernel::Vector_3 direction(normal.x(), normal.y(), normal.z());
  try {
    // clip keeps the negative side of the plane, the side opposite its normal.
    return {clipped_part(surface, Kernel::Plane_3(origin, direction), snap, block, "below", what),
            clipped_part(surface, Kernel::Plane_3(origin, -direction), snap, block, "above", what)};
  } catch (const GeometryError& error) {
    throw GeometryError(error.what() + near_vertex_hint(block, point, unit));
  }
}

}  // namespace ashlar
