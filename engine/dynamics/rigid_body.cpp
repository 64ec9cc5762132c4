#include "dynamics/rigid_body.hpp"

#include <algorithm>
#include <cmath>

namespace ashlar {

Mat3 inertia_tensor(const Block& block) {
  // Second moment C = integral of x x^T over the solid, x from the
  // centroid, summed over signed tetrahedra (centroid, triangle) of the
  // block's surface: for a tetrahedron (0, a, b, c) it is det[a b c] / 120
  // (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
  const Vec3& c0 = block.centroid();
  Mat3 second = Mat3::Zero();
  for (const FaceLoop& face : block.faces()) {
    for_each_surface_triangle(block.vertices(), face, [&](const Vec3& pa, const Vec3& pb, const Vec3& pc) {
      const Vec3 a = pa - c0, b = pb - c0, c = pc - c0;
      const double det = a.dot(b.cross(c));
      const Vec3 s = a + b + c;
      second += det / 120.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    });
  }
  second *= block.density();
  return second.trace() * Mat3::Identity() - second;
}

Vec3 rotation_vector(const Quat& q) {
  Quat unit = q.normalized();
  if (unit.w() < 0) unit.coeffs() = -unit.coeffs();  // the shorter way round
  const double s = unit.vec().norm();
  if (s < 1e-300) return Vec3::Zero();
  const double angle = 2.0 * std::atan2(s, unit.w());
  return unit.vec() / s * angle;
}

Quat quaternion_from_rotation_vector(const Vec3& w) {
  const double angle = w.norm();
  if (angle == 0.0) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, w / angle));
}

Block posed_block(const Block& block, const RigidPose& pose) {
  const Vec3 rotation = rotation_vector(pose.rotation);
  const double angle = rotation.norm();
  const Block turned = angle > 0.0 ? block.rotated(rotation / angle, angle, block.centroid()) : block;
  return turned.translated(pose.position - block.centroid());
}

double vertex_distance(const Block& block, const RigidPose& x, const RigidPose& y) {
  double largest = 0.0;
  for (const Vec3& p : block.vertices()) {
    largest = std::max(largest, (x.apply(p, block.centroid()) - y.apply(p, block.centroid())).norm());
  }
  return largest;
}

}  // namespace ashlar
