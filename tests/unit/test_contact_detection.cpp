// Contact detection: counts and areas against what the geometry implies.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <atomic>
#include <map>
#include <thread>
#include <vector>

#include "geometry/block_builders.hpp"
#include "test_support.hpp"
#include "structure/structure.hpp"

using namespace ashlar;

namespace {

// The stack from the foundation issue: a ground slab and three offset boxes.
Structure three_block_stack() {
  Structure s;
  s.add(box({2, 1, 0.2}, {0, 0, -0.1}), true);
  for (int i = 1; i <= 3; ++i) s.add(box({1, 1, 0.5}, {0.1 * i, 0, 0.25 + 0.5 * (i - 1)}));
  return s;
}

// Running bond: even courses hold `bricks` whole bricks, odd courses a half
// brick at each end and bricks - 1 whole ones, so both wall ends are flush.
struct Wall {
  Structure structure;
  double brick_length, brick_height, thickness;
};

Wall running_bond_wall(int bricks, int courses) {
  Wall w{{}, 0.24, 0.07, 0.11};
  const double l = w.brick_length, h = w.brick_height, t = w.thickness;
  w.structure.add(box({bricks * l + 1.0, t + 0.2, 0.1}, {bricks * l / 2, 0, -0.05}), true, "ground");
  for (int c = 0; c < courses; ++c) {
    std::vector<double> edges;  // x positions of vertical joints, both ends included
    if (c % 2 == 0) {
      for (int i = 0; i <= bricks; ++i) edges.push_back(i * l);
    } else {
      edges.push_back(0.0);
      for (int i = 0; i < bricks; ++i) edges.push_back((i + 0.5) * l);
      edges.push_back(bricks * l);
    }
    for (size_t i = 0; i + 1 < edges.size(); ++i) {
      w.structure.add(box({edges[i + 1] - edges[i], t, h},
                          {0.5 * (edges[i] + edges[i + 1]), 0, (c + 0.5) * h}));
    }
  }
  return w;
}

double total_area(const std::vector<Interface>& interfaces) {
  double sum = 0.0;
  for (const Interface& f : interfaces) sum += f.area;
  return sum;
}

}  // namespace

TEST(ContactDetection, ThreeBlockStackExact) {
  const Structure s = three_block_stack();
  const std::shared_ptr<const std::vector<Interface>> found_list = s.interfaces();
  const std::vector<Interface>& found = *found_list;
  ASSERT_EQ(found.size(), 3u);
  const double expected_area[] = {1.0, 0.9, 0.9};
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(found[k].a, k);
    EXPECT_EQ(found[k].b, k + 1);
    EXPECT_NEAR(found[k].area, expected_area[k], 1e-14);
    EXPECT_EQ(found[k].vertices.size(), 4u);
    EXPECT_TRUE(found[k].normal.isApprox(Vec3::UnitZ()));
    EXPECT_NEAR(found[k].u.dot(found[k].normal), 0.0, 1e-15);
    EXPECT_TRUE(found[k].normal.cross(found[k].u).isApprox(found[k].v));
  }
  EXPECT_NEAR(found[0].center.x(), 0.1, 1e-14);
  EXPECT_NEAR(found[1].center.x(), 0.15, 1e-14);
  EXPECT_NEAR(found[0].center.z(), 0.0, 1e-14);
  EXPECT_NEAR(found[2].center.z(), 1.0, 1e-14);
}

TEST(ContactDetection, RunningBondWallCountsAndAreas) {
  const int bricks = 20, courses = 10;
  const Wall w = running_bond_wall(bricks, courses);
  const double l = w.brick_length, h = w.brick_height, t = w.thickness;
  ASSERT_EQ(w.structure.size(), 1 + 5 * 20 + 5 * 21);
  const std::shared_ptr<const std::vector<Interface>> found_list = w.structure.interfaces();
  const std::vector<Interface>& found = *found_list;
  // Head joints: 19 per even course, 20 per odd; bed joints: 40 pieces per
  // pair of courses (every half brick), and 20 on the ground.
  const int head = 5 * 19 + 5 * 20, bed = (courses - 1) * 2 * bricks, ground = bricks;
  int vertical = 0, horizontal = 0, on_ground = 0;
  for (const Interface& f : found) {
    if (f.a == 0) {
      ++on_ground;
      EXPECT_NEAR(f.area, l * t, 1e-15);
    } else if (std::abs(f.normal.z()) > 0.5) {
      ++horizontal;
      EXPECT_NEAR(f.area, 0.5 * l * t, 1e-15);
    } else {
      ++vertical;
      EXPECT_NEAR(f.area, h * t, 1e-15);
    }
    EXPECT_EQ(f.vertices.size(), 4u);
  }
  EXPECT_EQ(vertical, head);
  EXPECT_EQ(horizontal, bed);
  EXPECT_EQ(on_ground, ground);
  EXPECT_EQ(found.size(), static_cast<size_t>(head + bed + ground));
  EXPECT_NEAR(total_area(found), head * h * t + bed * 0.5 * l * t + ground * l * t, 1e-12);
}

TEST(ContactDetection, RigidMotionLeavesContactsUnchanged) {
  const Structure s = three_block_stack();
  const Vec3 axis = Vec3(0.3, -1.0, 0.7).normalized();
  const Eigen::AngleAxisd rotation(1.1, axis);
  const Vec3 offset(120.0, -40.0, 7.0);
  Structure moved;
  for (int i = 0; i < s.size(); ++i) {
    moved.add(std::make_shared<const Block>(
                  s.block(i).rotated(axis, 1.1, Vec3::Zero()).translated(offset)),
              s.is_support(i));
  }
  const std::shared_ptr<const std::vector<Interface>> a_list = s.interfaces();
  const std::vector<Interface>& a = *a_list;
  const std::shared_ptr<const std::vector<Interface>> b_list = moved.interfaces();
  const std::vector<Interface>& b = *b_list;
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_NEAR(a[k].area, b[k].area, 1e-12);
    EXPECT_LE((rotation * a[k].normal - b[k].normal).norm(), 1e-12);
    EXPECT_LE((rotation * a[k].center + offset - b[k].center).norm(), 1e-12);
  }
}

TEST(ContactDetection, NonConvexFaceOnBox) {
  // L-shaped prism (footprint area 5) resting on a 2 x 2 box: the contact is
  // the L clipped to the box's top, the 2 x 2 square minus its 1 x 1 corner.
  const std::vector<Vec3> l = {{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {1, 1, 0}, {1, 3, 0}, {0, 3, 0}};
  Structure s;
  s.add(box({2, 2, 1}, {1, 1, -0.5}), true);
  s.add(std::make_shared<const Block>(make_prism(l, {0, 0, 0.5})));
  const std::shared_ptr<const std::vector<Interface>> found_list = s.interfaces();
  const std::vector<Interface>& found = *found_list;
  ASSERT_EQ(found.size(), 1u);
  EXPECT_NEAR(found[0].area, 3.0, 1e-12);
  EXPECT_EQ(found[0].vertices.size(), 6u);
  EXPECT_NEAR(found[0].center.x(), (4.0 * 1.0 - 1.0 * 1.5) / 3.0, 1e-12);
}

TEST(ContactDetection, TwoFeetOnOnePlaneGiveTwoInterfaces) {
  // An arch-like U standing on both legs: one plane, two separate contacts.
  const std::vector<Vec3> u = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {2, 2, 0},
                               {2, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}};
  Structure s;
  s.add(box({5, 5, 1}, {1.5, 1.5, -0.5}), true);
  // The polygon lies in the x-y plane; stand it up so that y becomes z.
  const Block standing =
      make_prism(u, {0, 0, 1}).rotated(Vec3::UnitX(), M_PI / 2, Vec3::Zero()).translated({0, 1, 0});
  s.add(std::make_shared<const Block>(standing));
  const std::shared_ptr<const std::vector<Interface>> found_list = s.interfaces();
  const std::vector<Interface>& found = *found_list;
  ASSERT_EQ(found.size(), 2u);
  EXPECT_NEAR(found[0].area, 1.0, 1e-12);
  EXPECT_NEAR(found[1].area, 1.0, 1e-12);
  EXPECT_LT(found[0].center.x(), found[1].center.x());
}

TEST(ContactDetection, NearCoplanarWithinAndOutsideTolerance) {
  ContactOptions options;
  options.tolerance = 1e-6;
  for (double gap : {0.0, 5e-7, -5e-7, 2e-6, -2e-6}) {
    Structure s;
    s.add(box({1, 1, 1}, {0, 0, -0.5}), true);
    s.add(box({1, 1, 1}, {0.2, 0, 0.5 + gap}));
    EXPECT_EQ(s.interfaces(options)->size(), std::abs(gap) <= 1e-6 ? 1u : 0u) << "gap " << gap;
  }
  for (double tilt : {1e-7, 1e-5}) {  // radians; gap at the far edge ~ tilt * 1 m
    Structure s;
    s.add(box({1, 1, 1}, {0, 0, -0.5}), true);
    s.add(std::make_shared<const Block>(
        make_box({1, 1, 1}, {0, 0, 0.5}).rotated(Vec3::UnitY(), tilt, {0, 0, 0})));
    EXPECT_EQ(s.interfaces(options)->size(), tilt < 1e-6 ? 1u : 0u) << "tilt " << tilt;
  }
}

// Two copies of one joint (as an imprecise model holds it): the interface
// is the polygon of the paired vertices' midpoints on its own plane, with the
// whole joint's area, where intersecting the copies would lose a strip.
TEST(ContactDetection, TwoCopiesOfOneJointMeetOnTheirMidPlane) {
  ContactOptions options;
  options.tolerance = 0.005;
  {  // shifted by (0.002, -0.001) and lifted 0.0006: the intersection is 0.998 x 0.999
    Structure s;
    s.add(box({1, 1, 1}, {0, 0, -0.5}), true);
    s.add(box({1, 1, 1}, {0.002, -0.001, 0.5006}));
    const std::shared_ptr<const std::vector<Interface>> found_list = s.interfaces(options);
    const std::vector<Interface>& found = *found_list;
    ASSERT_EQ(found.size(), 1u);
    EXPECT_TRUE(found[0].on_mid_plane);
    EXPECT_NEAR(found[0].area, 1.0, 1e-12);
    EXPECT_NEAR((found[0].normal - Vec3::UnitZ()).norm(), 0.0, 1e-12);
    EXPECT_NEAR((found[0].center - Vec3(0.001, -0.0005, 0.0003)).norm(), 0.0, 1e-12);
    for (const Vec3& x : found[0].vertices) EXPECT_NEAR(x.z(), 0.0003, 1e-12);
  }
  {  // tilted by theta about the x axis: the midpoints lie on the plane tilted
     // by theta / 2, their square foreshortened to cos(theta / 2) across it
    const double theta = 0.004;
    Structure s;
    s.add(box({1, 1, 1}, {0, 0, -0.5}), true);
    s.add(std::make_shared<const Block>(make_box({1, 1, 1}, {0, 0, 0.5}).rotated(Vec3::UnitX(), theta, {0, 0, 0})));
    const std::shared_ptr<const std::vector<Interface>> found_list = s.interfaces(options);
    const std::vector<Interface>& found = *found_list;
    ASSERT_EQ(found.size(), 1u);
    EXPECT_TRUE(found[0].on_mid_plane);
    EXPECT_NEAR(found[0].area, std::cos(theta / 2), 1e-12);
    EXPECT_NEAR((found[0].normal - Vec3(0, -std::sin(theta / 2), std::cos(theta / 2))).norm(), 0.0, 1e-12);
  }
  {  // a vertex further apart than the tolerance: the copies are cut as other faces
    Structure s;
    s.add(box({1, 1, 1}, {0, 0, -0.5}), true);
    s.add(box({1, 1, 1}, {0.006, 0, 0.5}));
    const std::shared_ptr<const std::vector<Interface>> found_list = s.interfaces(options);
    const std::vector<Interface>& found = *found_list;
    ASSERT_EQ(found.size(), 1u);
    EXPECT_FALSE(found[0].on_mid_plane);
    EXPECT_NEAR(found[0].area, 0.994, 1e-12);
  }
  {  // coincident copies: the same polygon, cut as before
    Structure s;
    s.add(box({1, 1, 1}, {0, 0, -0.5}), true);
    s.add(box({1, 1, 1}, {0, 0, 0.5}));
    const std::shared_ptr<const std::vector<Interface>> found_list = s.interfaces(options);
    const std::vector<Interface>& found = *found_list;
    ASSERT_EQ(found.size(), 1u);
    EXPECT_FALSE(found[0].on_mid_plane);
    EXPECT_NEAR(found[0].area, 1.0, 1e-12);
  }
}

TEST(ContactDetection, EdgeAndCornerTouchesAreNotContacts) {
  Structure s;
  s.add(box({1, 1, 1}, {0, 0, 0}));
  s.add(box({1, 1, 1}, {1, 0, 1}));  // shares only an edge with the first
  s.add(box({1, 1, 1}, {1, 1, -1}));  // shares only a corner with the first
  EXPECT_TRUE(s.interfaces()->empty());
}

TEST(ContactDetection, ListsHeldStayValidWhenOtherOptionsAreAsked) {
  // The cache holds one set of options; a list taken before another set is
  // asked for is still whole (under the sanitizers, never freed memory).
  const Structure s = three_block_stack();
  ContactOptions strict;
  strict.tolerance = 1e-9;
  ContactOptions loose;
  loose.tolerance = 1e-3;
  const std::shared_ptr<const std::vector<Interface>> held = s.interfaces(strict);
  const std::vector<Interface> copy = *held;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(s.interfaces(loose)->size(), 3u);
  ASSERT_EQ(held->size(), copy.size());
  for (size_t i = 0; i < copy.size(); ++i) {
    EXPECT_EQ((*held)[i].a, copy[i].a);
    EXPECT_EQ((*held)[i].area, copy[i].area);
  }
}

TEST(ContactDetection, ConstUseFromSeveralThreadsIsSafe) {
  // Four threads ask one structure for two sets of options in turn: every
  // answer is whole (the sanitizer build checks the memory).
  const Structure s = three_block_stack();
  std::atomic<int> wrong{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int k = 0; k < 200; ++k) {
        ContactOptions options;
        options.tolerance = (k + t) % 2 ? 1e-3 : 1e-9;
        if (s.interfaces(options)->size() != 3u) ++wrong;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(wrong.load(), 0);
}

TEST(ContactDetection, CacheIsReusedUntilTheStructureChanges) {
  Structure s = three_block_stack();
  const std::shared_ptr<const std::vector<Interface>> first = s.interfaces();
  EXPECT_EQ(first, s.interfaces());  // the cached list itself
  EXPECT_EQ(s.interfaces()->size(), 3u);
  s.add(box({1, 1, 0.5}, {0.4, 0, 1.75}));
  EXPECT_EQ(s.interfaces()->size(), 4u);
  ContactOptions loose;
  loose.tolerance = 1e-3;
  EXPECT_EQ(s.interfaces(loose)->size(), 4u);
}

TEST(ContactDetection, RelativeToleranceScalesWithTheModel) {
  for (double scale : {1e-3, 1.0, 1e3}) {
    Structure s;
    s.add(box(Vec3(1, 1, 1) * scale, Vec3(0, 0, -0.5) * scale), true);
    s.add(box(Vec3(1, 1, 1) * scale, Vec3(0.25, 0, 0.5 + 1e-8) * scale));
    ASSERT_EQ(s.interfaces()->size(), 1u) << "scale " << scale;
    EXPECT_NEAR((*s.interfaces())[0].area, 0.75 * scale * scale, 1e-12 * scale * scale);
  }
}

TEST(MissedContacts, AColumnWithGapsSaysWhichToleranceClosesEachGap) {
  // Ground (block 0), then three 0.3 m cubes (1-3) stacked with gaps of 0.5,
  // 0.2 and 1 mm, and a fourth (4) 0.15 m beside the column, beyond reach.
  Structure s;
  s.add(box({1, 1, 0.2}, {0, 0, -0.1}), true);
  const double gaps[3] = {0.0005, 0.0002, 0.001};
  double z = 0.0;
  for (double gap : gaps) {
    z += gap;
    s.add(box({0.3, 0.3, 0.3}, {0, 0, z + 0.15}));
    z += 0.3;
  }
  s.add(box({0.3, 0.3, 0.3}, {0.45, 0, 0.8}));
  const double reach = 0.01 * s.bounds().diagonal();
  ASSERT_LT(reach, 0.1);
  const std::vector<MissedContact> missed = s.missed_contacts({1, 2, 3, 4}, reach);
  ASSERT_EQ(missed.size(), 4u);
  // Block 1 is 0.5 mm above the ground and 0.2 mm below block 2: its
  // nearest miss is block 2. Block 3 is 1 mm above block 2.
  EXPECT_EQ(missed[0].block, 2);
  EXPECT_NEAR(missed[0].tolerance, 0.0002, 1e-3 * 0.0002 + 1e-9);
  EXPECT_EQ(missed[1].block, 1);
  EXPECT_NEAR(missed[1].tolerance, 0.0002, 1e-3 * 0.0002 + 1e-9);
  EXPECT_EQ(missed[2].block, 2);
  EXPECT_NEAR(missed[2].tolerance, 0.001, 1e-3 * 0.001 + 1e-9);
  EXPECT_EQ(missed[3].block, -1);
  EXPECT_TRUE(std::isinf(missed[3].tolerance));
  // Each closing tolerance does close that gap: an analysis with the
  // largest one finds all three.
  ContactOptions closing;
  closing.tolerance = missed[2].tolerance;
  EXPECT_EQ(s.interfaces(closing)->size(), 3u);
}
