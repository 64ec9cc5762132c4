// Planar polygon utilities shared by block validation, contact detection and
// export. All loops are lists of points; no CGAL here (see polygon_boolean.hpp).
#pragma once

#include <vector>

#include "core/types.hpp"

namespace ashlar {

// Newell's normal of a 3D loop: direction of the loop's vector area, length
// twice its area. Robust for non-convex and slightly non-planar loops.
Vec3 newell_normal(const std::vector<Vec3>& loop);

// Orthonormal frame of a plane: origin, e1, e2 with e1 x e2 = normal.
struct PlaneFrame {
  Vec3 origin;
  Vec3 normal;
  Vec3 e1, e2;

  static PlaneFrame from_normal(const Vec3& origin, const Vec3& normal);
  Vec2 project(const Vec3& p) const;  // orthogonal projection, in frame coords
  Vec3 lift(const Vec2& q) const;     // frame coords back to 3D on the plane
  double distance(const Vec3& p) const { return normal.dot(p - origin); }
};

// Signed area (positive counter-clockwise) and area centroid of a 2D loop.
double signed_area(const Loop2& loop);
Vec2 area_centroid(const Loop2& loop);
bool is_convex(const Loop2& loop);  // counter-clockwise, allowing collinear runs

// Length of a closed 2D loop.
double perimeter(const Loop2& loop);

// The least width of a 2D loop: the least distance between two parallel
// lines that enclose it (rotating calipers on its convex hull), which does
// not depend on how the loop is turned. 0 for fewer than three distinct
// points or collinear ones.
double least_width(const Loop2& loop);

// Intersection of two convex counter-clockwise loops (Sutherland-Hodgman).
// Empty when they do not overlap.
Loop2 clip_convex(const Loop2& subject, const Loop2& clip);

}  // namespace ashlar
