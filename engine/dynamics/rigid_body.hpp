// The rigid bodies of a simulation: mass, inertia and pose of each block.
//
// A pose maps a block's reference geometry (the coordinates it was built
// with, m) to where it is now: y = rotation * (y0 - centroid0) + position.
// `position` is the current centroid (m); `rotation` a unit quaternion.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "core/types.hpp"
#include "geometry/block.hpp"

namespace ashlar {

using Quat = Eigen::Quaterniond;

// Inertia tensor (kg m^2) of the solid polyhedron about its centroid, in the
// block's own coordinates: exact for the polyhedron (its faces
// triangulated by for_each_surface_triangle, as mass_properties does),
// density block.density().
Mat3 inertia_tensor(const Block& block);

struct RigidPose {
  Vec3 position = Vec3::Zero();      // centroid (m)
  Quat rotation = Quat::Identity();  // reference -> current

  // Where the reference point y0 (m) of a block whose reference centroid is
  // `centroid0` is now.
  Vec3 apply(const Vec3& y0, const Vec3& centroid0) const {
    return rotation * (y0 - centroid0) + position;
  }
};

// Rotation vector (axis times angle, rad, angle in [0, pi]) of a unit
// quaternion.
Vec3 rotation_vector(const Quat& q);
// The quaternion turning by |w| rad about w (identity for w = 0).
Quat quaternion_from_rotation_vector(const Vec3& w);

// The block placed at `pose` (reference geometry from `block`): a new block
// with the same faces, density and name.
Block posed_block(const Block& block, const RigidPose& pose);

// Largest distance (m) between the block's vertices at poses x and y.
double vertex_distance(const Block& block, const RigidPose& x, const RigidPose& y);

}  // namespace ashlar
