#include "geometry/block_builders.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/error.hpp"
#include "geometry/polygon.hpp"

namespace ashlar {

namespace {

// Side quads of a loft further than this (relative to the solid's size) from
// planar are split into triangles.
constexpr double kQuadPlanarity = 1e-9;

void check_points(const std::vector<Vec3>& points, const char* what, size_t minimum) {
  if (points.size() < minimum) {
    throw InvalidArgument(std::string(what) + " needs at least " + std::to_string(minimum) +
                          " points, got " + std::to_string(points.size()));
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw InvalidArgument(std::string(what) + ": point " + std::to_string(i + 1) +
                            " has a NaN or infinite coordinate");
    }
  }
}

// Unit normal of a planar polygon; throws if it has no area.
Vec3 polygon_normal(const std::vector<Vec3>& polygon, const char* what) {
  const Vec3 n = newell_normal(polygon);
  Box3 box;
  for (const Vec3& p : polygon) box.add(p);
  const double size = box.diagonal();
  if (n.norm() <= 1e-12 * size * size) {
    throw InvalidArgument(std::string(what) + " has zero area (its points are collinear)");
  }
  return n.normalized();
}

// "box", or "box 'name'" for a named one.
std::string builder_label(const char* builder, const BlockStyle& style) {
  return style.name.empty() ? std::string(builder) : std::string(builder) + " '" + style.name + "'";
}

std::string text(const Vec3& v) {
  std::ostringstream out;
  out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

Vec3 mean_point(const std::vector<Vec3>& points) {
  Vec3 sum = Vec3::Zero();
  for (const Vec3& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

bool quad_is_planar(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, double size) {
  const Vec3 n = newell_normal({a, b, c, d});
  if (n.norm() == 0.0) return false;
  return std::abs(n.normalized().dot(d - a)) <= kQuadPlanarity * size;
}

// Faces of a solid between loop `bottom` (indices 0..m-1) and `top`
// (m..2m-1), vertex i joined to vertex m+i. The bottom loop runs
// counter-clockwise about the direction towards the top.
std::vector<FaceLoop> side_faces_between(const std::vector<Vec3>& vertices, int m) {
  Box3 box;
  for (const Vec3& p : vertices) box.add(p);
  const double size = box.diagonal();
  std::vector<FaceLoop> faces;
  FaceLoop bottom, top;
  for (int i = 0; i < m; ++i) {
    bottom.push_back(m - 1 - i);
    top.push_back(m + i);
  }
  faces.push_back(bottom);
  faces.push_back(top);
  for (int i = 0; i < m; ++i) {
    const int j = (i + 1) % m;
    if (quad_is_planar(vertices[i], vertices[j], vertices[m + j], vertices[m + i], size)) {
      faces.push_back({i, j, m + j, m + i});
    } else {
      faces.push_back({i, j, m + j});
      faces.push_back({i, m + j, m + i});
    }
  }
  return faces;
}

}  // namespace

Block make_box(const Vec3& size, const Vec3& center, const BlockStyle& style) {
  if (!size.allFinite() || (size.array() <= 0.0).any()) {
    throw InvalidArgument(builder_label("box", style) +
                          " size must be three positive finite numbers (m), got " + text(size));
  }
  if (!center.allFinite()) {
    throw InvalidArgument(builder_label("box", style) + " center must be finite, got " + text(center));
  }
  const Vec3 half = 0.5 * size;
  std::vector<Vec3> corners;
  // Corner k has x = hi when bit 0 is set, y when bit 1, z when bit 2.
  for (int k = 0; k < 8; ++k) {
    corners.push_back(center + Vec3((k & 1) ? half.x() : -half.x(), (k & 2) ? half.y() : -half.y(),
                                    (k & 4) ? half.z() : -half.z()));
  }
  std::vector<FaceLoop> faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                 {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return Block(std::move(corners), std::move(faces), style.density, style.name, style.planarity);
}

Block make_prism(const std::vector<Vec3>& polygon, const Vec3& direction,
                 const BlockStyle& style) {
  check_points(polygon, "prism polygon", 3);
  if (!direction.allFinite() || direction.norm() == 0.0) {
    throw InvalidArgument(builder_label("prism", style) + " vector must be finite and non-zero, got " +
                          text(direction));
  }
  const Vec3 normal = polygon_normal(polygon, "prism polygon");
  if (std::abs(normal.dot(direction)) <= 1e-12 * direction.norm()) {
    throw InvalidArgument("prism vector lies in the polygon's plane: the prism would be flat");
  }
  std::vector<Vec3> bottom = polygon;
  if (normal.dot(direction) < 0.0) std::reverse(bottom.begin(), bottom.end());
  std::vector<Vec3> vertices = bottom;
  for (const Vec3& p : bottom) vertices.push_back(p + direction);
  const int m = static_cast<int>(bottom.size());
  std::vector<FaceLoop> faces = side_faces_between(vertices, m);
  return Block(std::move(vertices), std::move(faces), style.density, style.name, style.planarity);
}

Block support_plate(const std::vector<Vec3>& outline, const Vec3& toward, const BlockStyle& style) {
  Box3 extent;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : outline) {
    extent.add(p);
    centre += p;
  }
  centre /= static_cast<double>(outline.size());
  Vec3 away = -newell_normal(outline).normalized();
  if (away.dot(toward - centre) > 0.0) away = -away;
  return make_prism(outline, kSupportPlateThickness * extent.diagonal() * away, style);
}

Block make_loft(const std::vector<Vec3>& polygon_a, const std::vector<Vec3>& polygon_b,
                const BlockStyle& style) {
  check_points(polygon_a, "loft polygon_a", 3);
  check_points(polygon_b, "loft polygon_b", 3);
  if (polygon_a.size() != polygon_b.size()) {
    throw InvalidArgument("loft polygons need equal vertex counts, got " +
                          std::to_string(polygon_a.size()) + " and " +
                          std::to_string(polygon_b.size()));
  }
  const Vec3 normal_a = polygon_normal(polygon_a, "loft polygon_a");
  polygon_normal(polygon_b, "loft polygon_b");
  std::vector<Vec3> bottom = polygon_a, top = polygon_b;
  if (normal_a.dot(mean_point(polygon_b) - mean_point(polygon_a)) < 0.0) {
    std::reverse(bottom.begin(), bottom.end());
    std::reverse(top.begin(), top.end());
  }
  std::vector<Vec3> vertices = bottom;
  vertices.insert(vertices.end(), top.begin(), top.end());
  const int m = static_cast<int>(bottom.size());
  std::vector<FaceLoop> faces = side_faces_between(vertices, m);
  return Block(std::move(vertices), std::move(faces), style.density, style.name, style.planarity);
}

}  // namespace ashlar
