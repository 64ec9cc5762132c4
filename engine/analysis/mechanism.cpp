#include "analysis/mechanism.hpp"

#include <algorithm>
#include <Eigen/Geometry>
#include <array>

namespace ashlar {

namespace {

// Velocity at `p` (m) of block j moving as motion[j]; supports stand still.
Vec3 velocity_at(const Structure& structure, const std::vector<BlockMotion>& motion, int j, const Vec3& p) {
  if (structure.is_support(j)) return Vec3::Zero();
  return motion[j].velocity + motion[j].rotation.cross(p - structure.block(j).centroid());
}

}  // namespace

Block moved_by_mechanism(const Block& block, const BlockMotion& motion, double scale) {
  const double angle = scale * motion.rotation.norm();
  const Block turned = angle > 0.0 ? block.rotated(motion.rotation, angle, block.centroid()) : block;
  return turned.translated(scale * motion.velocity);
}

// The collapse mechanism from the balance rows' multipliers: they are the
// blocks' virtual velocities (a force row's over the unit of force, a
// moment row's over force times length), up to sign and scale.
Vec3 moved_point(const Vec3& p, const Vec3& centroid, const BlockMotion& motion, double scale) {
  const double angle = scale * motion.rotation.norm();
  const Vec3 turned = angle > 0.0 ? Vec3(centroid + Eigen::AngleAxisd(angle, motion.rotation.normalized()) * (p - centroid))
                                  : p;
  return turned + scale * motion.velocity;
}

std::vector<BlockMotion> mechanism_of(const Structure& structure, const EquilibriumProblem& problem,
                                      const double* multipliers, double* dual_unit) {
  const std::array<int, 6>& rows = balance_rows(problem.block_rows == 3);
  std::vector<BlockMotion> motion(structure.size());
  double fastest = 0.0;
  for (int j = 0; j < structure.size(); ++j) {
    const int first = problem.row_of_block[j];
    if (first < 0) continue;
    for (int r = 0; r < problem.block_rows; ++r) {
      // With this sign the multiplied load does positive work.
      const double y = -multipliers[first + r] / problem.weight_unit;
      if (rows[r] < 3) motion[j].velocity(rows[r]) = y;
      else motion[j].rotation(rows[r] - 3) = y / problem.length_unit;
    }
    fastest = std::max(fastest, motion[j].velocity.norm());
  }
  if (fastest <= 0.0) {
    for (int j = 0; j < structure.size(); ++j) {
      for (const Vec3& p : structure.block(j).vertices()) {
        fastest = std::max(fastest, velocity_at(structure, motion, j, p).norm());
      }
    }
  }
  if (fastest > 0.0) {
    for (BlockMotion& m : motion) {
      m.velocity /= fastest;
      m.rotation /= fastest;
    }
  }
  // A vertex's relative velocity along a unit force's column, in the units
  // above, is that column times the multipliers over weight_unit.
  if (dual_unit) *dual_unit = fastest * problem.weight_unit;
  return motion;
}

std::vector<LimitInterface> limit_interfaces(const Structure& structure, const std::vector<Interface>& interfaces,
                                             const std::vector<BlockMotion>& motion, double noise) {
  constexpr double kMoving = 1e-6, kShare = 1e-3;
  struct Relative {
    std::vector<double> opening, slip;
    double largest = 0.0;
  };
  std::vector<Relative> relative(interfaces.size());
  double fastest = 0.0;
  for (size_t k = 0; k < interfaces.size(); ++k) {
    const Interface& contact = interfaces[k];
    for (const Vec3& p : contact.vertices) {
      const Vec3 rate = velocity_at(structure, motion, contact.b, p) - velocity_at(structure, motion, contact.a, p);
      const double opening = rate.dot(contact.normal);
      relative[k].opening.push_back(opening);
      relative[k].slip.push_back((rate - opening * contact.normal).norm());
      relative[k].largest = std::max(relative[k].largest, rate.norm());
    }
    fastest = std::max(fastest, relative[k].largest);
  }
  std::vector<LimitInterface> limit;
  for (size_t k = 0; k < interfaces.size(); ++k) {
    const Relative& r = relative[k];
    if (!(r.largest > std::max(kMoving * fastest, noise))) continue;
    LimitInterface entry;
    entry.interface = static_cast<int>(k);
    const auto [least, most] = std::minmax_element(r.opening.begin(), r.opening.end());
    entry.opening = *most;
    entry.slip = *std::max_element(r.slip.begin(), r.slip.end());
    const double share = std::max(kShare * r.largest, noise);
    const bool rotating = *most - *least > share;
    const bool slipping = entry.slip > share;
    entry.mode = rotating ? (slipping ? LimitMode::hinge_sliding : LimitMode::hinge)
                          : (slipping ? LimitMode::sliding : LimitMode::separation);
    Vec3 sum = Vec3::Zero();
    int count = 0;
    for (size_t v = 0; v < r.opening.size(); ++v) {
      if (r.opening[v] - *least <= share) {
        sum += interfaces[k].vertices[v];
        ++count;
      }
    }
    entry.pivot = rotating && count > 0 ? Vec3(sum / count) : interfaces[k].center;
    limit.push_back(entry);
  }
  return limit;
}

}  // namespace ashlar
