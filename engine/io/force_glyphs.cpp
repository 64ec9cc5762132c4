#include "io/force_glyphs.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <set>

#include "analysis/equilibrium.hpp"

namespace ashlar {
namespace {


// A unit vector perpendicular to the unit vector `axis`, built from the
// coordinate axis least aligned with it so that it is well conditioned.
Vec3 any_perpendicular(const Vec3& axis) {
  Eigen::Index least = 0;
  axis.cwiseAbs().minCoeff(&least);
  return axis.cross(Vec3::Unit(least)).normalized();
}

// `sides` points on a circle about `center` in the plane normal to the unit
// vector `axis`, counter-clockwise about it, the first along `first`.
std::vector<Vec3> ring(const Vec3& center, const Vec3& axis, const Vec3& first, double radius,
                       int sides) {
  const Vec3 second = axis.cross(first);
  std::vector<Vec3> points;
  points.reserve(sides);
  for (int j = 0; j < sides; ++j) {
    const double angle = 2.0 * kPi * j / sides;
    points.push_back(center + radius * (std::cos(angle) * first + std::sin(angle) * second));
  }
  return points;
}

// Outward faces facing back along the axis (reversed ring) and the sides
// between two rings of the same orientation.
void add_start_cap(const std::vector<Vec3>& start, GlyphFaces& faces) {
  faces.emplace_back(start.rbegin(), start.rend());
}

void add_sides(const std::vector<Vec3>& start, const std::vector<Vec3>& end, GlyphFaces& faces) {
  const size_t n = start.size();
  for (size_t j = 0; j < n; ++j) {
    const size_t next = (j + 1) % n;
    faces.push_back({start[j], start[next], end[next], end[j]});
  }
}

}  // namespace

GlyphFaces arrow_faces(const Vec3& tail, const Vec3& tip, const ArrowShape& shape) {
  const double length = (tip - tail).norm();
  const Vec3 axis = (tip - tail) / length;
  const Vec3 first = any_perpendicular(axis);
  const Vec3 neck = tip - shape.head_length * axis;
  const auto tail_ring = ring(tail, axis, first, shape.shaft_radius, shape.sides);
  const auto neck_ring = ring(neck, axis, first, shape.shaft_radius, shape.sides);
  const auto head_ring = ring(neck, axis, first, shape.head_radius, shape.sides);

  GlyphFaces faces;
  add_start_cap(tail_ring, faces);
  add_sides(tail_ring, neck_ring, faces);
  const size_t n = neck_ring.size();
  for (size_t j = 0; j < n; ++j) {
    const size_t next = (j + 1) % n;
    // The flat ring under the head, facing back towards the tail.
    faces.push_back({neck_ring[j], neck_ring[next], head_ring[next], head_ring[j]});
    faces.push_back({head_ring[j], head_ring[next], tip});
  }
  return faces;
}

GlyphFaces tube_faces(const std::vector<Vec3>& points, double radius, int sides) {
  GlyphFaces faces;
  if (points.empty()) return faces;
  // Slivers would be degenerate triangles once stored in single precision.
  const double shortest = 1e-3 * radius;
  Vec3 from = points.front();
  Vec3 first = Vec3::Zero();
  for (const Vec3& to : points) {
    const Vec3 segment = to - from;
    if (segment.norm() <= shortest) continue;
    const Vec3 axis = segment.normalized();
    // Carry the previous orientation over the bend (parallel transport).
    const Vec3 carried = first - first.dot(axis) * axis;
    first = carried.norm() > 1e-6 ? Vec3(carried.normalized()) : any_perpendicular(axis);
    const auto start = ring(from, axis, first, radius, sides);
    const auto end = ring(to, axis, first, radius, sides);
    add_start_cap(start, faces);
    add_sides(start, end, faces);
    faces.push_back(end);
    from = to;
  }
  return faces;
}

namespace {

// Proportions of glyphs, as fractions of the mean free-block size or of
// the largest arrow: thin enough not to hide each other at a joint, thick
// enough to see in a whole-structure view.
constexpr double kLargestArrowOfBlockSize = 0.25;
constexpr double kShaftRadiusOfLargestArrow = 0.06;
constexpr double kHeadRadiusOfLargestArrow = 0.16;
constexpr double kHeadLengthOfLargestArrow = 0.35;
// Thinner than a shaft: arrows run along the thrust line and must show.
constexpr double kThrustRadiusOfBlockSize = 0.012;
// Thinner than the thrust line: hundreds of traces share a post.
constexpr double kTraceRadiusOfBlockSize = 0.006;
// Thicker than the thrust line so that a cable reads as a member.
constexpr double kCableRadiusOfBlockSize = 0.02;
constexpr int kGlyphSides = 6;
// Block edges: thin square tubes, so that blocks read as masonry in any
// viewer (line primitives are not drawn by every one).
constexpr double kEdgeRadiusOfBlockSize = 0.004;
constexpr int kEdgeSides = 4;

bool finite(const Vec3& v) { return v.allFinite(); }

// Joint normals closer than this to horizontal (or to a coordinate plane)
// count as lying in it: round-off must not flip an arrow.
constexpr double kFlatNormal = 1e-9;

// Whether the unit normal n points upward: z up, then +x, then +y.
bool points_up(const Vec3& n) {
  for (int axis : {2, 0, 1}) {
    if (std::abs(n[axis]) > kFlatNormal) return n[axis] > 0.0;
  }
  return false;
}

// The round number 1, 2 or 5 x 10^k nearest `value` (> 0) on a log scale.
double round_number(double value) {
  const double decade = std::pow(10.0, std::floor(std::log10(value)));
  double best = decade;
  for (double step : {2.0, 5.0, 10.0}) {
    if (std::abs(std::log(step * decade / value)) < std::abs(std::log(best / value))) best = step * decade;
  }
  return best;
}

double largest_resultant(const EquilibriumResult& result) {
  double largest = 0.0;
  for (const InterfaceForces& f : result.interfaces) {
    if (finite(f.resultant)) largest = std::max(largest, f.resultant.norm());
  }
  return largest;
}

void add_force_arrows(const Structure& structure, const EquilibriumResult& result, const ExportOptions& options,
                      std::vector<NamedGlyph>& glyphs) {
  const double largest = largest_resultant(result);
  if (largest == 0.0) return;
  const double metres_per_newton = force_arrow_scale(structure, options);
  const double largest_arrow = metres_per_newton * largest;
  const double negligible = options.negligible_force * largest;
  const std::shared_ptr<const std::vector<Interface>> contacts = structure.interfaces(options.contact);
  std::map<std::string, int> uses;
  for (std::size_t k = 0; k < result.interfaces.size(); ++k) {
    const InterfaceForces& f = result.interfaces[k];
    const double size = f.resultant.norm();
    if (!(size > negligible) || !finite(f.resultant) || !finite(f.center_of_pressure)) continue;
    const double length = metres_per_newton * size;
    ArrowShape shape;
    shape.sides = kGlyphSides;
    shape.shaft_radius = kShaftRadiusOfLargestArrow * largest_arrow;
    shape.head_radius = kHeadRadiusOfLargestArrow * largest_arrow;
    // Short arrows keep a shaft, so that their direction still reads.
    shape.head_length = std::min(kHeadLengthOfLargestArrow * largest_arrow, 0.5 * length);
    std::string name = "force " + std::to_string(f.a + 1) + "-" + std::to_string(f.b + 1);
    const int use = ++uses[name];
    if (use > 1) name += " #" + std::to_string(use);
    const ArrowForce drawn = arrow_force(structure, contacts->at(k), f);
    const Vec3 tip = f.center_of_pressure + length * drawn.force / size;
    const bool pulls = f.tension > negligible;
    glyphs.push_back({std::move(name), arrow_faces(f.center_of_pressure, tip, shape),
                      pulls ? options.tension_color : options.compression_color, SceneLayer::forces,
                      static_cast<int>(k), ArrowGlyph{f.center_of_pressure, tip, shape}});
  }
}

}  // namespace

std::vector<std::array<Vec3, 2>> block_edges(const Block& block) {
  std::vector<std::array<Vec3, 2>> edges;
  std::set<std::pair<int, int>> drawn;
  for (const FaceLoop& face : block.faces()) {
    for (std::size_t k = 0; k < face.size(); ++k) {
      const int p = face[k], q = face[(k + 1) % face.size()];
      if (drawn.insert({std::min(p, q), std::max(p, q)}).second) {
        edges.push_back({block.vertices()[p], block.vertices()[q]});
      }
    }
  }
  return edges;
}

double mean_free_block_size(const Structure& structure) {
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < structure.size(); ++i) {
    if (structure.is_support(i)) continue;
    sum += structure.block(i).bounds().diagonal();
    ++count;
  }
  return count > 0 ? sum / count : structure.bounds().diagonal();
}

ArrowForce arrow_force(const Structure& structure, const Interface& contact, const InterfaceForces& forces) {
  // forces.resultant acts on forces.b; contact.normal points from a into b.
  const bool a_support = structure.is_support(forces.a), b_support = structure.is_support(forces.b);
  const bool on_b = a_support != b_support ? a_support : points_up(contact.normal);
  if (on_b) return {forces.b, forces.a, forces.resultant};
  return {forces.a, forces.b, -forces.resultant};
}

double force_arrow_scale(const Structure& structure, const ExportOptions& options) {
  const double largest = largest_resultant(*options.result);
  if (largest == 0.0) return 0.0;
  if (options.force_scale > 0.0) return options.force_scale;
  const double newtons_per_metre = round_number(largest / (kLargestArrowOfBlockSize * mean_free_block_size(structure)));
  return 1.0 / newtons_per_metre;
}

std::vector<NamedGlyph> equilibrium_glyphs(const Structure& structure,
                                           const ExportOptions& options) {
  std::vector<NamedGlyph> glyphs;
  const double block_size = mean_free_block_size(structure);
  if (options.edges) {
    GlyphFaces edges;
    for (int i = 0; i < structure.size(); ++i) {
      for (const auto& [p, q] : block_edges(structure.block(i))) {
        GlyphFaces tube = tube_faces({p, q}, kEdgeRadiusOfBlockSize * block_size, kEdgeSides);
        edges.insert(edges.end(), std::make_move_iterator(tube.begin()), std::make_move_iterator(tube.end()));
      }
    }
    if (!edges.empty()) glyphs.push_back({"edges", std::move(edges), options.edge_color, SceneLayer::edges});
  }
  for (std::size_t c = 0; c < structure.cables().size(); ++c) {
    const Cable& cable = structure.cables()[c];
    GlyphFaces tube = tube_faces({cable.from.point, cable.to.point},
                                 kCableRadiusOfBlockSize * block_size, kGlyphSides);
    if (!tube.empty()) {
      glyphs.push_back({"cable " + std::to_string(c + 1), std::move(tube), options.cable_color, SceneLayer::cables});
    }
  }
  GlyphFaces traces;
  for (const std::vector<Vec3>& trace : options.traces) {
    GlyphFaces tube = tube_faces(trace, kTraceRadiusOfBlockSize * block_size, kGlyphSides);
    traces.insert(traces.end(), std::make_move_iterator(tube.begin()),
                  std::make_move_iterator(tube.end()));
  }
  if (!traces.empty()) glyphs.push_back({"load traces", std::move(traces), options.trace_color, SceneLayer::traces});
  if (!options.result) return glyphs;
  if (options.forces) add_force_arrows(structure, *options.result, options, glyphs);
  if (options.thrust) {  // every branch, as the drawings show it
    GlyphFaces tubes;
    for (std::vector<Vec3> points : thrust_polylines(structure, *options.result)) {
      const auto not_finite = [](const Vec3& p) { return !finite(p); };
      points.erase(std::remove_if(points.begin(), points.end(), not_finite), points.end());
      GlyphFaces tube = tube_faces(points, kThrustRadiusOfBlockSize * block_size, kGlyphSides);
      tubes.insert(tubes.end(), std::make_move_iterator(tube.begin()), std::make_move_iterator(tube.end()));
    }
    if (!tubes.empty()) glyphs.push_back({"thrust line", std::move(tubes), options.thrust_color, SceneLayer::thrust});
  }
  return glyphs;
}

}  // namespace ashlar
