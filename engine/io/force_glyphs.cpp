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
// Joints whose normal force is under this fraction of the largest carry no
// thrust (round-off, blocks that merely touch), as in thrust_polylines.
constexpr double kNegligibleThrust = 1e-3;
// A joint normal within this (as the cosine to the plane's normal) of a
// vertical plane lies in it: generated arches are exact to round-off.
constexpr double kInPlane = 1e-6;

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

// Thicker than the thrust line: a network's tubes are its only picture of
// the forces, read by their thickness.
constexpr double kNetworkRadiusOfBlockSize = 0.04;

// The interfaces' names in arrows: "a-b" (1-based blocks), "a-b #2" for a
// second interface between the same blocks, and so on.
std::vector<std::string> pair_labels(const EquilibriumResult& result) {
  std::map<std::string, int> uses;
  std::vector<std::string> labels;
  labels.reserve(result.interfaces.size());
  for (const InterfaceForces& f : result.interfaces) {
    std::string label = std::to_string(f.a + 1) + "-" + std::to_string(f.b + 1);
    const int use = ++uses[label];
    if (use > 1) label += " #" + std::to_string(use);
    labels.push_back(std::move(label));
  }
  return labels;
}

// The parts of the force at contact vertex j acting on block b (N): normal
// (along the joint's normal, positive in compression) and friction.
struct VertexParts {
  Vec3 normal = Vec3::Zero(), friction = Vec3::Zero();
};
VertexParts vertex_parts(const EquilibriumResult& result, const Interface& contact, std::size_t j) {
  const Eigen::Vector4d& f = result.vertex_forces[j];
  return {(f(0) - f(1)) * contact.normal, f(2) * contact.u + f(3) * contact.v};
}

// The largest force an arrow draws (N): a resultant, or a vertex's normal or
// friction part.
double largest_drawn_force(const Structure& structure, const ExportOptions& options) {
  const EquilibriumResult& result = *options.result;
  double largest = 0.0;
  if (options.force_mode == ForceMode::resultants) {
    for (const InterfaceForces& f : result.interfaces) {
      if (finite(f.resultant)) largest = std::max(largest, f.resultant.norm());
    }
    return largest;
  }
  const std::shared_ptr<const std::vector<Interface>> contacts = structure.interfaces(options.contact);
  for (std::size_t j = 0; j < result.vertex_forces.size(); ++j) {
    const VertexParts parts = vertex_parts(result, contacts->at(result.vertex_interface[j]), j);
    for (const Vec3& part : {parts.normal, parts.friction}) {
      if (finite(part)) largest = std::max(largest, part.norm());
    }
  }
  return largest;
}

// An arrow of `force` (N) from `tail`, `metres_per_newton` long per newton,
// proportioned to the largest arrow (m).
NamedGlyph force_arrow(std::string name, const Vec3& tail, const Vec3& force, double metres_per_newton,
                       double largest_arrow, const Rgb& color, int interface) {
  const double length = metres_per_newton * force.norm();
  ArrowShape shape;
  shape.sides = kGlyphSides;
  shape.shaft_radius = kShaftRadiusOfLargestArrow * largest_arrow;
  shape.head_radius = kHeadRadiusOfLargestArrow * largest_arrow;
  // Short arrows keep a shaft, so that their direction still reads.
  shape.head_length = std::min(kHeadLengthOfLargestArrow * largest_arrow, 0.5 * length);
  const Vec3 tip = tail + metres_per_newton * force;
  return {std::move(name), arrow_faces(tail, tip, shape), color, SceneLayer::forces, interface,
          ArrowGlyph{tail, tip, shape, force}};
}

void add_force_arrows(const Structure& structure, const EquilibriumResult& result, const ExportOptions& options,
                      std::vector<NamedGlyph>& glyphs) {
  const double largest = largest_drawn_force(structure, options);
  if (largest == 0.0) return;
  const double metres_per_newton = force_arrow_scale(structure, options);
  const double largest_arrow = metres_per_newton * largest;
  const double negligible = options.negligible_force * largest;
  const std::shared_ptr<const std::vector<Interface>> contacts = structure.interfaces(options.contact);
  const std::vector<std::string> labels = pair_labels(result);
  if (options.force_mode == ForceMode::resultants) {
    for (std::size_t k = 0; k < result.interfaces.size(); ++k) {
      const InterfaceForces& f = result.interfaces[k];
      if (!(f.resultant.norm() > negligible) || !finite(f.resultant) || !finite(f.center_of_pressure)) continue;
      const ArrowForce drawn = arrow_force(structure, contacts->at(k), f);
      const bool pulls = f.tension > negligible;
      glyphs.push_back(force_arrow("force " + labels[k], f.center_of_pressure, drawn.force, metres_per_newton,
                                   largest_arrow, pulls ? options.tension_color : options.compression_color,
                                   static_cast<int>(k)));
    }
    return;
  }
  std::vector<int> vertices_seen(result.interfaces.size(), 0);
  for (std::size_t j = 0; j < result.vertex_forces.size(); ++j) {
    const int k = result.vertex_interface[j];
    const Interface& contact = contacts->at(k);
    const InterfaceForces& f = result.interfaces[k];
    const std::string vertex = labels[k] + " vertex " + std::to_string(++vertices_seen[k]);
    // On the block the resultant's arrow acts on.
    const double sign = arrow_force(structure, contact, f).on == f.b ? 1.0 : -1.0;
    const VertexParts parts = vertex_parts(result, contact, j);
    const Vec3& at = result.vertex_positions[j];
    if (!finite(at)) continue;
    if (parts.normal.norm() > negligible && finite(parts.normal)) {
      const bool pulls = parts.normal.dot(contact.normal) < 0.0;
      glyphs.push_back(force_arrow("force " + vertex, at, sign * parts.normal, metres_per_newton, largest_arrow,
                                   pulls ? options.tension_color : options.compression_color, k));
    }
    if (parts.friction.norm() > negligible && finite(parts.friction)) {
      glyphs.push_back(force_arrow("friction " + vertex, at, sign * parts.friction, metres_per_newton,
                                   largest_arrow, options.friction_color, k));
    }
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
  const double largest = largest_drawn_force(structure, options);
  if (largest == 0.0) return 0.0;
  if (options.force_scale > 0.0) return options.force_scale;
  const double newtons_per_metre = round_number(largest / (kLargestArrowOfBlockSize * mean_free_block_size(structure)));
  return 1.0 / newtons_per_metre;
}

bool thrust_in_one_plane(const Structure& structure, const std::vector<Interface>& contacts,
                         const EquilibriumResult& result) {
  if (structure.planar()) return true;
  double largest = 0.0;
  for (const InterfaceForces& f : result.interfaces) {
    if (std::isfinite(f.normal_force)) largest = std::max(largest, f.normal_force);
  }
  // The plane's horizontal normal, from the first joint that is not level.
  std::optional<Vec3> across;
  for (std::size_t k = 0; k < result.interfaces.size(); ++k) {
    if (!(result.interfaces[k].normal_force > kNegligibleThrust * largest)) continue;
    const Vec3& n = contacts.at(k).normal;
    const Vec3 horizontal(n.x(), n.y(), 0.0);
    if (horizontal.norm() < kFlatNormal) continue;
    if (!across) {
      across = Vec3(-horizontal.y(), horizontal.x(), 0.0).normalized();
    } else if (std::abs(n.dot(*across)) > kInPlane) {
      return false;
    }
  }
  return true;
}

std::vector<TubeSegment> thrust_network(const Structure& structure, const EquilibriumResult& result,
                                        double largest_radius) {
  double largest_normal = 0.0, largest_resultant = 0.0;
  for (const InterfaceForces& f : result.interfaces) {
    if (std::isfinite(f.normal_force)) largest_normal = std::max(largest_normal, f.normal_force);
    if (finite(f.resultant)) largest_resultant = std::max(largest_resultant, f.resultant.norm());
  }
  std::vector<TubeSegment> segments;
  for (const InterfaceForces& f : result.interfaces) {
    if (!(f.normal_force > kNegligibleThrust * largest_normal) || !finite(f.center_of_pressure) ||
        !finite(f.resultant)) {
      continue;
    }
    const double radius = largest_radius * std::sqrt(f.resultant.norm() / largest_resultant);
    for (const int block : {f.a, f.b}) {
      if (!structure.is_support(block)) segments.push_back({structure.block(block).centroid(), f.center_of_pressure, radius});
    }
  }
  return segments;
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
  if (options.thrust && !thrust_in_one_plane(structure, *structure.interfaces(options.contact), *options.result)) {
    const std::vector<TubeSegment> network =
        thrust_network(structure, *options.result, kNetworkRadiusOfBlockSize * block_size);
    GlyphFaces tubes;
    for (const TubeSegment& segment : network) {
      GlyphFaces tube = tube_faces({segment.from, segment.to}, segment.radius, kGlyphSides);
      tubes.insert(tubes.end(), std::make_move_iterator(tube.begin()), std::make_move_iterator(tube.end()));
    }
    if (!tubes.empty()) {
      glyphs.push_back({"thrust network", std::move(tubes), options.thrust_color, SceneLayer::thrust, -1,
                        std::nullopt, -1, network});
    }
  } else if (options.thrust) {  // every branch, as the drawings show it
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
