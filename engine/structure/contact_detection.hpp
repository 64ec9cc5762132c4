// Finds every contact polygon between the blocks of a structure.
#pragma once

#include <vector>

#include "geometry/block.hpp"
#include "structure/interface.hpp"

namespace ashlar {

struct ContactOptions {
  // Largest gap or overlap (m) between two faces that still counts as
  // contact, measured at every vertex of the contact polygon; also the
  // thinnest contact kept (narrower strips are edge or corner touches).
  // <= 0 means relative_tolerance times the model's bounding-box diagonal.
  double tolerance = 0.0;
  double relative_tolerance = 1e-6;
};

// Broad phase: overlapping bounding boxes (CGAL box intersection,
// O(n log n + k)); narrow phase: face pairs with opposite normals whose
// planes coincide within the tolerance, intersected in the face plane
// (convex clipping, or exact general polygon intersection when a face is
// non-convex or several faces share a plane). Sorted by (a, b).
std::vector<Interface> detect_interfaces(const std::vector<const Block*>& blocks,
                                         const ContactOptions& options);

// The tolerance actually used for `blocks` under `options` (m).
double effective_tolerance(const std::vector<const Block*>& blocks,
                           const ContactOptions& options);

}  // namespace ashlar
