// The solid two blocks share, for overlap checks that the separating-axis
// test cannot settle (non-convex blocks).
#pragma once

#include <optional>
#include <vector>

#include "geometry/block.hpp"

namespace ashlar {

// The intersection of the two blocks' solids, by exact CGAL corefinement,
// as the vertices of each of its connected pieces: empty when they only
// touch or are apart. Nothing when CGAL cannot build the intersection as a
// manifold surface. (Two facetings of one curved joint share many thin
// lens-shaped pieces: each is thin, together they span the joint.)
std::optional<std::vector<std::vector<Vec3>>> shared_solid_pieces(const Block& a, const Block& b);

}  // namespace ashlar
