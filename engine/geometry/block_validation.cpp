#include "geometry/block_validation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <tuple>

#include "core/error.hpp"
#include "geometry/block.hpp"
#include "geometry/polygon.hpp"
#include "geometry/polygon_boolean.hpp"

namespace ashlar {

namespace {

// Relative tolerances, as fractions of the block's bounding-box diagonal.
// Planarity is loose enough for float32 mesh files (about 6e-8 relative).
constexpr double kCoincidentVertices = 1e-9;
constexpr double kPlanarity = 1e-6;
constexpr double kDegenerateArea = 1e-12;    // of size^2
constexpr double kDegenerateVolume = 1e-12;  // of size^3

[[noreturn]] void fail(const std::string& what, const std::string& defect) {
  throw GeometryError(what + " is not a valid block: " + defect);
}

std::string edge_name(int i, int j) {
  return "edge between vertices " + std::to_string(i + 1) + " and " + std::to_string(j + 1);
}

void check_counts_and_indices(const std::vector<Vec3>& vertices,
                              const std::vector<FaceLoop>& faces, const std::string& what) {
  if (vertices.size() < 4) {
    fail(what, "needs at least 4 vertices, got " + std::to_string(vertices.size()));
  }
  if (faces.size() < 4) fail(what, "needs at least 4 faces, got " + std::to_string(faces.size()));
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) {
      fail(what, "vertex " + std::to_string(i + 1) + " has a NaN or infinite coordinate");
    }
  }
  const int count = static_cast<int>(vertices.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    const FaceLoop& face = faces[f];
    const std::string face_name = "face " + std::to_string(f + 1);
    if (face.size() < 3) fail(what, face_name + " has fewer than 3 vertices");
    for (int index : face) {
      if (index < 0 || index >= count) {
        fail(what, face_name + " refers to vertex " + std::to_string(index + 1) + " but there are " +
                       std::to_string(count) + " vertices");
      }
    }
    FaceLoop sorted = face;
    std::sort(sorted.begin(), sorted.end());
    const auto repeat = std::adjacent_find(sorted.begin(), sorted.end());
    if (repeat != sorted.end()) {
      fail(what, face_name + " uses vertex " + std::to_string(*repeat + 1) + " twice");
    }
  }
}

void check_coincident_vertices(const std::vector<Vec3>& vertices, double size,
                               const std::string& what) {
  const double eps = kCoincidentVertices * size;
  std::vector<int> order(vertices.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return vertices[a].x() < vertices[b].x(); });
  for (size_t i = 0; i < order.size(); ++i) {
    for (size_t j = i + 1; j < order.size(); ++j) {
      if (vertices[order[j]].x() - vertices[order[i]].x() > eps) break;
      if ((vertices[order[j]] - vertices[order[i]]).norm() <= eps) {
        const int a = std::min(order[i], order[j]), b = std::max(order[i], order[j]);
        fail(what, "vertices " + std::to_string(a + 1) + " and " + std::to_string(b + 1) +
                       " coincide (degenerate)");
      }
    }
  }
}

void check_closed_and_oriented(const std::vector<FaceLoop>& faces, const std::string& what) {
  // (low, high, forward): forward when the face runs low -> high.
  std::vector<std::tuple<int, int, bool>> edges;
  for (const FaceLoop& face : faces) {
    for (size_t i = 0; i < face.size(); ++i) {
      const int from = face[i], to = face[(i + 1) % face.size()];
      edges.emplace_back(std::min(from, to), std::max(from, to), from < to);
    }
  }
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    int forward = 0;
    while (j < edges.size() && std::get<0>(edges[j]) == std::get<0>(edges[i]) &&
           std::get<1>(edges[j]) == std::get<1>(edges[i])) {
      forward += std::get<2>(edges[j]) ? 1 : 0;
      ++j;
    }
    const size_t uses = j - i;
    const int a = std::get<0>(edges[i]), b = std::get<1>(edges[i]);
    if (uses == 1) fail(what, "open surface: the " + edge_name(a, b) + " belongs to one face only");
    if (uses > 2) {
      fail(what, "non-manifold surface: the " + edge_name(a, b) + " belongs to " +
                     std::to_string(uses) + " faces");
    }
    if (forward != 1) {
      fail(what, "inconsistent face orientation: two faces run the " + edge_name(a, b) +
                     " in the same direction");
    }
    i = j;
  }
}

void check_faces(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                 double size, const std::string& what) {
  std::vector<Vec3> loop;
  for (size_t f = 0; f < faces.size(); ++f) {
    const std::string face_name = "face " + std::to_string(f + 1);
    loop.clear();
    for (int index : faces[f]) loop.push_back(vertices[index]);
    const Vec3 normal = newell_normal(loop);
    if (0.5 * normal.norm() <= kDegenerateArea * size * size) {
      fail(what, face_name + " has zero area (degenerate)");
    }
    const PlaneFrame frame = PlaneFrame::from_normal(loop[0], normal);
    Vec3 mean = Vec3::Zero();
    for (const Vec3& p : loop) mean += p;
    mean /= static_cast<double>(loop.size());
    for (size_t k = 0; k < loop.size(); ++k) {
      const double off = std::abs(frame.normal.dot(loop[k] - mean));
      if (off > kPlanarity * size) {
        std::ostringstream message;
        message << face_name << " is not planar: its vertex " << faces[f][k] + 1 << " is " << off
                << " m off the face's plane (allowed: " << kPlanarity * size << " m)";
        fail(what, message.str());
      }
    }
    if (loop.size() > 3) {
      Loop2 flat;
      for (const Vec3& p : loop) flat.push_back(frame.project(p));
      if (!is_convex(flat) && !is_simple_loop(flat)) {
        fail(what, face_name + " has an outline that crosses itself");
      }
    }
  }
}

}  // namespace

void validate_block(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                    const std::string& what) {
  check_counts_and_indices(vertices, faces, what);
  Box3 box;
  for (const Vec3& p : vertices) box.add(p);
  const double size = box.diagonal();
  if (size == 0.0) fail(what, "all vertices coincide (degenerate)");
  check_coincident_vertices(vertices, size, what);
  check_closed_and_oriented(faces, what);
  check_faces(vertices, faces, size, what);
  const double volume = mass_properties(vertices, faces).volume;
  if (std::abs(volume) <= kDegenerateVolume * size * size * size) {
    fail(what, "zero volume (degenerate: the vertices are flat or collapsed)");
  }
  if (volume < 0.0) {
    fail(what, "inverted: its faces point inward (list each face's vertices counter-clockwise "
               "seen from outside)");
  }
  // A closed, outward-oriented surface with every vertex behind every face
  // plane is convex and cannot intersect itself; only other shapes need the
  // (CGAL) intersection test.
  const bool convex =
      is_convex_polyhedron(vertices, face_planes(vertices, faces), kCoincidentVertices * size);
  if (!convex && surface_self_intersects(vertices, faces)) {
    fail(what, "self-intersecting: some of its faces cross each other");
  }
}

}  // namespace ashlar
