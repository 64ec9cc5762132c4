// Finds blocks that interpenetrate. Contact detection only pairs faces that
// lie on one plane, so two blocks pushed into each other have no interface
// and an analysis would treat them as apart: a wrong model, found here.
#pragma once

#include <vector>

#include "geometry/block.hpp"

namespace ashlar {

struct BlockOverlap {
  int a = -1, b = -1;  // 0-based block indices, a < b
  // m: for two convex blocks, how far they must move apart to only touch
  // (the least overlap of their projections on the separating-axis
  // candidates); otherwise the least extent of the solid they share along
  // those axes.
  double depth = 0.0;
};

// Pairs whose overlap is deeper than `tolerance` (m) plus the warp of the
// two blocks (Block::warp: two sides of a joint with warped faces cut
// differently are different surfaces, as far apart as their warp), sorted
// by (a, b). Blocks that touch along a face, an edge or a corner do not
// overlap.
// Convex pairs are decided by the separating-axis theorem (face normals of
// both, cross products of their edges); a pair with a non-convex block that
// no such axis separates is intersected exactly with CGAL.
std::vector<BlockOverlap> detect_overlaps(const std::vector<const Block*>& blocks,
                                          double tolerance);

}  // namespace ashlar
