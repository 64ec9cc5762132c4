// General polygon booleans with CGAL. Constructions are exact (Epeck): the
// vertices of an intersection are new points, and rounding them inside the
// sweep would break the arrangement; only the final output is rounded.
#include "geometry/polygon_boolean.hpp"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Polygon_set_2.h>

#include <iterator>
#include <string>

#include "core/error.hpp"

namespace ashlar {

namespace {

using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPolygon = CGAL::Polygon_2<ExactKernel>;
using ExactPolygonWithHoles = CGAL::Polygon_with_holes_2<ExactKernel>;
using ExactPolygonSet = CGAL::Polygon_set_2<ExactKernel>;
// Predicates alone are exact in the cheaper kernel; simplicity needs no new points.
using PredicateKernel = CGAL::Exact_predicates_inexact_constructions_kernel;

bool finite(const Loop2& loop) {
  for (const Vec2& p : loop) {
    if (!p.allFinite()) return false;
  }
  return true;
}

// The union of simple loops, each made counter-clockwise first (Polygon_set_2
// reads a clockwise outer boundary as a hole).
ExactPolygonSet union_of_loops(const std::vector<Loop2>& loops, const char* operand) {
  std::vector<ExactPolygon> polygons;
  polygons.reserve(loops.size());
  for (size_t k = 0; k < loops.size(); ++k) {
    if (!is_simple_loop(loops[k])) {
      throw InvalidArgument(std::string("polygon intersection: loop ") + std::to_string(k + 1) +
                            " of operand " + operand +
                            " is not a simple polygon (it needs at least 3 finite points and "
                            "must not touch or cross itself)");
    }
    ExactPolygon polygon;
    for (const Vec2& p : loops[k]) polygon.push_back(ExactKernel::Point_2(p.x(), p.y()));
    if (polygon.is_clockwise_oriented()) polygon.reverse_orientation();
    polygons.push_back(std::move(polygon));
  }
  ExactPolygonSet set;
  set.join(polygons.begin(), polygons.end());
  return set;
}

Loop2 to_loop(const ExactPolygon& polygon) {
  Loop2 loop;
  loop.reserve(polygon.size());
  for (auto v = polygon.vertices_begin(); v != polygon.vertices_end(); ++v) {
    loop.emplace_back(CGAL::to_double(v->x()), CGAL::to_double(v->y()));
  }
  return loop;
}

}  // namespace

std::vector<PolygonWithHoles2> intersect_polygon_sets(const std::vector<Loop2>& a,
                                                      const std::vector<Loop2>& b) {
  ExactPolygonSet common = union_of_loops(a, "a");
  common.intersection(union_of_loops(b, "b"));
  std::vector<ExactPolygonWithHoles> pieces;
  common.polygons_with_holes(std::back_inserter(pieces));

  std::vector<PolygonWithHoles2> result;
  result.reserve(pieces.size());
  for (const ExactPolygonWithHoles& piece : pieces) {
    PolygonWithHoles2 out;
    out.outer = to_loop(piece.outer_boundary());  // CGAL keeps it counter-clockwise
    for (auto hole = piece.holes_begin(); hole != piece.holes_end(); ++hole) {
      out.holes.push_back(to_loop(*hole));  // and holes clockwise
    }
    result.push_back(std::move(out));
  }
  return result;
}

bool is_simple_loop(const Loop2& loop) {
  if (loop.size() < 3 || !finite(loop)) return false;
  std::vector<PredicateKernel::Point_2> points;
  points.reserve(loop.size());
  for (const Vec2& p : loop) points.emplace_back(p.x(), p.y());
  return CGAL::is_simple_2(points.begin(), points.end(), PredicateKernel());
}

}  // namespace ashlar
