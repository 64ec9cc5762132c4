// The contact points of a simulation: where a point fixed to one block
// meets (or nears) a face plane fixed to another.
//
// Two sources, both on the blocks as they stand now:
// - face-to-face contacts found by ashlar's contact detection
//   (detect_interfaces, contact_detection.hpp) at a search distance: every
//   vertex of each contact polygon (which lies in a face of block a) becomes
//   a point on a against the face of b it was cut from;
// - for pairs of convex blocks with no such contact (a corner or an edge
//   landing on a face at an angle), every vertex of either block within the
//   search distance of the other's solid, against that block's face most
//   turned towards the vertex's block among those the vertex is least deep
//   behind to within a hundredth of the search distance (a corner on an
//   edge lies in two faces' planes). Where the two blocks meet corner to corner
//   at a hinge (a corner of b within the search distance of a corner of a,
//   their faces turned against each other within 30 degrees), only a's
//   corner makes a point: one normal at the hinge, not a wedge of two.
// Edge-to-edge crossings between blocks with no face contact, and corners of
// non-convex blocks meeting at an angle, are not found.
#pragma once

#include <vector>

#include "core/types.hpp"
#include "dynamics/rigid_body.hpp"
#include "geometry/block.hpp"

namespace ashlar {

// A point of block `a` against a face plane of block `b`, both kept in
// their block's reference coordinates relative to its reference centroid,
// so that they move with their blocks.
struct ContactPoint {
  int a = -1, b = -1;              // 0-based block indices, a != b
  int face = -1;                   // face of b (index into b's faces)
  Vec3 point = Vec3::Zero();       // on a: reference position - a's reference centroid (m)
  Vec3 normal = Vec3::Zero();      // b's outward face normal, reference frame (unit)
  double offset = 0.0;             // normal . (y - b's reference centroid) = offset on the plane (m)
  // Impulse (N s, world frame) the contact gave block b in the last step
  // (block a got its opposite): the solver's warm start.
  Vec3 impulse = Vec3::Zero();
};

// A contact point's place now: the point (m, world), the unit normal from a
// into b (the reverse of b's face normal) and the gap (m, positive apart,
// negative overlapping).
struct ContactGeometry {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double gap = 0.0;
};

ContactGeometry contact_geometry(const ContactPoint& contact, const std::vector<RigidPose>& poses);

// Contact points among `which` (0-based, distinct) of the blocks: posed[i]
// is block i where it stands now (world coordinates), poses[i] its motion
// from where it was built; `fixed[i]` marks blocks that
// never move (pairs of them are skipped). `distance` (m, > 0) is the search
// distance: gaps up to it are found; `angle` (rad) the largest angle between
// two faces that detection pairs (ContactOptions::angle). Sorted by (a, b).
std::vector<ContactPoint> find_contact_points(const std::vector<const Block*>& posed,
                                              const std::vector<RigidPose>& poses,
                                              const std::vector<bool>& fixed, const std::vector<int>& which,
                                              double distance, double angle);

}  // namespace ashlar
