// The solid two blocks share, for overlap checks that the separating-axis
// test cannot settle (non-convex blocks).
#pragma once

#include <optional>
#include <vector>

#include "geometry/block.hpp"

namespace ashlar {

// Vertices of the intersection of the two blocks' solids, by exact CGAL
// corefinement: empty when they only touch or are apart. Nothing when CGAL
// cannot build the intersection as a manifold surface.
std::optional<std::vector<Vec3>> shared_solid_vertices(const Block& a, const Block& b);

}  // namespace ashlar
