#include "structure/interface_gradient.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "core/error.hpp"
#include "core/point_grid.hpp"
#include "geometry/polygon.hpp"

namespace ashlar {

namespace {

// Points nearer than this fraction of the contact polygon's size are one point,
// as contact detection's loop simplification treats them.
constexpr double kSamePoint = 1e-9;
// Rounding of detection's projection into the plane and back, relative to the
// coordinates: far from the origin it outgrows kSamePoint.
constexpr double kRounding = 1e-12;

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

std::vector<Vec3> face_loop(const Block& block, int face) {
  std::vector<Vec3> loop;
  for (int index : block.faces()[face]) loop.push_back(block.vertices()[index]);
  return loop;
}

Box3 bounds_of(const std::vector<Vec3>& points) {
  Box3 box;
  for (const Vec3& p : points) box.add(p);
  return box;
}

// Whether contact detection intersects face f of block a with face g of block b.
bool faces_touch(const Block& a, int f, const Block& b, int g, double tol, double opposite) {
  const std::vector<Vec3> loop_a = face_loop(a, f), loop_b = face_loop(b, g);
  return boxes_overlap(bounds_of(loop_a), bounds_of(loop_b), tol) &&
         faces_may_touch(loop_a, a.face_planes()[f], loop_b, b.face_planes()[g], tol, opposite);
}

// The faces of blocks a and b that contact detection intersected on one plane.
struct ContactFaces {
  int plane_face = -1;  // the face of a whose plane the interface lies in ("face A")
  std::vector<int> faces_a, faces_b;
};

// Detection's faces: those of a on face A's plane and those of b facing
// them that touch one of them.
ContactFaces find_contact_faces(const Block& a, const Block& b, const Interface& contact,
                                double tol, double opposite) {
  ContactFaces faces;
  if (contact.face_a < 0 || contact.face_a >= static_cast<int>(a.faces().size())) return faces;
  const FacePlane& plane_a = a.face_planes()[contact.face_a];
  std::vector<int> on_plane_a, facing_b;
  for (size_t f = 0; f < a.faces().size(); ++f) {
    if (on_same_plane(plane_a.normal, plane_a.offset, a.face_planes()[f], tol)) {
      on_plane_a.push_back(static_cast<int>(f));
    }
  }
  for (size_t g = 0; g < b.faces().size(); ++g) {
    if (b.face_planes()[g].normal.dot(plane_a.normal) <= opposite) {
      facing_b.push_back(static_cast<int>(g));
    }
  }
  std::vector<bool> touched_b(facing_b.size(), false);
  for (int f : on_plane_a) {
    bool touched = false;
    for (size_t j = 0; j < facing_b.size(); ++j) {
      if (faces_touch(a, f, b, facing_b[j], tol, opposite)) touched = touched_b[j] = true;
    }
    if (touched) faces.faces_a.push_back(f);
  }
  for (size_t j = 0; j < facing_b.size(); ++j) {
    if (touched_b[j]) faces.faces_b.push_back(facing_b[j]);
  }
  if (!faces.faces_a.empty() && !faces.faces_b.empty()) faces.plane_face = contact.face_a;
  return faces;
}

// A vertex or an edge of a face in contact, in 2D coordinates of the contact plane.
struct Feature {
  bool of_a = false;  // a face of block a, else of block b
  bool edge = false;
  int from = -1, to = -1;  // vertex indices in the feature's block; to == from for a vertex
  Vec2 p0, p1;
};

double distance_to_segment(const Vec2& x, const Vec2& p0, const Vec2& p1) {
  const Vec2 e = p1 - p0;
  const double length2 = e.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((x - p0).dot(e) / length2, 0.0, 1.0) : 0.0;
  return (p0 + t * e - x).norm();
}

std::vector<Feature> contact_features(const Block& a, const Block& b, const ContactFaces& faces,
                                      const PlaneFrame& frame) {
  std::vector<Feature> features;
  const auto add_faces = [&](const Block& block, const std::vector<int>& face_list, bool of_a) {
    for (int f : face_list) {
      const FaceLoop& loop = block.faces()[f];
      for (size_t i = 0; i < loop.size(); ++i) {
        const int from = loop[i], to = loop[(i + 1) % loop.size()];
        const Vec2 p0 = frame.project(block.vertices()[from]);
        const Vec2 p1 = frame.project(block.vertices()[to]);
        features.push_back({of_a, false, from, from, p0, p0});
        features.push_back({of_a, true, from, to, p0, p1});
      }
    }
  };
  add_faces(a, faces.faces_a, true);
  add_faces(b, faces.faces_b, false);
  return features;
}

// Cells about as long as the mean edge: few features per cell, few cells per edge.
double grid_cell(const std::vector<Feature>& features, double match) {
  double length = 0.0;
  int edges = 0;
  for (const Feature& feature : features) {
    if (!feature.edge) continue;
    length += (feature.p1 - feature.p0).norm();
    ++edges;
  }
  return std::max(length / std::max(edges, 1), match);
}

// Where one contact vertex comes from (see the header's types 1 to 3).
struct Provenance {
  enum class Kind { vertex_of_a, vertex_of_b, crossing };
  Kind kind = Kind::vertex_of_a;
  int a0 = -1, a1 = -1;  // vertex of a, or the edge a0 a1 of a crossing
  int b0 = -1, b1 = -1;  // vertex of b, or the edge b0 b1 of a crossing
};

// The vertices and edges of the faces in contact, and a grid to find them by position.
class ContactFeatures {
public:
  ContactFeatures(std::vector<Feature> features, double match)
      : match_(match), features_(std::move(features)), cell_(grid_cell(features_, match)), grid_(Vec3::Zero(), cell_) {
    // Each feature goes into the cells it comes within `match` of, in
    // pieces no longer than a cell, so that a long diagonal edge costs its
    // length, not its bounding box; a contact vertex then meets only the
    // features of its own cell.
    for (size_t i = 0; i < features_.size(); ++i) {
      const Vec2 p0 = features_[i].p0, p1 = features_[i].p1;
      const int pieces = std::max(1, static_cast<int>(std::ceil((p1 - p0).norm() / cell_)));
      for (int k = 0; k < pieces; ++k) {
        const Vec2 s0 = p0 + (p1 - p0) * (static_cast<double>(k) / pieces);
        const Vec2 s1 = p0 + (p1 - p0) * (static_cast<double>(k + 1) / pieces);
        const Vec2 lo = s0.cwiseMin(s1).array() - match, hi = s0.cwiseMax(s1).array() + match;
        grid_.insert_box(Vec3(lo.x(), lo.y(), 0.0), Vec3(hi.x(), hi.y(), 0.0), static_cast<int>(i));
      }
    }
  }

  // Types in order of precedence: a vertex of a, a vertex of b, a crossing.
  std::optional<Provenance> find(const Vec2& x) const {
    const Feature* nearest_vertex[2] = {nullptr, nullptr};  // of a, of b
    double nearest_distance[2] = {match_, match_};
    std::vector<const Feature*> edges_a, edges_b;
    const Vec3 at(x.x(), x.y(), 0.0);
    grid_.for_each_in(at, at, [&](int i) {
      const Feature& feature = features_[i];
      if (feature.edge) {
        if (distance_to_segment(x, feature.p0, feature.p1) <= match_) {
          (feature.of_a ? edges_a : edges_b).push_back(&feature);
        }
        return;
      }
      const int side = feature.of_a ? 0 : 1;
      const double distance = (feature.p0 - x).norm();
      if (distance <= nearest_distance[side]) {
        nearest_distance[side] = distance;
        nearest_vertex[side] = &feature;
      }
    });
    Provenance found;
    if (nearest_vertex[0]) {
      found.kind = Provenance::Kind::vertex_of_a;
      found.a0 = nearest_vertex[0]->from;
      return found;
    }
    if (nearest_vertex[1]) {
      found.kind = Provenance::Kind::vertex_of_b;
      found.b0 = nearest_vertex[1]->from;
      return found;
    }
    double best = match_;
    const Feature *best_a = nullptr, *best_b = nullptr;
    for (const Feature* edge_a : edges_a) {
      for (const Feature* edge_b : edges_b) {
        const Vec2 e = edge_a->p1 - edge_a->p0, h = edge_b->p1 - edge_b->p0;
        const double den = cross2(h, e);
        if (den == 0.0) continue;
        const double s = cross2(h, edge_b->p0 - edge_a->p0) / den;
        const double distance = (edge_a->p0 + s * e - x).norm();
        if (distance <= best) {
          best = distance;
          best_a = edge_a;
          best_b = edge_b;
        }
      }
    }
    if (!best_a) return std::nullopt;
    found.kind = Provenance::Kind::crossing;
    found.a0 = best_a->from;
    found.a1 = best_a->to;
    found.b0 = best_b->from;
    found.b1 = best_b->to;
    return found;
  }

private:
  double match_;
  std::vector<Feature> features_;
  double cell_;
  PointGrid grid_;  // in the plane's coordinates (z = 0)
};

// Face A's plane as the projection uses it: unit normal n and centre c.
struct ContactPlane {
  Vec3 normal, centre;
};

// dP/dn and dP/dc, gathered over the whole interface before they flow back to
// face A's vertices in one pass.
struct PlaneAdjoint {
  Vec3 normal = Vec3::Zero(), centre = Vec3::Zero();
};

// Reverse of x = y - n n.(y - c): returns dP/dy and adds to dP/dn and dP/dc.
Vec3 projection_back(const ContactPlane& plane, const Vec3& y, const Vec3& d_x,
                     PlaneAdjoint& d_plane) {
  const Vec3& n = plane.normal;
  const Vec3 from_centre = y - plane.centre;
  const double d_x_along_n = n.dot(d_x);
  d_plane.normal -= n.dot(from_centre) * d_x + d_x_along_n * from_centre;
  d_plane.centre += d_x_along_n * n;
  return d_x - d_x_along_n * n;
}

// Reverse of x = proj(p0 + s (p1 - p0)), s = w.(q0 - p0) / w.(p1 - p0), w = (q1 - q0) x n.
void crossing_back(const ContactPlane& plane, const Vec3& p0, const Vec3& p1, const Vec3& q0,
                   const Vec3& q1, const Vec3& d_x, Vec3& d_p0, Vec3& d_p1, Vec3& d_q0,
                   Vec3& d_q1, PlaneAdjoint& d_plane) {
  const Vec3 e = p1 - p0, h = q1 - q0;
  const Vec3 w = h.cross(plane.normal);
  const double den = w.dot(e);
  const double s = w.dot(q0 - p0) / den;
  const Vec3 d_y = projection_back(plane, p0 + s * e, d_x, d_plane);
  const double d_s = d_y.dot(e);
  const double d_num = d_s / den, d_den = -d_s * s / den;
  const Vec3 d_w = d_num * (q0 - p0) + d_den * e;
  const Vec3 d_h = plane.normal.cross(d_w);
  d_p0 += (1.0 - s) * d_y - (d_num + d_den) * w;
  d_p1 += s * d_y + d_den * w;
  d_q0 += d_num * w - d_h;
  d_q1 += d_h;
  d_plane.normal += d_w.cross(h);
}

// Adds the frame's adjoints (n, u on the longest edge, v = n x u) to the
// vertices' and the plane normal's.
void frame_back(const Interface& contact, const InterfaceAdjoint& adjoint,
                std::vector<Vec3>& d_vertices, PlaneAdjoint& d_plane) {
  const size_t count = contact.vertices.size();
  size_t longest = 0;
  double longest_length = -1.0;
  for (size_t i = 0; i < count; ++i) {
    const double length = (contact.vertices[(i + 1) % count] - contact.vertices[i]).norm();
    if (length > longest_length) {
      longest_length = length;
      longest = i;
    }
  }
  const Vec3& u = contact.u;
  const Vec3 d_u = adjoint.u + adjoint.v.cross(contact.normal);
  const Vec3 d_edge = (d_u - u * u.dot(d_u)) / longest_length;
  d_vertices[(longest + 1) % count] += d_edge;
  d_vertices[longest] -= d_edge;
  // The interface normal is face A's unit normal normalised again, whose
  // derivative (the tangent projection) plane_back applies.
  d_plane.normal += adjoint.normal + u.cross(adjoint.v);
}

// Reverse of n = N / |N| (N the Newell normal of the loop `points`) and c =
// the mean of the points: adds dP/d(point i) to d_points[i].
void plane_back(const std::vector<Vec3>& points, const ContactPlane& plane, const PlaneAdjoint& d_plane,
                std::vector<Vec3>& d_points) {
  const Vec3& n = plane.normal;
  const Vec3 d_newell =
      (d_plane.normal - n * n.dot(d_plane.normal)) / newell_normal(points).norm();
  const size_t count = points.size();
  const Vec3 d_centre = d_plane.centre / static_cast<double>(count);
  for (size_t i = 0; i < count; ++i) {
    // N = sum_i q_i x q_(i+1), so dN/dq_i applied backwards is (q_(i+1) - q_(i-1)) x dP/dN.
    const Vec3 across = points[(i + 1) % count] - points[(i + count - 1) % count];
    d_points[i] += d_centre + across.cross(d_newell);
  }
}

// A face's plane as the projection uses it: its unit Newell normal and the mean of its vertices.
ContactPlane face_plane(const Block& block, int face) {
  ContactPlane plane{block.face_planes()[face].normal, Vec3::Zero()};
  for (int index : block.faces()[face]) plane.centre += block.vertices()[index];
  plane.centre /= static_cast<double>(block.faces()[face].size());
  return plane;
}

// plane_back for a face of a block, added to the block's vertex gradient.
void add_face_plane_back(const Block& block, int face, const ContactPlane& plane, const PlaneAdjoint& d_plane,
                         std::vector<Vec3>& gradient) {
  const FaceLoop& loop = block.faces()[face];
  std::vector<Vec3> d_points(loop.size(), Vec3::Zero());
  plane_back(face_loop(block, face), plane, d_plane, d_points);
  for (size_t i = 0; i < loop.size(); ++i) gradient[loop[i]] += d_points[i];
}

bool all_zero(const InterfaceAdjoint& adjoint) {
  for (const Vec3& d : adjoint.vertices) {
    if (!d.isZero(0.0)) return false;
  }
  return adjoint.normal.isZero(0.0) && adjoint.u.isZero(0.0) && adjoint.v.isZero(0.0);
}

std::string describe_pair(const Structure& structure, const Interface& contact) {
  return "blocks " + std::to_string(contact.a + 1) + " ('" + structure.name(contact.a) +
         "') and " + std::to_string(contact.b + 1) + " ('" + structure.name(contact.b) + "')";
}

void accumulate_one(const Structure& structure, const Interface& contact,
                    const InterfaceAdjoint& adjoint, double tol, double opposite,
                    std::vector<std::vector<Vec3>>& gradient) {
  const Block& a = structure.block(contact.a);
  const Block& b = structure.block(contact.b);
  const ContactFaces faces = find_contact_faces(a, b, contact, tol, opposite);
  if (faces.plane_face < 0) {
    throw InvalidArgument("interface gradient: no faces of " + describe_pair(structure, contact) +
                          " meet on the plane of their interface");
  }
  const ContactPlane plane = face_plane(a, faces.plane_face);

  const Box3 extent = bounds_of(contact.vertices);
  double magnitude = 0.0;
  for (const Vec3& x : contact.vertices) magnitude = std::max(magnitude, x.cwiseAbs().maxCoeff());
  const double match = kSamePoint * extent.diagonal() + kRounding * magnitude;
  const PlaneFrame frame = PlaneFrame::from_normal(plane.centre, plane.normal);
  const ContactFeatures features(contact_features(a, b, faces, frame), match);

  std::vector<Vec3> d_vertices = adjoint.vertices;
  d_vertices.resize(contact.vertices.size(), Vec3::Zero());
  PlaneAdjoint d_plane;
  frame_back(contact, adjoint, d_vertices, d_plane);

  std::vector<Vec3>& gradient_a = gradient[contact.a];
  std::vector<Vec3>& gradient_b = gradient[contact.b];
  for (size_t k = 0; k < contact.vertices.size(); ++k) {
    const std::optional<Provenance> source = features.find(frame.project(contact.vertices[k]));
    if (!source) {
      throw InvalidArgument("interface gradient: contact vertex " + std::to_string(k + 1) +
                            " of the interface between " + describe_pair(structure, contact) +
                            " is neither a vertex of their faces nor a crossing of their edges");
    }
    switch (source->kind) {
      case Provenance::Kind::vertex_of_a:
        gradient_a[source->a0] +=
            projection_back(plane, a.vertices()[source->a0], d_vertices[k], d_plane);
        break;
      case Provenance::Kind::vertex_of_b:
        gradient_b[source->b0] +=
            projection_back(plane, b.vertices()[source->b0], d_vertices[k], d_plane);
        break;
      case Provenance::Kind::crossing:
        crossing_back(plane, a.vertices()[source->a0], a.vertices()[source->a1],
                      b.vertices()[source->b0], b.vertices()[source->b1], d_vertices[k],
                      gradient_a[source->a0], gradient_a[source->a1], gradient_b[source->b0],
                      gradient_b[source->b1], d_plane);
        break;
    }
  }
  add_face_plane_back(a, faces.plane_face, plane, d_plane, gradient_a);
}

// A mid-plane interface (Interface::on_mid_plane): contact vertex k is
// proj(m_k), m_k = (p_k + q_pairing(k)) / 2 the midpoint of vertex k of face
// A and its pair on face B, projected onto the plane through the midpoints'
// mean with their unit Newell normal; u and v as for any interface.
void accumulate_mid_plane(const Structure& structure, const Interface& contact, const InterfaceAdjoint& adjoint,
                          double tol, std::vector<std::vector<Vec3>>& gradient) {
  const Block& a = structure.block(contact.a);
  const Block& b = structure.block(contact.b);
  const bool faces_exist = contact.face_a >= 0 && contact.face_a < static_cast<int>(a.faces().size()) &&
                           contact.face_b >= 0 && contact.face_b < static_cast<int>(b.faces().size());
  const std::vector<Vec3> copy_a = faces_exist ? face_loop(a, contact.face_a) : std::vector<Vec3>{};
  const std::vector<Vec3> copy_b = faces_exist ? face_loop(b, contact.face_b) : std::vector<Vec3>{};
  const std::optional<std::vector<int>> pairing = mid_plane_pairing(copy_a, copy_b, tol);
  if (!pairing) {
    throw InvalidArgument("interface gradient: no faces of " + describe_pair(structure, contact) +
                          " are the two copies of their mid-plane joint");
  }
  const std::vector<Vec3> midpoints = paired_midpoints(copy_a, copy_b, *pairing);
  ContactPlane plane{contact.normal, Vec3::Zero()};
  for (const Vec3& m : midpoints) plane.centre += m;
  plane.centre /= static_cast<double>(midpoints.size());

  std::vector<Vec3> d_vertices = adjoint.vertices;
  d_vertices.resize(contact.vertices.size(), Vec3::Zero());
  PlaneAdjoint d_plane;
  frame_back(contact, adjoint, d_vertices, d_plane);
  std::vector<Vec3> d_midpoints(midpoints.size(), Vec3::Zero());
  for (size_t k = 0; k < midpoints.size(); ++k) {
    d_midpoints[k] = projection_back(plane, midpoints[k], d_vertices[k], d_plane);
  }
  plane_back(midpoints, plane, d_plane, d_midpoints);
  const FaceLoop& loop_a = a.faces()[contact.face_a];
  const FaceLoop& loop_b = b.faces()[contact.face_b];
  for (size_t k = 0; k < midpoints.size(); ++k) {
    gradient[contact.a][loop_a[k]] += 0.5 * d_midpoints[k];
    gradient[contact.b][loop_b[(*pairing)[k]]] += 0.5 * d_midpoints[k];
  }
}

}  // namespace

void accumulate_interface_gradient(const Structure& structure, const ContactOptions& options,
                                   const std::vector<InterfaceAdjoint>& adjoints,
                                   std::vector<std::vector<Vec3>>& gradient) {
  const std::shared_ptr<const std::vector<Interface>> interfaces_list = structure.interfaces(options);
  const std::vector<Interface>& interfaces = *interfaces_list;
  if (adjoints.size() != interfaces.size()) {
    throw InvalidArgument("interface gradient: " + std::to_string(adjoints.size()) +
                          " adjoints for " + std::to_string(interfaces.size()) +
                          " interfaces (one per interface needed)");
  }
  if (gradient.size() != static_cast<size_t>(structure.size())) {
    throw InvalidArgument("interface gradient: gradient has " + std::to_string(gradient.size()) +
                          " blocks, the structure " + std::to_string(structure.size()));
  }
  std::vector<const Block*> blocks;
  for (int i = 0; i < structure.size(); ++i) {
    blocks.push_back(&structure.block(i));
    if (gradient[i].size() != structure.block(i).vertices().size()) {
      throw InvalidArgument("interface gradient: gradient of block " + std::to_string(i + 1) +
                            " has " + std::to_string(gradient[i].size()) +
                            " vertices, the block " +
                            std::to_string(structure.block(i).vertices().size()));
    }
  }
  for (size_t k = 0; k < interfaces.size(); ++k) {
    const size_t given = adjoints[k].vertices.size();
    if (given != 0 && given != interfaces[k].vertices.size()) {
      throw InvalidArgument("interface gradient: adjoint " + std::to_string(k + 1) + " has " +
                            std::to_string(given) + " vertices, its interface " +
                            std::to_string(interfaces[k].vertices.size()));
    }
  }
  const double tol = effective_tolerance(blocks, options);
  for (size_t k = 0; k < interfaces.size(); ++k) {
    if (all_zero(adjoints[k])) continue;
    if (interfaces[k].on_mid_plane) {
      accumulate_mid_plane(structure, interfaces[k], adjoints[k], tol, gradient);
    } else {
      accumulate_one(structure, interfaces[k], adjoints[k], tol, opposite_cosine(options), gradient);
    }
  }
}

}  // namespace ashlar
