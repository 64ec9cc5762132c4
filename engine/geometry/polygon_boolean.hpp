// Boolean operations on general 2D polygons (non-convex, several pieces,
// holes). Exact arithmetic inside (CGAL); only this .cpp includes CGAL.
#pragma once

#include <vector>

#include "core/types.hpp"

namespace ashlar {

struct PolygonWithHoles2 {
  Loop2 outer;               // counter-clockwise
  std::vector<Loop2> holes;  // clockwise
};

// Intersection of the union of loops `a` with the union of loops `b`.
// Each input loop must be simple; orientation is normalised internally.
// The result lists every connected piece.
std::vector<PolygonWithHoles2> intersect_polygon_sets(const std::vector<Loop2>& a,
                                                      const std::vector<Loop2>& b);

// True if the loop does not touch or cross itself.
bool is_simple_loop(const Loop2& loop);

}  // namespace ashlar
