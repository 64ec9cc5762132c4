// Finds every contact polygon between the blocks of a structure.
#pragma once

#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "geometry/block.hpp"
#include "structure/interface.hpp"

namespace ashlar {

struct ContactOptions {
  // Largest gap, overlap or warp (m) between two faces that still counts as
  // contact, measured at every vertex of the contact polygon. <= 0 means
  // relative_tolerance times the model's bounding-box diagonal. It decides
  // which faces meet, never how large a contact must be (min_width and
  // min_area do), so a larger tolerance never loses a contact.
  double tolerance = 0.0;
  double relative_tolerance = 1e-6;
  // Largest angle (rad) between one face's outward normal and the reverse of
  // the other's for the two to be in contact: acos(0.99), about 8.1 degrees,
  // by default; larger for warped or curved joints whose facets do not
  // match, less than pi / 2.
  double angle = std::acos(0.99);
  // Contact pieces narrower than this (m) are edge or corner touches and
  // are dropped. The width is contact_width's: it does not depend on how
  // the joint is turned. <= 0 means the tolerance (faces misaligned within
  // it overlap in strips as narrow: imprecision, not contact), but at most
  // relative_min_width times the size of the smaller of the two blocks
  // (block_size: a box's diagonal), so that a larger tolerance never loses
  // a joint wider than that.
  double min_width = 0.0;
  double relative_min_width = 0.02;
  // Interfaces smaller than this (m^2) are dropped: slivers of imperfect
  // models. <= 0 means relative_min_area times the square of the smaller
  // block's size (rounding's pieces of no area at any scale).
  double min_area = 0.0;
  double relative_min_area = 1e-8;
};

// The width (m) of a contact piece with outer loop `outer` and net area
// `area`: its least caliper width (least_width), or 4 area / perimeter
// where that is smaller (a thin L- or U-shaped piece, whose hull is wide).
// A rectangle's is its shorter side.
double contact_width(const Loop2& outer, double area);

// -cos(options.angle): two faces may touch when the dot product of their
// outward normals is at most this.
double opposite_cosine(const ContactOptions& options);
// Whether two option sets find the same interfaces.
bool same_contacts(const ContactOptions& x, const ContactOptions& y);

// Broad phase: overlapping bounding boxes (CGAL box intersection,
// O(n log n + k)); narrow phase: face pairs that describe one joint twice
// (mid_plane_pairing) give their mid-polygon; other face pairs with
// opposite normals whose planes coincide within the tolerance are
// intersected in the face plane (convex clipping, or exact general polygon
// intersection when a face is non-convex or several faces share a plane).
// Sorted by (a, b).
std::vector<Interface> detect_interfaces(const std::vector<const Block*>& blocks,
                                         const ContactOptions& options);

// The contact a block just misses: the nearest block it has no interface
// with, and the least contact tolerance (m) that would give them one (a gap
// between two faces closes at about its width).
struct MissedContact {
  int block = -1;  // 0-based; -1: none within reach
  double tolerance = std::numeric_limits<double>::infinity();
};

// For blocks[i], i in `which`: the missed contact with the smallest closing
// tolerance up to `reach` (m), among the blocks it has no interface with at
// options' tolerance. The tolerance is found by bisection to 1e-3 of itself
// (on the detection itself, so it is the one an analysis would need).
std::vector<MissedContact> missed_contacts(const std::vector<const Block*>& blocks,
                                           const std::vector<int>& which, double reach,
                                           const ContactOptions& options);

// Every pair of blocks with no interface at options' tolerance that has one
// at some tolerance up to `reach` (m), with that least tolerance (as
// missed_contacts finds it), sorted by it.
struct NearMiss {
  int a = -1, b = -1;  // 0-based, a < b
  double tolerance = 0.0;  // m
};
std::vector<NearMiss> near_misses(const std::vector<const Block*>& blocks, double reach,
                                  const ContactOptions& options);

// The rules by which detection pairs faces, shared with the interfaces'
// derivatives (interface_gradient.cpp), which must find the faces an
// interface was cut from.
//
// Normals of faces of one block within this (1 - cos) are treated as one plane.
constexpr double kSamePlaneNormals = 1e-9;

bool boxes_overlap(const Box3& a, const Box3& b, double grow);
// Whether two faces (vertex loops and planes, m) may touch within `tol` (m):
// normals opposite to within the contact angle (their dot product at most
// `opposite`, see opposite_cosine), and neither loop entirely more than tol
// to one side of the other's plane. Their boxes are checked apart.
bool faces_may_touch(const std::vector<Vec3>& loop_a, const FacePlane& plane_a,
                     const std::vector<Vec3>& loop_b, const FacePlane& plane_b, double tol,
                     double opposite);
// Whether the plane (normal, offset) is `plane` within `tol` (m).
bool on_same_plane(const Vec3& normal, double offset, const FacePlane& plane, double tol);

// Two faces that describe one joint twice become one mid-plane interface
// (Interface::on_mid_plane): faces with as many vertices, each vertex of
// loop_a within `tol` (m) of one of loop_b (whose loop runs the other way,
// its normal facing a's), every edge of both longer than 2 tol so that the
// pairing is the only one, and the pairs not all coincident to rounding
// (kCoincidentCopies of the face's size): coincident faces are cut as
// before, which gives the same polygon. Returns pairing[i], the index in loop_b of the vertex
// paired with loop_a[i], or nothing. The angle between the faces is not
// tested: vertices that pair up within the tolerance are one joint, however
// far the imprecision has tilted its narrow copies.
constexpr double kCoincidentCopies = 1e-9;
std::optional<std::vector<int>> mid_plane_pairing(const std::vector<Vec3>& loop_a,
                                                  const std::vector<Vec3>& loop_b, double tol);

// The midpoints of the paired vertices of two such faces, in loop_a's order.
std::vector<Vec3> paired_midpoints(const std::vector<Vec3>& loop_a, const std::vector<Vec3>& loop_b,
                                   const std::vector<int>& pairing);

// The broad phase of contact and overlap detection: the pairs (i, j), i < j,
// sorted, of blocks whose bounding boxes intersect when each is grown by
// `grow` (m) on every side, or shrunk when it is negative.
std::vector<std::pair<int, int>> box_pairs(const std::vector<const Block*>& blocks, double grow);

// The tolerance actually used for `blocks` under `options` (m).
double effective_tolerance(const std::vector<const Block*>& blocks,
                           const ContactOptions& options);

}  // namespace ashlar
