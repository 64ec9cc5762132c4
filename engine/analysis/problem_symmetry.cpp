#include "analysis/problem_symmetry.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "core/point_grid.hpp"

namespace ashlar {

namespace {

using Effect = Eigen::Matrix<double, 6, 4>;
using Motion6 = Eigen::Matrix<double, 6, 6>;

// Scaled quantities (effects, right-hand sides: O(1) per block) must map to
// this; positions to this many length units.
constexpr double kSameScaled = 1e-9;
constexpr double kSamePosition = 1e-7;
// Motions tried at most (each costs a pass over the problem; a failing one
// usually stops at its first blocks).
constexpr int kMaxCandidates = 4096;

// The unknowns' signed permutations that may carry a group's unknowns to
// its image's: the first two kept, the last two (a contact vertex's
// friction pair f_u, f_v) permuted with signs, where the kind's rules,
// Hessian and linear term allow.
std::vector<Eigen::Matrix4d> friction_permutations(const GroupRules& rules) {
  std::vector<Eigen::Matrix4d> kept;
  for (int swap = 0; swap < 2; ++swap) {
    for (int sign_u = -1; sign_u <= 1; sign_u += 2) {
      for (int sign_v = -1; sign_v <= 1; sign_v += 2) {
        Eigen::Matrix4d s = Eigen::Matrix4d::Zero();
        s(0, 0) = s(1, 1) = 1.0;
        s(swap ? 3 : 2, 2) = sign_u;  // x' = S x: f_u goes to (swap ? f_v' : f_u')
        s(swap ? 2 : 3, 3) = sign_v;
        // The rules hold for S x exactly when they hold for x: each row
        // r S (with its bound) is one of the rows.
        bool rows_kept = true;
        for (Eigen::Index i = 0; i < rules.rows.rows() && rows_kept; ++i) {
          const Eigen::RowVector4d mapped = rules.rows.row(i) * s;
          bool found = false;
          for (Eigen::Index j = 0; j < rules.rows.rows() && !found; ++j) {
            found = (mapped - rules.rows.row(j)).lpNorm<Eigen::Infinity>() <= kSameScaled &&
                    (rules.bound_coefficients.size() == 0 ||
                     std::abs(rules.bound_coefficients(i) - rules.bound_coefficients(j)) <= kSameScaled);
          }
          rows_kept = found;
        }
        const Eigen::Vector4d h = (s.transpose() * rules.hessian.asDiagonal() * s).diagonal();
        if (rows_kept && (h - rules.hessian).lpNorm<Eigen::Infinity>() <= kSameScaled * rules.hessian.norm() &&
            (s.transpose() * rules.linear - rules.linear).lpNorm<Eigen::Infinity>() <= kSameScaled) {
          kept.push_back(s);
        }
      }
    }
  }
  return kept;
}

// Whether a is b to kSameScaled, relative to b's size (at least 1).
template <class A, class B>
bool same_scaled(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
  return (a - b).template lpNorm<Eigen::Infinity>() <= kSameScaled * (1.0 + b.template lpNorm<Eigen::Infinity>());
}

class SymmetrySearch {
public:
  SymmetrySearch(const Structure& structure, const EquilibriumProblem& problem)
      : structure_(structure),
        problem_(problem),
        tolerance_(kSamePosition * problem.length_unit),
        blocks_(Vec3::Zero(), 4.0 * tolerance_),
        vertices_(Vec3::Zero(), 4.0 * tolerance_) {
    for (int kind = 0; kind < kGroupKinds; ++kind) permutations_[kind] = friction_permutations(problem.rules[kind]);
    for (int j = 0; j < structure.size(); ++j) {
      if (problem.row_of_block[j] >= 0) blocks_.insert(structure.block(j).centroid(), j);
    }
    for (int k = 0; k < static_cast<int>(problem.groups.size()); ++k) vertices_.insert(position(problem.groups[k]), k);
  }

  // The block map of the motion p -> axis + Q (p - axis), or empty when
  // it does not map the problem onto itself.
  std::vector<int> block_map(const Vec3& axis, const Mat3& q) const {
    const int n = structure_.size();
    Motion6 t = Motion6::Zero();
    t.topLeftCorner<3, 3>() = q;
    t.bottomRightCorner<3, 3>() = q.determinant() * q;  // moments are axial vectors
    std::vector<int> map(n, -1);
    std::vector<char> taken(n, 0);
    for (int j = 0; j < n; ++j) {
      const int row = problem_.row_of_block[j];
      if (row < 0) continue;
      const Block& block = structure_.block(j);
      const Vec3 image = axis + q * (block.centroid() - axis);
      int found = -1;
      blocks_.for_each_near(image, tolerance_, [&](int i) {
        if (found < 0 && !taken[i] && (structure_.block(i).centroid() - image).norm() <= tolerance_ &&
            std::abs(structure_.block(i).mass() - block.mass()) <= kSameScaled * block.mass()) {
          found = i;
        }
      });
      if (found < 0) return {};
      const Eigen::Matrix<double, 6, 1> loads = t * problem_.rhs.segment<6>(row);
      const Eigen::Matrix<double, 6, 1> image_loads = problem_.rhs.segment<6>(problem_.row_of_block[found]);
      if (!same_scaled(loads, image_loads)) return {};
      map[j] = found;
      taken[found] = 1;
    }
    std::vector<char> used(problem_.groups.size(), 0);
    for (const ForceGroup& group : problem_.groups) {
      const Vec3 image = axis + q * (position(group) - axis);
      int found = -1;
      vertices_.for_each_near(image, tolerance_, [&](int k) {
        if (found < 0 && !used[k] && (position(problem_.groups[k]) - image).norm() <= tolerance_ &&
            maps_to(group, problem_.groups[k], map, t)) {
          found = k;
        }
      });
      if (found < 0) return {};
      used[found] = 1;
    }
    return map;
  }

private:
  // Where a group acts: a contact vertex's position, a weight's block's
  // centroid (searchable() admits no other groups).
  const Vec3& position(const ForceGroup& group) const {
    return group.kind == GroupKind::contact_vertex ? problem_.vertex_position(group)
                                                   : structure_.block(group.source).centroid();
  }
  // Whether `group`'s image under the motion (block map `map`, 6 x 6
  // action t) is `image`, through one of its kind's permutations.
  bool maps_to(const ForceGroup& group, const ForceGroup& image, const std::vector<int>& map,
               const Motion6& t) const {
    if (image.kind != group.kind || std::abs(image.bound - group.bound) > kSameScaled * (1.0 + std::abs(group.bound))) {
      return false;
    }
    // Each side of `group` (a free block, a support, or none, as a
    // weight's second side) against a side of `image`: the free block's
    // image, any support, or none.
    auto side_maps = [&](int block, int row, int image_block, int image_row) {
      if (block < 0) return image_block < 0;
      if (row < 0) return image_block >= 0 && structure_.is_support(image_block);
      return image_row == problem_.row_of_block[map[block]];
    };
    const bool same_order = side_maps(group.block_a, group.row_a, image.block_a, image.row_a) &&
                            side_maps(group.block_b, group.row_b, image.block_b, image.row_b);
    const bool swapped = !same_order && side_maps(group.block_a, group.row_a, image.block_b, image.row_b) &&
                         side_maps(group.block_b, group.row_b, image.block_a, image.row_a);
    if (!same_order && !swapped) return false;
    const Effect image_a = image.on_a(problem_.block_rows);
    const Effect on_a = t * group.on_a(problem_.block_rows), on_b = t * group.on_b;
    const Effect& image_on_a = same_order ? image_a : image.on_b;
    const Effect& image_on_b = same_order ? image.on_b : image_a;
    for (const Eigen::Matrix4d& s : permutations_[static_cast<int>(group.kind)]) {
      if ((group.row_a < 0 || same_scaled(image_on_a * s, on_a)) &&
          (group.row_b < 0 || same_scaled(image_on_b * s, on_b))) {
        return true;
      }
    }
    return false;
  }

  const Structure& structure_;
  const EquilibriumProblem& problem_;
  double tolerance_;
  std::array<std::vector<Eigen::Matrix4d>, kGroupKinds> permutations_;  // per group kind
  PointGrid blocks_, vertices_;
};

bool searchable(const Structure& structure, const EquilibriumProblem& problem) {
  if (problem.block_rows != 6 || problem.has_floating_bodies() || !problem.junctions.empty()) return false;
  for (const ForceGroup& group : problem.groups) {
    if (group.kind != GroupKind::contact_vertex && group.kind != GroupKind::weight) return false;
  }
  for (int j = 0; j < structure.size(); ++j) {
    if (problem.row_of_block[j] >= 0) return true;
  }
  return false;
}

void assign_orbits(const Structure& structure, const EquilibriumProblem& problem, ProblemSymmetry& symmetry) {
  const int n = structure.size();
  symmetry.representative.assign(n, -1);
  symmetry.symmetry_of.assign(n, 0);
  for (int j = 0; j < n; ++j) {
    if (symmetry.representative[j] >= 0) continue;
    symmetry.representative[j] = j;
    if (problem.row_of_block[j] < 0) continue;
    for (size_t e = 1; e < symmetry.block_maps.size(); ++e) {
      const int member = symmetry.block_maps[e][j];
      if (symmetry.representative[member] < 0) {
        symmetry.representative[member] = j;
        symmetry.symmetry_of[member] = static_cast<int>(e);
      }
    }
  }
}

// Appends to symmetry.block_maps every turn about the vertical axis through
// the free blocks' mean centroid, and every mirror in a vertical plane
// through it, that maps `problem` onto itself.
void add_motions(const Structure& structure, const EquilibriumProblem& problem, ProblemSymmetry& symmetry) {
  // A symmetry permutes the free blocks, so it keeps their mean centroid:
  // the vertical axis passes through it.
  Vec3 axis = Vec3::Zero();
  int free_blocks = 0;
  for (int j = 0; j < structure.size(); ++j) {
    if (problem.row_of_block[j] < 0) continue;
    axis += structure.block(j).centroid();
    ++free_blocks;
  }
  axis /= free_blocks;
  axis.z() = 0.0;
  const double tolerance = kSamePosition * problem.length_unit;
  auto horizontal = [&](const Vec3& p) { return Vec2(p.x() - axis.x(), p.y() - axis.y()); };
  // The candidates map the free block farthest from the axis to the free
  // blocks of its mass at its height and distance: a rotation to each
  // other one, and the reflection in the plane halfway to each.
  int chosen = -1;
  for (int j = 0; j < structure.size(); ++j) {
    if (problem.row_of_block[j] < 0) continue;
    if (chosen < 0 || horizontal(structure.block(j).centroid()).norm() >
                          horizontal(structure.block(chosen).centroid()).norm() + tolerance) {
      chosen = j;
    }
  }
  const Vec3 c0 = structure.block(chosen).centroid();
  const double r0 = horizontal(c0).norm();
  if (r0 <= tolerance) return;
  const double angle0 = std::atan2(horizontal(c0).y(), horizontal(c0).x());
  const double mass = structure.block(chosen).mass();
  const SymmetrySearch motions(structure, problem);
  int candidates = 0;
  for (int j = 0; j < structure.size() && candidates < kMaxCandidates; ++j) {
    if (problem.row_of_block[j] < 0) continue;
    const Vec3 c = structure.block(j).centroid();
    if (std::abs(c.z() - c0.z()) > tolerance || std::abs(horizontal(c).norm() - r0) > tolerance ||
        std::abs(structure.block(j).mass() - mass) > kSameScaled * mass) {
      continue;
    }
    const double angle = std::atan2(horizontal(c).y(), horizontal(c).x());
    Mat3 rotation = Mat3::Identity(), reflection = Mat3::Identity();
    const double turn = angle - angle0, mirror = angle + angle0;  // mirror: twice the plane's angle
    rotation.topLeftCorner<2, 2>() << std::cos(turn), -std::sin(turn), std::sin(turn), std::cos(turn);
    reflection.topLeftCorner<2, 2>() << std::cos(mirror), std::sin(mirror), std::sin(mirror), -std::cos(mirror);
    for (const Mat3* q : {&rotation, &reflection}) {
      if (q == &rotation && j == chosen) continue;  // the identity
      ++candidates;
      // Motions that permute the blocks alike (an arch's mirror in its own
      // plane moves none) are one symmetry to the per-block analyses.
      std::vector<int> map = motions.block_map(axis, *q);
      if (!map.empty() && std::find(symmetry.block_maps.begin(), symmetry.block_maps.end(), map) ==
                              symmetry.block_maps.end()) {
        symmetry.block_maps.push_back(std::move(map));
      }
    }
  }
}

}  // namespace

ProblemSymmetry find_problem_symmetry(const Structure& structure, const EquilibriumProblem& problem, bool search) {
  ProblemSymmetry symmetry;
  std::vector<int> identity(structure.size(), -1);
  for (int j = 0; j < structure.size(); ++j) {
    if (problem.row_of_block[j] >= 0) identity[j] = j;
  }
  symmetry.block_maps.push_back(std::move(identity));
  if (search && searchable(structure, problem)) add_motions(structure, problem, symmetry);
  assign_orbits(structure, problem, symmetry);
  return symmetry;
}

}  // namespace ashlar
