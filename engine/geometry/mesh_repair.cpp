// Turns a polygon soup (mesh files, CGAL outputs) into a Block: welds
// vertices, drops what welding made degenerate, and merges coplanar faces
// back into polygons so that a triangulated box has six faces again.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <queue>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "core/error.hpp"
#include "core/point_grid.hpp"
#include "geometry/block_builders.hpp"
#include "geometry/polygon.hpp"
#include "geometry/polygon_boolean.hpp"

namespace ashlar {

namespace {

// Fractions of the mesh's bounding-box diagonal. Faces merge when they lie
// within this distance of a common plane: far above rounding, and small
// because a merged polygon that is not planar has a volume that depends on
// how it is triangulated (splitting promises volumes exact to 1e-12).
constexpr double kPlaneTolerance = 1e-9;
// A vertex this close to the straight line through its two neighbours only
// subdivides an edge; a face this narrow across its longest edge is flat.
constexpr double kCollinear = 1e-9;

using DirectedEdge = std::pair<int, int>;
// The input faces (0-based, ascending) a repaired face was made of.
using FaceSources = std::vector<int>;

void check_input(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                 double weld_tolerance, const std::string& what, const MeshNumbering& numbering) {
  if (!std::isfinite(weld_tolerance) || weld_tolerance < 0.0) {
    std::ostringstream message;
    message << what << ": the weld tolerance must be a finite number >= 0 (m), got "
            << weld_tolerance;
    throw InvalidArgument(message.str());
  }
  for (size_t i = 0; i < vertices.size(); ++i) {
    if (!vertices[i].allFinite()) {
      std::ostringstream message;
      message << what << ": ";
      // Names by coordinates already show them.
      if (numbering.vertex_name) {
        message << numbering.vertex(static_cast<int>(i));
      } else {
        message << "vertex " << i + 1 << " is (" << vertices[i].x() << ", " << vertices[i].y() << ", "
                << vertices[i].z() << ")";
      }
      message << ": expected finite coordinates, not NaN or infinity";
      throw GeometryError(message.str());
    }
  }
  const int count = static_cast<int>(vertices.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int index : faces[f]) {
      if (index < 0 || index >= count) {
        throw GeometryError(what + ": " + numbering.face(static_cast<int>(f)) + " refers to vertex " +
                            std::to_string(index + 1) + " but there are " +
                            std::to_string(count) + " vertices");
      }
    }
  }
}

// Maps every vertex to the earliest kept vertex within `tolerance`, or
// keeps it: the first vertex of a cluster represents it, so callers can list
// the points they want kept first. A grid with cells no smaller than the
// tolerance finds the candidates among 27 cells.
std::vector<int> weld(const std::vector<Vec3>& vertices, double tolerance) {
  double largest = 0.0;
  for (const Vec3& p : vertices) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  // Cells bigger than the tolerance stay correct; this floor keeps the cell
  // indices far inside int64 when the tolerance is 0 or tiny.
  const double cell = std::max({tolerance, 1e-15 * largest, std::numeric_limits<double>::min()});
  PointGrid grid(Vec3::Zero(), cell);
  std::vector<int> representative(vertices.size());
  for (size_t i = 0; i < vertices.size(); ++i) {
    const Vec3& p = vertices[i];
    int found = -1;
    grid.for_each_near(p, tolerance, [&](int candidate) {
      if ((found < 0 || candidate < found) && (vertices[candidate] - p).norm() <= tolerance) found = candidate;
    });
    if (found < 0) {
      found = static_cast<int>(i);
      grid.insert(p, found);
    }
    representative[i] = found;
  }
  return representative;
}

std::vector<Vec3> loop_points(const std::vector<Vec3>& points, const FaceLoop& face) {
  std::vector<Vec3> loop;
  loop.reserve(face.size());
  for (int index : face) loop.push_back(points[index]);
  return loop;
}

// Re-indexes the faces through the weld and removes the repeats it created;
// faces left with fewer than 3 vertices were edges or points. `sources`
// gets each kept face's input face.
std::vector<FaceLoop> reindex_faces(const std::vector<FaceLoop>& faces, const std::vector<int>& representative,
                                    std::vector<FaceSources>& sources) {
  std::vector<FaceLoop> result;
  result.reserve(faces.size());
  sources.clear();
  for (size_t f = 0; f < faces.size(); ++f) {
    FaceLoop cleaned;
    for (int index : faces[f]) {
      const int welded = representative[index];
      if (cleaned.empty() || cleaned.back() != welded) cleaned.push_back(welded);
    }
    while (cleaned.size() > 1 && cleaned.front() == cleaned.back()) cleaned.pop_back();
    if (cleaned.size() < 3) continue;
    result.push_back(std::move(cleaned));
    sources.push_back({static_cast<int>(f)});
  }
  return result;
}

// Drops flat faces (all vertices within kCollinear of a line; tiny faces
// are not flat and merge into their plane's polygon later). A flat triangle,
// a sliver whose middle vertex m lies on its longest edge, is glued to its
// neighbour across that edge by inserting m into the neighbour, so the
// surface stays closed.
std::vector<FaceLoop> drop_flat_faces(const std::vector<Vec3>& points, std::vector<FaceLoop> faces,
                                      double size, std::vector<FaceSources>& sources) {
  std::map<DirectedEdge, int> owner;
  for (size_t f = 0; f < faces.size(); ++f) {
    const FaceLoop& face = faces[f];
    for (size_t i = 0; i < face.size(); ++i) {
      owner[{face[i], face[(i + 1) % face.size()]}] = static_cast<int>(f);
    }
  }
  std::vector<bool> flat(faces.size(), false);
  std::vector<size_t> longest_edge(faces.size(), 0);
  for (size_t f = 0; f < faces.size(); ++f) {
    const FaceLoop& face = faces[f];
    double longest = 0.0;
    for (size_t i = 0; i < face.size(); ++i) {
      const double length = (points[face[(i + 1) % face.size()]] - points[face[i]]).norm();
      if (length > longest) {
        longest = length;
        longest_edge[f] = i;
      }
    }
    const double twice_area = newell_normal(loop_points(points, face)).norm();
    flat[f] = twice_area <= kCollinear * size * longest;
  }
  // Slivers back to back (a zero-area face and the fan triangle of its
  // neighbour over the same points) close against each other: neither is
  // glued anywhere.
  const std::map<DirectedEdge, int> first_owner = owner;
  const auto against_flat_face = [&](int from, int to) {
    const auto partner = first_owner.find({to, from});
    return partner != first_owner.end() && flat[partner->second];
  };
  std::vector<bool> dropped(faces.size(), false);
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!flat[f]) continue;
    const FaceLoop& face = faces[f];
    dropped[f] = true;
    for (size_t i = 0; i < face.size(); ++i) {
      const auto edge = owner.find({face[i], face[(i + 1) % face.size()]});
      if (edge != owner.end() && edge->second == static_cast<int>(f)) owner.erase(edge);
    }
    if (face.size() != 3) continue;
    // The longest edge runs next -> prev, and m sits between them.
    const size_t longest_at = longest_edge[f];
    const int next = face[longest_at], prev = face[(longest_at + 1) % 3],
              m = face[(longest_at + 2) % 3];
    if (against_flat_face(prev, m) || against_flat_face(m, next)) continue;
    const auto across = owner.find({prev, next});
    if (across == owner.end()) continue;
    const int g = across->second;
    FaceLoop& neighbour = faces[g];
    if (std::find(neighbour.begin(), neighbour.end(), m) != neighbour.end()) continue;
    const auto at = std::find(neighbour.begin(), neighbour.end(), prev);
    neighbour.insert(at + 1, m);
    owner.erase(across);
    owner[{prev, m}] = g;
    owner[{m, next}] = g;
  }
  std::vector<FaceLoop> kept;
  std::vector<FaceSources> kept_sources;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (dropped[f]) continue;
    kept.push_back(std::move(faces[f]));
    kept_sources.push_back(std::move(sources[f]));
  }
  sources = std::move(kept_sources);
  return kept;
}

// The single boundary loop of a patch of faces, or nothing when the boundary
// is several loops (a hole) or pinched at a vertex.
std::optional<FaceLoop> patch_outline(const std::vector<FaceLoop>& faces,
                                      const std::vector<int>& members) {
  std::map<DirectedEdge, int> boundary;  // an edge cancels against its reverse
  for (int f : members) {
    const FaceLoop& face = faces[f];
    for (size_t i = 0; i < face.size(); ++i) {
      const int from = face[i], to = face[(i + 1) % face.size()];
      const auto reverse = boundary.find({to, from});
      if (reverse != boundary.end()) {
        if (--reverse->second == 0) boundary.erase(reverse);
      } else {
        ++boundary[{from, to}];
      }
    }
  }
  std::unordered_map<int, int> successor;
  for (const auto& [edge, count] : boundary) {
    if (count != 1 || !successor.emplace(edge.first, edge.second).second) return std::nullopt;
  }
  if (boundary.size() < 3) return std::nullopt;
  FaceLoop outline;
  const int start = boundary.begin()->first.first;
  int at = start;
  do {
    outline.push_back(at);
    const auto step = successor.find(at);
    if (step == successor.end() || outline.size() > boundary.size()) return std::nullopt;
    at = step->second;
  } while (at != start);
  if (outline.size() != boundary.size()) return std::nullopt;
  return outline;
}

// Grows each patch from its largest face across edges shared by exactly two
// faces, taking faces whose vertices all lie within `plane_tolerance` of the
// seed's plane. Distance, not the angle between normals, decides: normals of
// the slivers a clip leaves behind are too noisy to compare.
std::vector<FaceLoop> merge_coplanar_faces(const std::vector<Vec3>& points,
                                           const std::vector<FaceLoop>& faces,
                                           double plane_tolerance, std::vector<FaceSources>& sources) {
  std::map<DirectedEdge, std::vector<int>> users;  // undirected edge -> faces
  for (size_t f = 0; f < faces.size(); ++f) {
    const FaceLoop& face = faces[f];
    for (size_t i = 0; i < face.size(); ++i) {
      const int a = face[i], b = face[(i + 1) % face.size()];
      users[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  }
  std::vector<std::vector<int>> neighbours(faces.size());
  for (const auto& [edge, list] : users) {
    if (list.size() == 2 && list[0] != list[1]) {
      neighbours[list[0]].push_back(list[1]);
      neighbours[list[1]].push_back(list[0]);
    }
  }
  std::vector<Vec3> normals(faces.size());
  std::vector<double> areas(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    const Vec3 n = newell_normal(loop_points(points, faces[f]));
    areas[f] = n.norm();
    normals[f] = n.normalized();
  }
  std::vector<int> order(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) order[f] = static_cast<int>(f);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return areas[a] > areas[b]; });

  std::vector<bool> taken(faces.size(), false);
  std::vector<FaceLoop> merged;
  std::vector<FaceSources> merged_sources;
  for (int seed : order) {
    if (taken[seed]) continue;
    taken[seed] = true;
    const Vec3& normal = normals[seed];
    const double offset = normal.dot(points[faces[seed][0]]);
    const auto in_plane = [&](int f) {
      if (normals[f].dot(normal) <= 0.0) return false;
      for (int index : faces[f]) {
        if (std::abs(normal.dot(points[index]) - offset) > plane_tolerance) return false;
      }
      return true;
    };
    std::vector<int> members{seed};
    std::queue<int> frontier;
    frontier.push(seed);
    while (!frontier.empty()) {
      const int f = frontier.front();
      frontier.pop();
      for (int g : neighbours[f]) {
        if (taken[g] || !in_plane(g)) continue;
        taken[g] = true;
        members.push_back(g);
        frontier.push(g);
      }
    }
    const std::optional<FaceLoop> outline =
        members.size() > 1 ? patch_outline(faces, members) : std::nullopt;
    if (outline) {
      merged.push_back(*outline);
      FaceSources patch;
      for (int f : members) patch.insert(patch.end(), sources[f].begin(), sources[f].end());
      std::sort(patch.begin(), patch.end());
      merged_sources.push_back(std::move(patch));
    } else {
      for (int f : members) {
        merged.push_back(faces[f]);
        merged_sources.push_back(sources[f]);
      }
    }
  }
  sources = std::move(merged_sources);
  return merged;
}

// With a planarity allowance, a warped quad that a mesh file holds as two
// triangles is one face again: triangles across an edge that only they
// share, whose quad lies within `planarity` of its size off its best-fit
// plane and is convex there, pair up, the flattest quads first. The quad
// starts at an end of the shared edge, so the fan that bounds a block's
// solid (see Block) is the two triangles and the volume does not change.
std::vector<FaceLoop> merge_warped_triangle_pairs(const std::vector<Vec3>& points,
                                                  std::vector<FaceLoop> faces, double planarity,
                                                  std::vector<FaceSources>& sources) {
  std::map<DirectedEdge, std::vector<int>> users;  // undirected edge -> triangles
  for (size_t f = 0; f < faces.size(); ++f) {
    if (faces[f].size() != 3) continue;
    for (size_t i = 0; i < 3; ++i) {
      const int a = faces[f][i], b = faces[f][(i + 1) % 3];
      users[{std::min(a, b), std::max(a, b)}].push_back(static_cast<int>(f));
    }
  }
  struct Candidate {
    double warp;  // relative to the quad's size
    int first, second;
    FaceLoop quad;
  };
  std::vector<Candidate> candidates;
  for (const auto& [edge, list] : users) {
    if (list.size() != 2 || list[0] == list[1]) continue;
    // first runs x -> y -> p, second y -> x -> q: the quad is x q y p.
    const FaceLoop& first = faces[list[0]];
    const FaceLoop& second = faces[list[1]];
    size_t at = 0;
    while (!(first[at] == edge.first || first[at] == edge.second) ||
           !(first[(at + 1) % 3] == edge.first || first[(at + 1) % 3] == edge.second)) {
      ++at;
    }
    const int x = first[at], y = first[(at + 1) % 3], p = first[(at + 2) % 3];
    int q = -1;
    for (int index : second) {
      if (index != x && index != y) q = index;
    }
    if (q < 0 || q == p) continue;
    const FaceLoop quad{x, q, y, p};
    const std::vector<FacePlane> plane = face_planes(points, {quad});
    std::vector<Vec3> corners;
    Box3 box;
    for (int index : quad) {
      corners.push_back(points[index]);
      box.add(points[index]);
    }
    const double warp = largest_warp(points, {quad}, plane) / box.diagonal();
    if (!(warp <= planarity)) continue;
    const PlaneFrame frame = PlaneFrame::from_normal(corners[0], plane[0].normal);
    Loop2 flat;
    for (const Vec3& corner : corners) flat.push_back(frame.project(corner));
    if (!is_convex(flat) || signed_area(flat) <= 0.0) continue;
    candidates.push_back({warp, list[0], list[1], quad});
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& x, const Candidate& y) { return x.warp < y.warp; });
  // The quad takes the place of the earlier of its triangles, so faces keep
  // their order (and the numbers messages give them).
  std::vector<bool> taken(faces.size(), false);
  std::vector<bool> dropped(faces.size(), false);
  for (const Candidate& candidate : candidates) {
    if (taken[candidate.first] || taken[candidate.second]) continue;
    taken[candidate.first] = taken[candidate.second] = true;
    const auto [earlier, later] = std::minmax(candidate.first, candidate.second);
    faces[earlier] = candidate.quad;
    sources[earlier].insert(sources[earlier].end(), sources[later].begin(), sources[later].end());
    std::sort(sources[earlier].begin(), sources[earlier].end());
    dropped[later] = true;
  }
  std::vector<FaceLoop> merged;
  std::vector<FaceSources> merged_sources;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (dropped[f]) continue;
    merged.push_back(std::move(faces[f]));
    merged_sources.push_back(std::move(sources[f]));
  }
  sources = std::move(merged_sources);
  return merged;
}

// Removes vertices that only subdivide a straight edge between two faces
// (clip points on the diagonals of triangulated faces, midpoints in mesh
// files). The triangle each removal cuts off one face it adds to the other,
// so the volume does not change.
void remove_edge_midpoints(const std::vector<Vec3>& points, std::vector<FaceLoop>& faces,
                           double tolerance) {
  std::vector<std::vector<int>> users(points.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    for (int index : faces[f]) users[index].push_back(static_cast<int>(f));
  }
  const auto neighbours_in = [](const FaceLoop& face, int v) {
    const size_t at = std::find(face.begin(), face.end(), v) - face.begin();
    return std::make_pair(face[(at + face.size() - 1) % face.size()],
                          face[(at + 1) % face.size()]);
  };
  for (size_t v = 0; v < points.size(); ++v) {
    if (users[v].size() != 2 || users[v][0] == users[v][1]) continue;
    FaceLoop& first = faces[users[v][0]];
    FaceLoop& second = faces[users[v][1]];
    if (first.size() <= 3 || second.size() <= 3) continue;
    const int vertex = static_cast<int>(v);
    const auto [u, w] = neighbours_in(first, vertex);
    if (neighbours_in(second, vertex) != std::make_pair(w, u)) continue;
    const Vec3 along = points[w] - points[u];
    const Vec3 offset = points[v] - points[u];
    if (along.dot(offset) <= 0.0 || along.dot(points[w] - points[v]) <= 0.0) continue;
    if (along.cross(offset).norm() > tolerance * along.norm()) continue;
    first.erase(std::find(first.begin(), first.end(), vertex));
    second.erase(std::find(second.begin(), second.end(), vertex));
  }
}

// Keeps the vertices that faces use, in their original order; returns the
// old index of each kept vertex.
std::vector<int> drop_unused_vertices(std::vector<Vec3>& points, std::vector<FaceLoop>& faces) {
  std::vector<int> new_index(points.size(), -1);
  for (const FaceLoop& face : faces) {
    for (int index : face) new_index[index] = 0;
  }
  std::vector<Vec3> used;
  std::vector<int> old_index;
  for (size_t i = 0; i < points.size(); ++i) {
    if (new_index[i] < 0) continue;
    new_index[i] = static_cast<int>(used.size());
    used.push_back(points[i]);
    old_index.push_back(static_cast<int>(i));
  }
  for (FaceLoop& face : faces) {
    for (int& index : face) index = new_index[index];
  }
  points = std::move(used);
  return old_index;
}

// The mesh welded, without what welding made degenerate, coplanar faces
// merged (and, with a planarity, warped triangle pairs), edge midpoints and
// unused vertices dropped; with where each point and loop came from.
struct RepairedMesh {
  std::vector<Vec3> points;
  std::vector<FaceLoop> loops;
  std::vector<int> source_vertex;            // per point, the input vertex it is (the first of its weld)
  std::vector<FaceSources> source_faces;     // per loop, the input faces merged into it
};

RepairedMesh repair_mesh(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                         double weld_tolerance, double planarity) {
  Box3 box;
  for (const Vec3& p : vertices) box.add(p);
  const double size = box.diagonal();
  RepairedMesh mesh;
  mesh.points = vertices;
  mesh.loops = reindex_faces(faces, weld(vertices, weld_tolerance), mesh.source_faces);
  mesh.loops = drop_flat_faces(mesh.points, std::move(mesh.loops), size, mesh.source_faces);
  mesh.loops = merge_coplanar_faces(mesh.points, mesh.loops, kPlaneTolerance * size, mesh.source_faces);
  if (planarity > 0.0) {
    mesh.loops = merge_warped_triangle_pairs(mesh.points, std::move(mesh.loops), planarity, mesh.source_faces);
  }
  remove_edge_midpoints(mesh.points, mesh.loops, kCollinear * size);
  mesh.source_vertex = drop_unused_vertices(mesh.points, mesh.loops);
  return mesh;
}

}  // namespace

Block block_from_mesh(const std::vector<Vec3>& vertices, const std::vector<FaceLoop>& faces,
                      double weld_tolerance, const BlockStyle& style, const std::string& what,
                      const MeshNumbering& input_numbering) {
  check_input(vertices, faces, weld_tolerance, what, input_numbering);
  RepairedMesh mesh = repair_mesh(vertices, faces, weld_tolerance, style.planarity);
  // Defects are found in the repaired mesh and named as the input numbers
  // its vertices and faces; a merged face by the input faces it was made of.
  MeshNumbering numbering;
  numbering.vertex_name = [&](int index) { return input_numbering.vertex(mesh.source_vertex[index]); };
  numbering.face_name = [&](int index) {
    const FaceSources& sources = mesh.source_faces[index];
    std::string name = input_numbering.face(sources[0]);
    if (sources.size() == 1) return name;
    name += " (merged with";
    for (size_t k = 1; k < sources.size(); ++k) name += (k == 1 ? " " : ", ") + input_numbering.face(sources[k]);
    return name + ")";
  };
  std::ostringstream repair;
  if (mesh.points.size() != vertices.size() || mesh.loops.size() != faces.size()) {
    repair << "; welding vertices closer than " << weld_tolerance
           << " m, dropping flat faces and merging coplanar ones made the mesh's "
           << faces.size() << " faces and " << vertices.size() << " vertices into "
           << mesh.loops.size() << " faces and " << mesh.points.size() << " vertices";
  }
  try {
    return Block(std::move(mesh.points), std::move(mesh.loops), style.density, style.name, style.planarity,
                 numbering);
  } catch (const GeometryError& error) {
    throw GeometryError(what + ": " + error.what() + repair.str());
  }
}

std::optional<std::vector<Vec3>> open_planar_outline(const std::vector<Vec3>& vertices,
                                                     const std::vector<FaceLoop>& faces,
                                                     double weld_tolerance, double planarity) {
  try {
    check_input(vertices, faces, weld_tolerance, "open surface", {});
  } catch (const Error&) {
    return std::nullopt;  // block_from_mesh names the defect
  }
  const RepairedMesh mesh = repair_mesh(vertices, faces, weld_tolerance, planarity);
  const std::vector<Vec3>& points = mesh.points;
  const std::vector<FaceLoop>& loops = mesh.loops;
  if (loops.size() != 1 || loops[0].size() < 3) return std::nullopt;
  std::vector<Vec3> outline;
  for (int index : loops[0]) outline.push_back(points[index]);
  const Vec3 normal = newell_normal(outline);
  if (!(normal.norm() > 0.0)) return std::nullopt;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : outline) centre += p;
  centre /= static_cast<double>(outline.size());
  const PlaneFrame frame = PlaneFrame::from_normal(centre, normal.normalized());
  Box3 extent;
  for (const Vec3& p : outline) extent.add(p);
  const double allowed = std::max(planarity, 1e-6) * extent.diagonal();
  Loop2 flat;
  for (const Vec3& p : outline) {
    if (std::abs(frame.distance(p)) > allowed) return std::nullopt;
    flat.push_back(frame.project(p));
  }
  if (!is_simple_loop(flat)) return std::nullopt;
  for (size_t i = 0; i < outline.size(); ++i) outline[i] = frame.lift(flat[i]);
  return outline;
}

}  // namespace ashlar
