#include "dynamics/contact_points.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <tuple>
#include <utility>

#include "structure/contact_detection.hpp"

namespace ashlar {
namespace {

// The contact point of world point p on block a against face f of block b
// (world plane `plane`), in reference coordinates.
ContactPoint make_point(int a, int b, int face, const Vec3& p, const FacePlane& plane,
                        const std::vector<RigidPose>& poses) {
  ContactPoint contact;
  contact.a = a;
  contact.b = b;
  contact.face = face;
  contact.point = poses[a].rotation.conjugate() * (p - poses[a].position);
  contact.normal = poses[b].rotation.conjugate() * plane.normal;
  contact.offset = plane.offset - plane.normal.dot(poses[b].position);
  return contact;
}

// The face of `block` (world) an interface polygon with normal n (pointing
// into the block) was cut from: among faces turned against n within the
// contact angle, the one whose plane passes nearest the polygon's centre.
int facing_face(const Block& block, const Vec3& n, const Vec3& center, double opposite) {
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  const std::vector<FacePlane>& planes = block.face_planes();
  for (size_t f = 0; f < planes.size(); ++f) {
    if (planes[f].normal.dot(n) > opposite) continue;
    const double distance = std::abs(planes[f].normal.dot(center) - planes[f].offset);
    if (distance < best_distance) {
      best_distance = distance;
      best = static_cast<int>(f);
    }
  }
  return best;
}

// The cosine between two faces' outward normals below which the faces are
// the two sides of a hinge (turned against each other, apart by at most
// 30 degrees): see add_vertex_contacts.
constexpr double kHingeCosine = -0.866;
// A vertex within this fraction of the search distance of a face's plane,
// inside it, is on that face's edge: see add_vertex_contacts.
constexpr double kOnPlane = 0.01;

// Vertices of convex block `from` within `distance` of convex block `to`
// (both world), each against a face of `to`: of the faces whose planes the
// vertex is least deep behind to within kOnPlane x distance, the one most
// turned towards `from` (its outward normal along the centroids' offset).
// A corner on an edge of `to` lies in the plane of the face beside the
// one it meets (an arch's extrados beside a joint, the blocks' common
// front plane); sunk a little into the joint it is least deep behind that
// face, and pressed against it the pair pushed itself apart both ways
// (347 of the 349 stalled solves of a collapsing 18-voussoir arch). A
// wider window is worse: at a tenth of the search distance the
// Armadillo's dynamics took 78 sweeps a step instead of 22, and at the
// whole of it a block tipping off a pedestal's edge, its corner on the
// top face a centimetre from the edge, took the side face when its
// centroid was past the edge, and sank 4-6 mm into the pedestal.
// `made`, when given, gets each point's vertex and face normal (world).
// A vertex within `distance` of one in `hinge` (the other block's points)
// whose face is turned against that point's face (kHingeCosine) is left
// out: the blocks meet corner to corner at a hinge, and one point with one
// normal carries it. With both, the hinge would hold two normals at its
// opening angle, a wedge that locks under friction when the angle is
// below twice the friction angle: squeezed, its points may carry any
// impulse (six collapsing arches: 50 steps before the first fall stalled
// with both, 3 without).
void add_vertex_contacts(int from, int to, const Block& a, const Block& b, double distance,
                         const std::vector<RigidPose>& poses, std::vector<ContactPoint>& out,
                         const std::vector<std::pair<Vec3, Vec3>>& hinge,
                         std::vector<std::pair<Vec3, Vec3>>* made) {
  const std::vector<FacePlane>& planes = b.face_planes();
  const Vec3 towards = a.centroid() - b.centroid();
  for (const Vec3& p : a.vertices()) {
    double outside = -std::numeric_limits<double>::infinity();
    for (const FacePlane& plane : planes) outside = std::max(outside, plane.normal.dot(p) - plane.offset);
    if (outside > distance) continue;
    int best = -1;
    for (size_t f = 0; f < planes.size(); ++f) {
      const double s = planes[f].normal.dot(p) - planes[f].offset;
      if (s < outside - kOnPlane * distance) continue;
      if (best < 0 || planes[f].normal.dot(towards) > planes[best].normal.dot(towards)) best = static_cast<int>(f);
    }
    const Vec3& normal = planes[best].normal;
    const auto same_hinge = [&](const std::pair<Vec3, Vec3>& point) {
      return (point.first - p).norm() <= distance && point.second.dot(normal) < kHingeCosine;
    };
    if (std::any_of(hinge.begin(), hinge.end(), same_hinge)) continue;
    out.push_back(make_point(from, to, best, p, planes[best], poses));
    if (made) made->emplace_back(p, normal);
  }
}

}  // namespace

ContactGeometry contact_geometry(const ContactPoint& contact, const std::vector<RigidPose>& poses) {
  const RigidPose& a = poses[contact.a];
  const RigidPose& b = poses[contact.b];
  ContactGeometry geometry;
  geometry.point = a.position + a.rotation * contact.point;
  const Vec3 face_normal = b.rotation * contact.normal;
  geometry.gap = face_normal.dot(geometry.point - b.position) - contact.offset;
  geometry.normal = -face_normal;
  return geometry;
}

std::vector<ContactPoint> find_contact_points(const std::vector<const Block*>& posed,
                                              const std::vector<RigidPose>& poses,
                                              const std::vector<bool>& fixed, const std::vector<int>& which,
                                              double distance, double angle) {
  std::vector<const Block*> subset;
  subset.reserve(which.size());
  for (int i : which) subset.push_back(posed[i]);
  ContactOptions options;
  options.tolerance = distance;
  options.angle = angle;
  const double opposite = opposite_cosine(options);

  std::vector<ContactPoint> out;
  std::set<std::pair<int, int>> face_pairs;
  for (const Interface& contact : detect_interfaces(subset, options)) {
    const int a = which[contact.a], b = which[contact.b];
    if (fixed[a] && fixed[b]) continue;
    const int face = facing_face(*posed[b], contact.normal, contact.center, opposite);
    if (face < 0) continue;
    face_pairs.emplace(std::min(a, b), std::max(a, b));
    for (const Vec3& p : contact.vertices) {
      out.push_back(make_point(a, b, face, p, posed[b]->face_planes()[face], poses));
    }
  }
  for (const auto& [i, j] : box_pairs(subset, distance)) {
    const int a = which[i], b = which[j];
    if ((fixed[a] && fixed[b]) || face_pairs.count({std::min(a, b), std::max(a, b)})) continue;
    if (!posed[a]->convex() || !posed[b]->convex()) continue;
    std::vector<std::pair<Vec3, Vec3>> of_a;
    add_vertex_contacts(a, b, *posed[a], *posed[b], distance, poses, out, {}, &of_a);
    add_vertex_contacts(b, a, *posed[b], *posed[a], distance, poses, out, of_a, nullptr);
  }
  std::stable_sort(out.begin(), out.end(), [](const ContactPoint& x, const ContactPoint& y) {
    return std::tie(x.a, x.b) < std::tie(y.a, y.b);
  });
  return out;
}

}  // namespace ashlar
