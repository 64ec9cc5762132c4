#include "structure/contact_detection.hpp"

#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "geometry/polygon_boolean.hpp"

namespace ashlar {

namespace {

using BoxWithIndex = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

// Above this many candidate face pairs in one block pair, pair the faces by
// box intersection instead of testing all of them (meshes with many facets).
constexpr size_t kBruteForceFacePairs = 1024;

// The box grown by `grow` on every side; a negative grow shrinks it, no
// further than its centre.
BoxWithIndex make_box(const Box3& box, double grow, int index) {
  const Vec3 centre = 0.5 * (box.lo + box.hi);
  const Vec3 lo = (box.lo.array() - grow).min(centre.array());
  const Vec3 hi = (box.hi.array() + grow).max(centre.array());
  return BoxWithIndex(CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()), index);
}

// Per-face data computed once per block.
struct FaceInfo {
  std::vector<Vec3> loop;
  Box3 box;
  FacePlane plane;
};

std::vector<FaceInfo> face_infos(const Block& block) {
  std::vector<FaceInfo> infos;
  infos.reserve(block.faces().size());
  for (size_t f = 0; f < block.faces().size(); ++f) {
    FaceInfo info;
    for (int index : block.faces()[f]) {
      info.loop.push_back(block.vertices()[index]);
      info.box.add(block.vertices()[index]);
    }
    info.plane = block.face_planes()[f];
    infos.push_back(std::move(info));
  }
  return infos;
}

// True when every vertex of the loop is further than tol on one side of the plane.
bool clear_of_plane(const std::vector<Vec3>& loop, const FacePlane& plane, double tol) {
  bool above = true, below = true;
  for (const Vec3& p : loop) {
    const double d = plane.normal.dot(p) - plane.offset;
    above = above && d > tol;
    below = below && d < -tol;
  }
  return above || below;
}

// Calls visit(face_a, face_b) for the faces of a and b whose boxes overlap.
template <class Visit>
void for_each_overlapping_face_pair(const std::vector<FaceInfo>& a, const Box3& box_a,
                                    const std::vector<FaceInfo>& b, const Box3& box_b, double tol,
                                    Visit visit) {
  std::vector<int> near_a, near_b;
  for (size_t f = 0; f < a.size(); ++f) {
    if (boxes_overlap(a[f].box, box_b, tol)) near_a.push_back(static_cast<int>(f));
  }
  for (size_t f = 0; f < b.size(); ++f) {
    if (boxes_overlap(b[f].box, box_a, tol)) near_b.push_back(static_cast<int>(f));
  }
  if (near_a.size() * near_b.size() <= kBruteForceFacePairs) {
    for (int fa : near_a) {
      for (int fb : near_b) {
        if (boxes_overlap(a[fa].box, b[fb].box, tol)) visit(fa, fb);
      }
    }
    return;
  }
  std::vector<BoxWithIndex> boxes_a, boxes_b;
  for (int fa : near_a) boxes_a.push_back(make_box(a[fa].box, 0.5 * tol, fa));
  for (int fb : near_b) boxes_b.push_back(make_box(b[fb].box, 0.5 * tol, fb));
  CGAL::box_intersection_d(boxes_a.begin(), boxes_a.end(), boxes_b.begin(), boxes_b.end(),
                           [&](const BoxWithIndex& x, const BoxWithIndex& y) {
                             visit(x.info(), y.info());
                           });
}

// Drops repeated points and points where the outline does not turn.
Loop2 simplify_loop(const Loop2& loop, double size) {
  const double close = 1e-9 * size;
  Loop2 out = loop;
  bool changed = true;
  while (changed && out.size() >= 3) {
    changed = false;
    for (size_t i = 0; i < out.size() && out.size() >= 3; ++i) {
      const Vec2& prev = out[(i + out.size() - 1) % out.size()];
      const Vec2& here = out[i];
      const Vec2& next = out[(i + 1) % out.size()];
      const Vec2 d1 = here - prev, d2 = next - here;
      const double cross = d1.x() * d2.y() - d1.y() * d2.x();
      const bool repeated = d1.norm() <= close;
      const bool straight = std::abs(cross) <= 1e-9 * d1.norm() * d2.norm() && d1.dot(d2) > 0.0;
      if (repeated || straight) {
        out.erase(out.begin() + static_cast<long>(i));
        changed = true;
      }
    }
  }
  if (out.size() < 3) out.clear();
  return out;
}

// The least width (m) and area (m^2) of a contact piece between two blocks.
struct SliverLimits {
  double width = 0.0;
  double area = 0.0;
};

SliverLimits sliver_limits(const ContactOptions& options, double tolerance, const Block& a, const Block& b) {
  const double size = std::min(block_size(a), block_size(b));
  return {options.min_width > 0.0 ? options.min_width : std::min(tolerance, options.relative_min_width * size),
          options.min_area > 0.0 ? options.min_area : options.relative_min_area * size * size};
}

bool is_sliver(const Loop2& outer, double area, const SliverLimits& limits) {
  return area <= 0.0 || area < limits.area || contact_width(outer, area) < limits.width;
}

// The faces of block a and block b that touch on one plane.
struct PlaneContact {
  std::vector<int> faces_a, faces_b;
};

class ContactBuilder {
public:
  ContactBuilder(double tol, double opposite) : tol_(tol), opposite_(opposite) {}

  void add_contacts(int ia, int ib, const std::vector<FaceInfo>& fa,
                    const std::vector<FaceInfo>& fb, const Box3& box_a, const Box3& box_b,
                    const SliverLimits& limits, std::vector<Interface>& out) const {
    std::vector<std::pair<int, int>> near;
    for_each_overlapping_face_pair(fa, box_a, fb, box_b, tol_, [&](int f, int g) { near.emplace_back(f, g); });
    // A face that is one copy of a joint meets its other copy across the
    // whole joint, and its neighbours only at edges: it takes no part in
    // the cutting below.
    std::vector<bool> paired_a(fa.size(), false), paired_b(fb.size(), false);
    for (const auto& [f, g] : near) {
      if (paired_a[f] || paired_b[g]) continue;
      const std::optional<std::vector<int>> pairing = mid_plane_pairing(fa[f].loop, fb[g].loop, tol_);
      if (pairing && add_mid_plane_contact(ia, ib, fa[f].loop, fb[g].loop, *pairing, limits, out)) {
        paired_a[f] = paired_b[g] = true;
        out.back().face_a = f;
        out.back().face_b = g;
      }
    }
    std::vector<PlaneContact> planes;
    for (const auto& [f, g] : near) {
      if (paired_a[f] || paired_b[g]) continue;
      const FacePlane& pa = fa[f].plane;
      if (!faces_may_touch(fa[f].loop, pa, fb[g].loop, fb[g].plane, tol_, opposite_)) continue;
      PlaneContact* target = nullptr;
      for (PlaneContact& contact : planes) {
        if (on_same_plane(pa.normal, pa.offset, fa[contact.faces_a.front()].plane, tol_)) {
          target = &contact;
        }
      }
      if (!target) target = &planes.emplace_back();
      if (std::find(target->faces_a.begin(), target->faces_a.end(), f) == target->faces_a.end()) {
        target->faces_a.push_back(f);
      }
      if (std::find(target->faces_b.begin(), target->faces_b.end(), g) == target->faces_b.end()) {
        target->faces_b.push_back(g);
      }
    }
    for (const PlaneContact& contact : planes) {
      add_plane_contact(ia, ib, fa, fb, contact, limits, out);
    }
  }

private:
  // The mid-polygon of two copies of one joint, projected onto its best-fit
  // plane (Newell normal, through the mean of the midpoints), kept in
  // loop_a's order so that interface vertex k comes from vertex k of each
  // copy. False, and nothing added, when the polygon crosses itself or is
  // a sliver: the faces are then cut as others.
  bool add_mid_plane_contact(int ia, int ib, const std::vector<Vec3>& loop_a,
                             const std::vector<Vec3>& loop_b, const std::vector<int>& pairing,
                             const SliverLimits& limits, std::vector<Interface>& out) const {
    const std::vector<Vec3> midpoints = paired_midpoints(loop_a, loop_b, pairing);
    Vec3 centre = Vec3::Zero();
    for (const Vec3& p : midpoints) centre += p;
    centre /= static_cast<double>(midpoints.size());
    const PlaneFrame frame = PlaneFrame::from_normal(centre, newell_normal(midpoints).normalized());
    Loop2 loop;
    for (const Vec3& p : midpoints) loop.push_back(frame.project(p));
    const double area = signed_area(loop);
    if (is_sliver(loop, area, limits) || !is_simple_loop(loop)) return false;
    Interface contact;
    contact.a = ia;
    contact.b = ib;
    contact.normal = frame.normal;
    contact.area = area;
    contact.center = frame.lift(area_centroid(loop));
    for (const Vec2& p : loop) contact.vertices.push_back(frame.lift(p));
    contact.on_mid_plane = true;
    set_frame_along_longest_edge(contact);
    out.push_back(std::move(contact));
    return true;
  }

  void add_plane_contact(int ia, int ib, const std::vector<FaceInfo>& fa,
                         const std::vector<FaceInfo>& fb, const PlaneContact& contact,
                         const SliverLimits& limits, std::vector<Interface>& out) const {
    const FacePlane& plane_a = fa[contact.faces_a.front()].plane;
    const PlaneFrame frame =
        PlaneFrame::from_normal(plane_a.normal * plane_a.offset, plane_a.normal);
    std::vector<Loop2> loops_a, loops_b;
    for (int f : contact.faces_a) {
      Loop2 loop;
      for (const Vec3& p : fa[f].loop) loop.push_back(frame.project(p));
      loops_a.push_back(std::move(loop));
    }
    for (int g : contact.faces_b) {
      // b's faces run counter-clockwise about b's normal, i.e. clockwise here.
      Loop2 loop;
      for (auto it = fb[g].loop.rbegin(); it != fb[g].loop.rend(); ++it) {
        loop.push_back(frame.project(*it));
      }
      loops_b.push_back(std::move(loop));
    }
    std::vector<PolygonWithHoles2> pieces;
    if (loops_a.size() == 1 && loops_b.size() == 1 && is_convex(loops_a[0]) &&
        is_convex(loops_b[0])) {
      Loop2 clipped = clip_convex(loops_a[0], loops_b[0]);
      if (!clipped.empty()) pieces.push_back({std::move(clipped), {}});
    } else {
      pieces = intersect_polygon_sets(loops_a, loops_b);
    }
    std::vector<FacePlane> planes_b;
    for (int g : contact.faces_b) planes_b.push_back(fb[g].plane);
    for (const PolygonWithHoles2& piece : pieces) {
      const size_t before = out.size();
      add_piece(ia, ib, frame, planes_b, piece, limits, out);
      if (out.size() == before) continue;
      out.back().face_a = contact.faces_a.front();
      out.back().face_b = contact.faces_b.front();
    }
  }

  void add_piece(int ia, int ib, const PlaneFrame& frame, const std::vector<FacePlane>& planes_b,
                 const PolygonWithHoles2& piece, const SliverLimits& limits,
                 std::vector<Interface>& out) const {
    Box3 extent;
    for (const Vec2& p : piece.outer) extent.add(Vec3(p.x(), p.y(), 0.0));
    const double size = extent.diagonal();
    const Loop2 outer = simplify_loop(piece.outer, size);
    if (outer.empty()) return;
    double area = signed_area(outer);
    Vec2 moment = area * area_centroid(outer);
    std::vector<Loop2> holes;
    for (const Loop2& hole : piece.holes) {
      Loop2 simple = simplify_loop(hole, size);
      if (simple.empty()) continue;
      const double hole_area = signed_area(simple);  // negative: clockwise
      area += hole_area;
      moment += hole_area * area_centroid(simple);
      holes.push_back(std::move(simple));
    }
    // A strip narrower than the least width is an edge or corner touch.
    if (is_sliver(outer, area, limits)) return;
    Interface contact;
    contact.a = ia;
    contact.b = ib;
    contact.normal = frame.normal;
    contact.area = area;
    contact.center = frame.lift(moment / area);
    for (const Vec2& p : outer) contact.vertices.push_back(frame.lift(p));
    for (const Loop2& hole : holes) {
      std::vector<Vec3> lifted;
      for (const Vec2& p : hole) lifted.push_back(frame.lift(p));
      contact.holes.push_back(std::move(lifted));
    }
    // The faces must meet across the whole polygon, not just cross each other.
    for (const Vec3& p : contact.vertices) {
      double gap = std::numeric_limits<double>::infinity();
      for (const FacePlane& plane : planes_b) {
        gap = std::min(gap, std::abs(plane.normal.dot(p) - plane.offset));
      }
      if (gap > tol_) return;
    }
    set_frame_along_longest_edge(contact);
    out.push_back(std::move(contact));
  }

  double tol_;
  double opposite_;  // see opposite_cosine
};

}  // namespace

bool boxes_overlap(const Box3& a, const Box3& b, double grow) {
  return (a.lo.array() <= b.hi.array() + grow).all() && (b.lo.array() <= a.hi.array() + grow).all();
}

bool faces_may_touch(const std::vector<Vec3>& loop_a, const FacePlane& plane_a,
                     const std::vector<Vec3>& loop_b, const FacePlane& plane_b, double tol,
                     double opposite) {
  return plane_a.normal.dot(plane_b.normal) <= opposite &&
         !clear_of_plane(loop_b, plane_a, tol) && !clear_of_plane(loop_a, plane_b, tol);
}

bool on_same_plane(const Vec3& normal, double offset, const FacePlane& plane, double tol) {
  return 1.0 - plane.normal.dot(normal) <= kSamePlaneNormals &&
         std::abs(plane.offset - offset) <= tol;
}

std::optional<std::vector<int>> mid_plane_pairing(const std::vector<Vec3>& loop_a,
                                                  const std::vector<Vec3>& loop_b, double tol) {
  const size_t n = loop_a.size();
  if (n < 3 || loop_b.size() != n) return std::nullopt;
  size_t first = 0;  // the vertex of b nearest a's first
  for (size_t j = 1; j < n; ++j) {
    if ((loop_b[j] - loop_a[0]).squaredNorm() < (loop_b[first] - loop_a[0]).squaredNorm()) first = j;
  }
  std::vector<int> pairing(n);
  double largest = 0.0;
  Box3 extent;
  for (size_t i = 0; i < n; ++i) {
    pairing[i] = static_cast<int>((first + n - i) % n);
    const double distance = (loop_b[pairing[i]] - loop_a[i]).norm();
    if (distance > tol) return std::nullopt;
    largest = std::max(largest, distance);
    extent.add(loop_a[i]);
  }
  if (largest <= kCoincidentCopies * extent.diagonal()) return std::nullopt;
  for (const std::vector<Vec3>* loop : {&loop_a, &loop_b}) {
    for (size_t i = 0; i < n; ++i) {
      if (((*loop)[(i + 1) % n] - (*loop)[i]).norm() <= 2.0 * tol) return std::nullopt;
    }
  }
  return pairing;
}

std::vector<Vec3> paired_midpoints(const std::vector<Vec3>& loop_a, const std::vector<Vec3>& loop_b,
                                   const std::vector<int>& pairing) {
  std::vector<Vec3> midpoints;
  midpoints.reserve(loop_a.size());
  for (size_t i = 0; i < loop_a.size(); ++i) midpoints.push_back(0.5 * (loop_a[i] + loop_b[pairing[i]]));
  return midpoints;
}

double opposite_cosine(const ContactOptions& options) { return -std::cos(options.angle); }

bool same_contacts(const ContactOptions& x, const ContactOptions& y) {
  return x.tolerance == y.tolerance && x.relative_tolerance == y.relative_tolerance && x.angle == y.angle &&
         x.min_width == y.min_width && x.relative_min_width == y.relative_min_width &&
         x.min_area == y.min_area && x.relative_min_area == y.relative_min_area;
}

double contact_width(const Loop2& outer, double area) {
  const double length = perimeter(outer);
  return length > 0.0 ? std::min(least_width(outer), 4.0 * area / length) : 0.0;
}

double effective_tolerance(const std::vector<const Block*>& blocks,
                           const ContactOptions& options) {
  if (!std::isfinite(options.tolerance) || options.tolerance < 0.0) {
    throw InvalidArgument("contact tolerance must be a finite number >= 0 (m)");
  }
  if (!std::isfinite(options.relative_tolerance) || options.relative_tolerance <= 0.0) {
    throw InvalidArgument("relative contact tolerance must be a finite number > 0");
  }
  if (!(options.angle > 0.0 && options.angle < 0.5 * M_PI)) {
    throw InvalidArgument("contact angle must be a number of radians in (0, pi/2), got " +
                          std::to_string(options.angle));
  }
  if (!std::isfinite(options.min_area) || options.min_area < 0.0) {
    throw InvalidArgument("contact min_area must be a finite number >= 0 (m^2), got " +
                          std::to_string(options.min_area));
  }
  if (!std::isfinite(options.min_width) || options.min_width < 0.0) {
    throw InvalidArgument("contact min_width must be a finite number >= 0 (m), got " +
                          std::to_string(options.min_width));
  }
  if (!(options.relative_min_width >= 0.0 && options.relative_min_width < 1.0) ||
      !(options.relative_min_area >= 0.0 && options.relative_min_area < 1.0)) {
    throw InvalidArgument("relative contact min_width and min_area must be numbers in [0, 1)");
  }
  if (options.tolerance > 0.0) return options.tolerance;
  Box3 box;
  for (const Block* block : blocks) box.add(block->bounds());
  return options.relative_tolerance * box.diagonal();
}

std::vector<std::pair<int, int>> box_pairs(const std::vector<const Block*>& blocks, double grow) {
  std::vector<BoxWithIndex> boxes;
  boxes.reserve(blocks.size());
  for (size_t i = 0; i < blocks.size(); ++i) {
    boxes.push_back(make_box(blocks[i]->bounds(), grow, static_cast<int>(i)));
  }
  std::vector<std::pair<int, int>> pairs;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(),
                                [&](const BoxWithIndex& x, const BoxWithIndex& y) {
                                  pairs.emplace_back(std::min(x.info(), y.info()),
                                                     std::max(x.info(), y.info()));
                                });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

namespace {

// The pairs (a, b) with wanted(a, b) that have no interface at options'
// tolerance but one at `reach`, each with the least tolerance that gives
// one (bisection on the detection itself, to 1e-3 of it).
template <typename Wanted>
std::vector<NearMiss> find_near_misses(const std::vector<const Block*>& blocks, double reach,
                                       const ContactOptions& options, Wanted&& wanted) {
  const double tol = effective_tolerance(blocks, options);
  const double opposite = opposite_cosine(options);
  std::vector<NearMiss> out;
  if (!(reach > tol)) return out;
  std::vector<std::vector<FaceInfo>> faces(blocks.size());
  auto faces_of = [&](int i) -> const std::vector<FaceInfo>& {
    if (faces[i].empty()) faces[i] = face_infos(*blocks[i]);
    return faces[i];
  };
  auto touch = [&](int a, int b, double tolerance) {
    std::vector<Interface> found;
    ContactBuilder(tolerance, opposite).add_contacts(a, b, faces_of(a), faces_of(b), blocks[a]->bounds(),
                                                     blocks[b]->bounds(),
                                                     sliver_limits(options, tolerance, *blocks[a], *blocks[b]),
                                                     found);
    return !found.empty();
  };
  for (const auto& [a, b] : box_pairs(blocks, 0.5 * reach)) {
    if (!wanted(a, b) || touch(a, b, tol) || !touch(a, b, reach)) continue;
    double lo = tol, hi = reach;  // no contact at lo, contact at hi
    while (hi - lo > 1e-3 * hi) {
      const double mid = 0.5 * (lo + hi);
      (touch(a, b, mid) ? hi : lo) = mid;
    }
    out.push_back({a, b, hi});
  }
  return out;
}

}  // namespace

std::vector<MissedContact> missed_contacts(const std::vector<const Block*>& blocks,
                                           const std::vector<int>& which, double reach,
                                           const ContactOptions& options) {
  std::vector<int> slot(blocks.size(), -1);  // into `which`
  for (size_t k = 0; k < which.size(); ++k) slot[which[k]] = static_cast<int>(k);
  std::vector<MissedContact> out(which.size());
  const std::vector<NearMiss> misses =
      find_near_misses(blocks, reach, options, [&](int a, int b) { return slot[a] >= 0 || slot[b] >= 0; });
  for (const NearMiss& miss : misses) {  // in pair order: ties go to the first pair
    for (const auto& [self, other] : {std::pair{miss.a, miss.b}, std::pair{miss.b, miss.a}}) {
      if (slot[self] >= 0 && miss.tolerance < out[slot[self]].tolerance) out[slot[self]] = {other, miss.tolerance};
    }
  }
  return out;
}

std::vector<NearMiss> near_misses(const std::vector<const Block*>& blocks, double reach,
                                  const ContactOptions& options) {
  std::vector<NearMiss> out = find_near_misses(blocks, reach, options, [](int, int) { return true; });
  std::stable_sort(out.begin(), out.end(),
                   [](const NearMiss& x, const NearMiss& y) { return x.tolerance < y.tolerance; });
  return out;
}

std::vector<Interface> detect_interfaces(const std::vector<const Block*>& blocks,
                                         const ContactOptions& options) {
  const double tol = effective_tolerance(blocks, options);
  const std::vector<std::pair<int, int>> candidates = box_pairs(blocks, 0.5 * tol);

  // Face data only for blocks that have a neighbour, computed once each.
  std::vector<std::vector<FaceInfo>> faces(blocks.size());
  for (const auto& [a, b] : candidates) {
    if (faces[a].empty()) faces[a] = face_infos(*blocks[a]);
    if (faces[b].empty()) faces[b] = face_infos(*blocks[b]);
  }
  const ContactBuilder builder(tol, opposite_cosine(options));
  std::vector<Interface> interfaces;
  for (const auto& [a, b] : candidates) {
    builder.add_contacts(a, b, faces[a], faces[b], blocks[a]->bounds(), blocks[b]->bounds(),
                         sliver_limits(options, tol, *blocks[a], *blocks[b]), interfaces);
  }
  // Same-pair pieces in a stable order, whatever order CGAL reported pairs in.
  std::stable_sort(interfaces.begin(), interfaces.end(), [](const Interface& x, const Interface& y) {
    return std::tie(x.a, x.b, x.center.x(), x.center.y(), x.center.z()) <
           std::tie(y.a, y.b, y.center.x(), y.center.y(), y.center.z());
  });
  interfaces.shrink_to_fit();  // kept with the structure: no room left from growing by doubling
  return interfaces;
}

}  // namespace ashlar
