// The symmetries of an equilibrium problem (analysis/problem_symmetry.hpp)
// and the interface frames they rest on (structure/interface.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "analysis/problem_symmetry.hpp"
#include "test_support.hpp"

using namespace ashlar;

TEST(ProblemSymmetry, AnArchHasItsMirror) {
  // Nine voussoirs in the x-z plane: the reflection x -> -x takes voussoir
  // i to 8 - i; the keystone is its own image.
  const Structure s = semicircular_arch(9, 0.8);
  const EquilibriumProblem problem = build_equilibrium_problem(s, EquilibriumOptions{});
  const ProblemSymmetry symmetry = find_problem_symmetry(s, problem);
  ASSERT_EQ(symmetry.block_maps.size(), 2u);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(symmetry.block_maps[0][i], i);
    EXPECT_EQ(symmetry.block_maps[1][i], 8 - i);
    EXPECT_EQ(symmetry.representative[i], std::min(i, 8 - i));
    EXPECT_EQ(symmetry.block_maps[symmetry.symmetry_of[i]][symmetry.representative[i]], i);
  }
  for (int support : {9, 10}) {
    EXPECT_EQ(symmetry.block_maps[1][support], -1);
    EXPECT_EQ(symmetry.representative[support], support);
  }
}

TEST(ProblemSymmetry, WhatBreaksTheProblemsSymmetryLeavesTheIdentity) {
  const EquilibriumOptions options;
  // Not searched.
  Structure s = semicircular_arch(9, 0.8);
  EXPECT_EQ(find_problem_symmetry(s, build_equilibrium_problem(s, options), false).block_maps.size(), 1u);
  // A load on one side: the blocks' shapes are symmetric, the problem not.
  Structure loaded = semicircular_arch(9, 0.8);
  loaded.add_load({2, Vec3(0, 0, -100.0), loaded.block(2).centroid()});
  EXPECT_EQ(find_problem_symmetry(loaded, build_equilibrium_problem(loaded, options)).block_maps.size(), 1u);
  // A load and its mirror image keep it.
  loaded.add_load({6, Vec3(0, 0, -100.0), loaded.block(6).centroid()});
  EXPECT_EQ(find_problem_symmetry(loaded, build_equilibrium_problem(loaded, options)).block_maps.size(), 2u);
  // A hexagonal friction pyramid (a corner on u) is symmetric under
  // u -> -u and v -> -v, all the mirror asks of the arch's joints.
  EquilibriumOptions hexagonal;
  hexagonal.friction_sides = 6;
  EXPECT_EQ(find_problem_symmetry(s, build_equilibrium_problem(s, hexagonal)).block_maps.size(), 2u);
  // The same arch analysed in its plane: planar problems are not searched.
  Structure planar = semicircular_arch(9, 0.8);
  planar.set_planar(true);
  EXPECT_EQ(find_problem_symmetry(planar, build_equilibrium_problem(planar, options)).block_maps.size(), 1u);
}

TEST(InterfaceFrame, OfEquallyLongEdgesTheLowest) {
  // A trapezoid in the x-z plane whose bottom (z = 0) and top edges are
  // both 1 m long and not parallel, as a dome's head joints are: u runs
  // along the bottom one, whichever vertex the polygon starts at.
  const Vec3 top_left(1.2, 0, 0.5);
  const Vec3 top_right = top_left + Vec3(std::cos(0.1), 0, -std::sin(0.1));
  const std::vector<Vec3> polygon = {{1, 0, 0}, {2, 0, 0}, top_right, top_left};
  for (size_t start = 0; start < polygon.size(); ++start) {
    Interface contact;
    contact.normal = Vec3(0, -1, 0);
    for (size_t k = 0; k < polygon.size(); ++k) contact.vertices.push_back(polygon[(start + k) % polygon.size()]);
    set_frame_along_longest_edge(contact);
    EXPECT_NEAR(contact.u.x(), 1.0, 1e-12) << start;
    EXPECT_NEAR(contact.v.dot(contact.u), 0.0, 1e-12) << start;
  }
}
