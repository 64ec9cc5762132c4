// Flat-shaded triangle meshes of planar polygons, shared by every export
// that draws geometry (assimp's files and the HTML viewer).
#include "io/flat_mesh.hpp"

#include <algorithm>
#include <numeric>

#include "geometry/polygon.hpp"

namespace ashlar {
namespace {

double turn(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

bool inside_or_on(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
  return turn(a, b, p) >= 0 && turn(b, c, p) >= 0 && turn(c, a, p) >= 0;
}

// Ear clipping of a simple planar loop (convex or not; collinear runs
// allowed) seen from the side `normal` points to. Returns index triples into
// `loop`, counter-clockwise about `normal`.
std::vector<std::array<int, 3>> triangulate(const std::vector<Vec3>& loop, const Vec3& normal) {
  const PlaneFrame frame = PlaneFrame::from_normal(loop.front(), normal);
  Loop2 points;
  points.reserve(loop.size());
  for (const Vec3& p : loop) points.push_back(frame.project(p));
  std::vector<int> remaining(loop.size());
  std::iota(remaining.begin(), remaining.end(), 0);
  if (signed_area(points) < 0) std::reverse(remaining.begin(), remaining.end());

  std::vector<std::array<int, 3>> triangles;
  triangles.reserve(loop.size() - 2);
  // A strictly convex face is fanned from its first vertex, which is how a
  // Block bounds the solid of a warped face (mass_properties): the mesh
  // written is then the very solid the analyses use, and reads back with
  // the same volume. (Any triangulation of a planar face bounds the same
  // solid.)
  Loop2 ordered;
  for (int index : remaining) ordered.push_back(points[index]);
  const size_t corners = remaining.size();
  bool strictly_convex = is_convex(ordered);
  for (size_t i = 0; i < corners && strictly_convex; ++i) {
    strictly_convex = turn(ordered[(i + corners - 1) % corners], ordered[i], ordered[(i + 1) % corners]) > 0;
  }
  if (strictly_convex) {
    const size_t first = static_cast<size_t>(std::find(remaining.begin(), remaining.end(), 0) - remaining.begin());
    for (size_t k = 1; k + 1 < corners; ++k) {
      triangles.push_back({0, remaining[(first + k) % corners], remaining[(first + k + 1) % corners]});
    }
    return triangles;
  }
  while (remaining.size() > 3) {
    const size_t n = remaining.size();
    auto corner = [&](size_t i) {
      return std::array<int, 3>{remaining[(i + n - 1) % n], remaining[i], remaining[(i + 1) % n]};
    };
    auto corner_turn = [&](size_t i) {
      const auto [a, b, c] = corner(i);
      return turn(points[a], points[b], points[c]);
    };
    // Only reflex or straight corners can lie in an ear of a simple polygon.
    auto is_ear = [&](size_t i) {
      const auto [a, b, c] = corner(i);
      if (corner_turn(i) <= 0) return false;
      for (size_t j = 0; j < n; ++j) {
        const int other = remaining[j];
        if (other == a || other == b || other == c || corner_turn(j) > 0) continue;
        if (inside_or_on(points[other], points[a], points[b], points[c])) return false;
      }
      return true;
    };
    size_t ear = n;
    for (size_t i = 0; i < n && ear == n; ++i) {
      if (is_ear(i)) ear = i;
    }
    // Round-off can leave no clean ear in a nearly degenerate loop; the
    // sharpest convex corner is then the least harmful cut.
    if (ear == n) {
      ear = 0;
      for (size_t i = 1; i < n; ++i) {
        if (corner_turn(i) > corner_turn(ear)) ear = i;
      }
    }
    triangles.push_back(corner(ear));
    remaining.erase(remaining.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  triangles.push_back({remaining[0], remaining[1], remaining[2]});
  return triangles;
}

}  // namespace

void FlatMesh::add_polygon(const std::vector<Vec3>& loop, const Vec3& normal, bool flip) {
  const auto base = static_cast<unsigned>(positions.size());
  for (const Vec3& p : loop) {
    positions.push_back(p);
    normals.push_back(flip ? Vec3(-normal) : normal);
  }
  for (const auto& [a, b, c] : triangulate(loop, normal)) {
    if (flip) {
      triangles.push_back({base + a, base + c, base + b});
    } else {
      triangles.push_back({base + a, base + b, base + c});
    }
  }
}

FlatMesh block_mesh(const Block& block) {
  FlatMesh mesh;
  std::vector<Vec3> loop;
  for (size_t f = 0; f < block.faces().size(); ++f) {
    loop.clear();
    for (int index : block.faces()[f]) loop.push_back(block.vertices()[index]);
    mesh.add_polygon(loop, block.face_planes()[f].normal, false);
  }
  return mesh;
}

}  // namespace ashlar
