#include "geometry/block_validation.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <sstream>
#include <tuple>

#include "core/error.hpp"
#include "core/union_find.hpp"
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
// Block sizes (m) whose volume and first moments (size^4) stay normal
// doubles, with room for densities and forces.
constexpr double kSmallestSize = 1e-30;
constexpr double kLargestSize = 1e30;

[[noreturn]] void fail(const std::string& what, const std::string& defect) {
  throw GeometryError(what + " is not a valid block: " + defect);
}

std::string edge_name(int i, int j, const MeshNumbering& numbering) {
  return "edge between " + numbering.vertices(i, j);
}

void check_counts_and_indices(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                              const std::string& what, const MeshNumbering& numbering) {
  if (vertices.size() < 4) {
    fail(what, "needs at least 4 vertices, got " + std::to_string(vertices.size()));
  }
  if (faces.size() < 4) fail(what, "needs at least 4 faces, got " + std::to_string(faces.size()));
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) {
      std::ostringstream message;
      message << numbering.vertex(static_cast<int>(i)) << " is (" << vertices[i].x() << ", " << vertices[i].y() << ", "
              << vertices[i].z() << "): expected finite coordinates, not NaN or infinity";
      fail(what, message.str());
    }
  }
  const int count = static_cast<int>(vertices.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    const FaceLoop& face = faces[f];
    const std::string face_name = numbering.face(static_cast<int>(f));
    if (face.size() < 3) {
      fail(what, face_name + " has " + std::to_string(face.size()) +
                     " vertices: expected a polygon of at least 3");
    }
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
      fail(what, face_name + " uses " + numbering.vertex(*repeat) +
                     " twice: expected each corner of a face once");
    }
  }
}

void check_coincident_vertices(const std::vector<Vec3>& vertices, double size, const std::string& what,
                               const MeshNumbering& numbering) {
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
        fail(what, numbering.vertices(a, b) +
                       " coincide: expected distinct points (faces that share a corner use "
                       "one vertex index for it)");
      }
    }
  }
}

void check_closed_and_oriented(const std::vector<FaceLoop>& faces, const std::string& what,
                               const MeshNumbering& numbering) {
  // (low, high, forward, face): forward when the face runs low -> high.
  std::vector<std::tuple<int, int, bool, int>> edges;
  for (size_t f = 0; f < faces.size(); ++f) {
    const FaceLoop& face = faces[f];
    for (size_t i = 0; i < face.size(); ++i) {
      const int from = face[i], to = face[(i + 1) % face.size()];
      edges.emplace_back(std::min(from, to), std::max(from, to), from < to, static_cast<int>(f));
    }
  }
  std::sort(edges.begin(), edges.end());
  UnionFind pieces(faces.size());  // faces joined through shared edges
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
    const std::string first_face = numbering.face(std::get<3>(edges[i]));
    if (uses == 1) {
      fail(what, "open surface: the " + edge_name(a, b, numbering) + " belongs to " + first_face +
                     " only (expected a closed surface: every edge shared by two faces)");
    }
    if (uses > 2) {
      fail(what, "non-manifold surface: the " + edge_name(a, b, numbering) + " belongs to " +
                     std::to_string(uses) + " faces (expected two)");
    }
    if (forward != 1) {
      fail(what, "inconsistent face orientation: " + first_face + " and " +
                     numbering.face(std::get<3>(edges[i + 1])) + " run the " + edge_name(a, b, numbering) +
                     " in the same direction (expected every face counter-clockwise seen from "
                     "outside, so that neighbours run a shared edge in opposite directions)");
    }
    pieces.join(std::get<3>(edges[i]), std::get<3>(edges[i + 1]));
    i = j;
  }
  // Two solids in one block (two mesh objects of one name, which OBJ
  // readers merge, or a shell inside a shell) would move as one rigid body.
  for (size_t f = 1; f < faces.size(); ++f) {
    if (pieces.root(static_cast<int>(f)) != pieces.root(0)) {
      fail(what, "its surface is in separate pieces (" + numbering.face(0) + " and " +
                     numbering.face(static_cast<int>(f)) + " are not joined by any path of shared edges): expected one connected solid; "
                     "make each piece a block of its own");
    }
  }
}

// The largest distance of a face's vertices from its best-fit plane (unit
// normal, through `mean`) as a fraction of its size, rounded up to 2
// significant digits: the planarity that accepts the face.
double warp_fraction(const std::vector<Vec3>& loop, const Vec3& normal, const Vec3& mean, double face_size) {
  double off = 0.0;
  for (const Vec3& p : loop) off = std::max(off, std::abs(normal.dot(p - mean)));
  const double fraction = off / face_size;
  const double unit = std::pow(10.0, std::floor(std::log10(fraction)) - 1);
  return std::ceil(fraction / unit) * unit;
}

void check_faces(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces, double size,
                 double planarity, const std::string& what, const MeshNumbering& numbering) {
  std::vector<Vec3> loop;
  for (size_t f = 0; f < faces.size(); ++f) {
    const std::string face_name = numbering.face(static_cast<int>(f));
    loop.clear();
    for (int index : faces[f]) loop.push_back(vertices[index]);
    const Vec3 normal = newell_normal(loop);
    if (0.5 * normal.norm() <= kDegenerateArea * size * size) {
      fail(what, face_name + " has zero area: expected a polygon whose vertices do not all lie "
                             "on one line");
    }
    const PlaneFrame frame = PlaneFrame::from_normal(loop[0], normal);
    Vec3 mean = Vec3::Zero();
    Box3 face_box;
    for (const Vec3& p : loop) {
      mean += p;
      face_box.add(p);
    }
    mean /= static_cast<double>(loop.size());
    const double face_size = face_box.diagonal();
    const double allowed = std::max(kPlanarity * size, planarity * face_size);
    for (size_t k = 0; k < loop.size(); ++k) {
      const double off = std::abs(frame.normal.dot(loop[k] - mean));
      if (off > allowed) {
        std::ostringstream message;
        if (planarity == 0.0) {
          message << face_name << " is not planar: its " << numbering.vertex(faces[f][k]) << " is " << off
                  << " m off the face's plane (allowed: " << allowed
                  << " m); to accept warped faces pass planarity, a fraction of each face's size: "
                  << "this face needs at least " << warp_fraction(loop, frame.normal, mean, face_size);
        } else {
          message << face_name << " is warped beyond planarity " << planarity << ": its "
                  << numbering.vertex(faces[f][k]) << " is " << off << " m off the face's best-fit plane, "
                  << off / face_size << " of the face's size " << face_size << " m (allowed: " << allowed
                  << " m); this face needs planarity " << warp_fraction(loop, frame.normal, mean, face_size);
        }
        fail(what, message.str());
      }
    }
    if (loop.size() > 3) {
      Loop2 flat;
      for (const Vec3& p : loop) flat.push_back(frame.project(p));
      if (!is_convex(flat) && !is_simple_loop(flat)) {
        fail(what, face_name + " has an outline that crosses itself: expected a simple polygon");
      }
    }
  }
}

}  // namespace

std::string MeshNumbering::vertex(int index) const {
  return vertex_name ? vertex_name(index) : "vertex " + std::to_string(index + 1);
}

std::string MeshNumbering::face(int index) const {
  return face_name ? face_name(index) : "face " + std::to_string(index + 1);
}

std::string MeshNumbering::vertices(int a, int b) const {
  if (vertex_name) return vertex_name(a) + " and " + vertex_name(b);
  return "vertices " + std::to_string(a + 1) + " and " + std::to_string(b + 1);
}

std::string MeshNumbering::faces(int a, int b) const {
  if (face_name) return face_name(a) + " and " + face_name(b);
  return "faces " + std::to_string(a + 1) + " and " + std::to_string(b + 1);
}

void validate_block(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                    const std::string& what, double planarity, const MeshNumbering& numbering) {
  check_counts_and_indices(vertices, faces, what, numbering);
  Box3 box;
  for (const Vec3& p : vertices) box.add(p);
  // stableNorm: the plain norm squares the extent, which overflows or
  // underflows long before the extent itself does.
  const double size = (box.hi - box.lo).stableNorm();
  if (size == 0.0) fail(what, "all vertices coincide: expected a solid with extent");
  if (size < kSmallestSize || size > kLargestSize) {
    std::ostringstream message;
    message << "its size (bounding-box diagonal) is " << size << " m: expected " << kSmallestSize
            << " to " << kLargestSize << " m, where its volume and moments stay within double range";
    fail(what, message.str());
  }
  check_coincident_vertices(vertices, size, what, numbering);
  check_closed_and_oriented(faces, what, numbering);
  check_faces(vertices, faces, size, planarity, what, numbering);
  const double volume = mass_properties(vertices, faces).volume;
  if (std::abs(volume) <= kDegenerateVolume * size * size * size) {
    fail(what, "zero volume: its vertices are flat or collapsed (expected a solid with volume)");
  }
  if (volume < 0.0) {
    fail(what, "inverted: its faces point inward (list each face's vertices counter-clockwise "
               "seen from outside)");
  }
  // A closed, outward-oriented surface with every vertex behind every face
  // plane is convex and cannot intersect itself; only other shapes need the
  // (CGAL) intersection test.
  const std::vector<FacePlane> planes = face_planes(vertices, faces);
  // A warped face's own vertices lie in front of its best-fit plane.
  const bool convex = is_convex_polyhedron(vertices, planes,
                                           std::max(kCoincidentVertices * size, largest_warp(vertices, faces, planes)));
  if (!convex) {
    if (const std::optional<std::string> crossing = surface_self_intersection(vertices, faces, numbering)) {
      fail(what, "self-intersecting: " + *crossing +
                     " (expected a surface that does not cross or touch itself)");
    }
  }
}

}  // namespace ashlar
