#include "structure/overlap_detection.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "geometry/solid_intersection.hpp"
#include "structure/contact_detection.hpp"

namespace ashlar {

namespace {

// Edge directions closer than this (1 - |cos|) are one direction, and edge
// pairs closer than it to parallel give no axis.
constexpr double kParallel = 1e-12;

std::vector<Vec3> edge_directions(const Block& block) {
  std::vector<Vec3> directions;
  for (const FaceLoop& face : block.faces()) {
    for (size_t k = 0; k < face.size(); ++k) {
      const int from = face[k], to = face[(k + 1) % face.size()];
      if (from > to) continue;  // each edge once: its other face runs it the other way
      const Vec3 d = (block.vertices()[to] - block.vertices()[from]).normalized();
      const bool known = std::any_of(directions.begin(), directions.end(), [&](const Vec3& e) {
        return 1.0 - std::abs(e.dot(d)) <= kParallel;
      });
      if (!known) directions.push_back(d);
    }
  }
  return directions;
}

struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
};

// Extent of points along a unit axis, measured from `origin`: relative to a
// point near them, the products keep their digits far from the origin.
Extent extent_along(const std::vector<Vec3>& points, const Vec3& axis, const Vec3& origin) {
  Extent extent;
  for (const Vec3& p : points) {
    const double t = axis.dot(p - origin);
    extent.lo = std::min(extent.lo, t);
    extent.hi = std::max(extent.hi, t);
  }
  return extent;
}

// Overlap (m) of the two blocks' projections on a unit axis; <= 0 when the
// axis separates them.
double projected_overlap(const Block& a, const Block& b, const Vec3& axis, const Vec3& origin) {
  const Extent ea = extent_along(a.vertices(), axis, origin), eb = extent_along(b.vertices(), axis, origin);
  return std::min(ea.hi, eb.hi) - std::max(ea.lo, eb.lo);
}

// Face normals of both blocks: most touching pairs are separated by one.
std::vector<Vec3> face_axes(const Block& a, const Block& b) {
  std::vector<Vec3> axes;
  for (const Block* block : {&a, &b}) {
    for (const FacePlane& plane : block->face_planes()) axes.push_back(plane.normal);
  }
  return axes;
}

// The rest of the separating-axis candidates: cross products of edge
// directions, one of each block.
std::vector<Vec3> edge_axes(const Block& a, const Block& b) {
  std::vector<Vec3> axes;
  const std::vector<Vec3> edges_a = edge_directions(a), edges_b = edge_directions(b);
  for (const Vec3& e : edges_a) {
    for (const Vec3& f : edges_b) {
      const Vec3 axis = e.cross(f);
      const double length = axis.norm();
      if (length * length > kParallel) axes.push_back(axis / length);
    }
  }
  return axes;
}

// How deep a and b overlap (m), or nothing when they do not by more than
// tol plus the warp of both blocks: two sides of a joint whose warped faces
// are cut differently (one face against two, as in staggered courses) are
// different surfaces, and share a lens as thick as their warp.
std::optional<double> overlap_depth(const Block& a, const Block& b, double tol) {
  tol += a.warp() + b.warp();
  const Vec3 origin = 0.5 * (a.bounds().lo + a.bounds().hi);
  std::vector<Vec3> axes = face_axes(a, b);
  double least = std::numeric_limits<double>::infinity();
  const auto separated = [&](const std::vector<Vec3>& candidates) {
    for (const Vec3& axis : candidates) {
      least = std::min(least, projected_overlap(a, b, axis, origin));
      if (least <= tol) return true;
    }
    return false;
  };
  if (separated(axes)) return std::nullopt;
  const std::vector<Vec3> more = edge_axes(a, b);
  if (separated(more)) return std::nullopt;
  axes.insert(axes.end(), more.begin(), more.end());
  if (a.convex() && b.convex() && !a.warped() && !b.warped()) return least;
  // Unseparated non-convex blocks may still only touch (a box in an L's
  // corner), and so may warped ones, whose solids are not the hulls of
  // their corners (the hulls of the two sides of a warped joint share its
  // warp): measure the solid they share, piece by piece (the depth is the
  // thickest piece's thinnest extent along the axes: differently faceted
  // curved joints share many thin pieces that together span the joint).
  // When CGAL cannot build it, the pair is left alone: a refused valid
  // structure is worse than a missed overlap.
  const std::optional<std::vector<std::vector<Vec3>>> shared = shared_solid_pieces(a, b);
  if (!shared || shared->empty()) return std::nullopt;
  double depth = 0.0;
  for (const std::vector<Vec3>& piece : *shared) {
    double thickness = std::numeric_limits<double>::infinity();
    for (const Vec3& axis : axes) {
      const Extent extent = extent_along(piece, axis, origin);
      thickness = std::min(thickness, extent.hi - extent.lo);
    }
    depth = std::max(depth, thickness);
  }
  if (depth <= tol) return std::nullopt;
  return depth;
}

}  // namespace

std::vector<BlockOverlap> detect_overlaps(const std::vector<const Block*>& blocks,
                                          double tolerance) {
  // Boxes shrunk by half the tolerance: boxes that only meet within it hold
  // no overlap deeper than it.
  std::vector<BlockOverlap> overlaps;
  for (const auto& [a, b] : box_pairs(blocks, -0.5 * tolerance)) {
    if (const std::optional<double> depth = overlap_depth(*blocks[a], *blocks[b], tolerance)) {
      overlaps.push_back({a, b, *depth});
    }
  }
  return overlaps;
}

}  // namespace ashlar
