// Rigid motions of a whole structure: blocks, supports, loads and cables
// move together, as on a tilt table.
#pragma once

#include "core/types.hpp"
#include "structure/structure.hpp"

namespace ashlar {

// ROTATED  The structure turned rigidly: a right-handed rotation by `angle`
// (radians) about `axis` (any length but zero) through `origin` (m).
//
//   Structure tilted = rotated(s, Vec3::UnitY(), theta, base_center(s));
//
// Every block, supports included, keeps its name, support flag, density and
// faces; cable end points (anchors and junctions) turn with the blocks, and
// cables keep their mass and tension bound; explicit interfaces turn with
// their blocks. Point loads move their point of
// application but keep their force vector in world coordinates: they are
// dead weights that still hang vertically, as gravity does. So about +y by
// theta > 0 (which moves +z towards +x) gravity, seen in the structure's own
// frame, acts along (sin theta, 0, -cos theta): the same verdict as the
// untilted structure under a horizontal body force tan(theta) times each
// block's weight along +x.
//
// A planar structure (an extrusion along y, analysed in the x-z plane) stays
// planar when the axis is parallel to y, which keeps the x-z plane, or the
// angle is 0; any other rotation clears the flag of the copy.
//
// Throws InvalidArgument for a non-finite angle, axis or origin, or a zero axis.
Structure rotated(const Structure& structure, const Vec3& axis, double angle, const Vec3& origin);

// The centre of the bottom face of the structure's bounding box: centre in x
// and y, lowest z (m); the origin at which a tilt table turns a structure
// standing on it. The zero vector for an empty structure.
Vec3 base_center(const Structure& structure);

}  // namespace ashlar
