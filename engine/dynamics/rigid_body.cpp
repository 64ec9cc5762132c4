#include "dynamics/rigid_body.hpp"

#include <cmath>

namespace ashlar {

Mat3 inertia_tensor(const Block& block) {
  // Second moment C = integral of x x^T over the solid, x from the
  // centroid, summed over signed tetrahedra (centroid, v0, vi, vi+1): for a
  // tetrahedron (0, a, b, c) it is det[a b c] / 120 (a a^T + b b^T + c c^T
  // + s s^T), s = a + b + c.
  const Vec3& c0 = block.centroid();
  const std::vector<Vec3>& p = block.vertices();
  Mat3 second = Mat3::Zero();
  for (const FaceLoop& face : block.faces()) {
    const Vec3 a = p[face[0]] - c0;
    for (size_t k = 1; k + 1 < face.size(); ++k) {
      const Vec3 b = p[face[k]] - c0, c = p[face[k + 1]] - c0;
      const double det = a.dot(b.cross(c));
      const Vec3 s = a + b + c;
      second += det / 120.0 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
    }
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

}  // namespace ashlar
