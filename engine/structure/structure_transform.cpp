#include "structure/structure_transform.hpp"

#include <cmath>
#include <memory>

#include "core/error.hpp"

namespace ashlar {

Structure rotated(const Structure& structure, const Vec3& axis, double angle, const Vec3& origin) {
  // Checked here as well as by Block::rotated, so that a structure without
  // blocks rejects the same arguments.
  if (!std::isfinite(angle)) throw InvalidArgument("rotation angle must be finite");
  if (!axis.allFinite()) throw InvalidArgument("rotation axis must be finite");
  if (!origin.allFinite()) throw InvalidArgument("rotation origin must be finite");
  if (axis.norm() == 0.0) throw InvalidArgument("rotation axis must not be zero");
  const Mat3 rotation = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  auto move = [&](const Vec3& p) -> Vec3 { return origin + rotation * (p - origin); };

  Structure out;
  for (const StructureBlock& entry : structure.entries()) {
    out.add(std::make_shared<const Block>(entry.block->rotated(axis, angle, origin)), entry.support,
            entry.name);
  }
  const bool keeps_plane = axis.x() == 0.0 && axis.z() == 0.0;
  out.set_planar(structure.planar() && (keeps_plane || angle == 0.0));
  for (PointLoad load : structure.loads()) {
    load.at = move(load.at);
    out.add_load(load);
  }
  for (Cable cable : structure.cables()) {
    cable.from.point = move(cable.from.point);
    cable.to.point = move(cable.to.point);
    out.add_cable(cable);
  }
  for (const Interface& contact : structure.explicit_interfaces()) {
    std::vector<Vec3> polygon;
    for (const Vec3& p : contact.vertices) polygon.push_back(move(p));
    out.add_interface(contact.a, contact.b, {polygon}, Vec3(rotation * contact.normal));
  }
  return out;
}

Vec3 base_center(const Structure& structure) {
  const Box3 box = structure.bounds();
  if (box.empty()) return Vec3::Zero();
  return {0.5 * (box.lo.x() + box.hi.x()), 0.5 * (box.lo.y() + box.hi.y()), box.lo.z()};
}

}  // namespace ashlar
