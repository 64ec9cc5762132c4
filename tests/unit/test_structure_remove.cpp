// Structure::remove: the blocks after the removed one and every reference
// to them (loads, cable ends, explicit interfaces, names) move down one
// index; what refers to the removed block goes with it; the cached contacts
// are recomputed.
#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace ashlar;

namespace {

// A column of four unit cubes on a ground slab: ground (0), cubes 1..4 from
// z = 0 up. Loads on cubes 1, 2 and 4; a cable from the ground to cube 2
// and one from cube 1 to cube 4; an explicit interface between cubes 3 and 4.
Structure three_boxes() {
  Structure s;
  s.add(box({3, 3, 1}, {0, 0, -0.5}), true, "ground");
  for (int k = 1; k <= 4; ++k) s.add(box({1, 1, 1}, {0, 0, k - 0.5}), false, "cube " + std::to_string(k));
  s.add_load({1, Vec3(10, 0, 0), Vec3(0, 0, 0.5)});
  s.add_load({2, Vec3(20, 0, 0), Vec3(0, 0, 1.5)});
  s.add_load({4, Vec3(40, 0, 0), Vec3(0, 0, 3.5)});
  Cable ground_to_2, one_to_4;
  ground_to_2.from = {0, Vec3(1.5, 0, 0)};
  ground_to_2.to = {2, Vec3(0.5, 0, 1.5)};
  one_to_4.from = {1, Vec3(0.5, 0, 0.5)};
  one_to_4.to = {4, Vec3(0.5, 0, 3.5)};
  s.add_cable(ground_to_2);
  s.add_cable(one_to_4);
  s.add_interface(3, 4, {{Vec3(-0.5, -0.5, 3), Vec3(0.5, -0.5, 3), Vec3(0.5, 0.5, 3), Vec3(-0.5, 0.5, 3)}});
  return s;
}

}  // namespace

TEST(StructureRemove, RenumbersWhatFollowsAndDropsWhatReferredToTheBlock) {
  Structure s = three_boxes();
  // Contacts before, cached: ground-1, 1-2, 2-3 detected, 3-4 explicit.
  ASSERT_EQ(s.interfaces()->size(), 4u);
  const StructureBlock removed = s.remove(2);  // cube 2
  EXPECT_EQ(removed.name, "cube 2");
  EXPECT_DOUBLE_EQ(removed.block->volume(), 1.0);
  ASSERT_EQ(s.size(), 4);
  EXPECT_EQ(s.name(2), "cube 3");
  EXPECT_EQ(s.find("cube 4"), 3);
  EXPECT_EQ(s.find("cube 2"), -1);
  EXPECT_EQ(s.find("ground"), 0);
  // The load on cube 2 went with it; cube 4's is now on block 3.
  ASSERT_EQ(s.loads().size(), 2u);
  EXPECT_EQ(s.loads()[0].block, 1);
  EXPECT_EQ(s.loads()[0].force.x(), 10.0);
  EXPECT_EQ(s.loads()[1].block, 3);
  EXPECT_EQ(s.loads()[1].force.x(), 40.0);
  // The cable to cube 2 went with it; the other now joins blocks 1 and 3.
  ASSERT_EQ(s.cables().size(), 1u);
  EXPECT_EQ(s.cables()[0].from.block, 1);
  EXPECT_EQ(s.cables()[0].to.block, 3);
  // Contacts recomputed: ground-cube 1 and the explicit one, now 2-3; cube 1
  // and cube 3 are a metre apart.
  const auto contacts = s.interfaces();
  ASSERT_EQ(contacts->size(), 2u);
  EXPECT_EQ((*contacts)[0].a, 0);
  EXPECT_EQ((*contacts)[0].b, 1);
  EXPECT_EQ((*contacts)[1].a, 2);
  EXPECT_EQ((*contacts)[1].b, 3);
  EXPECT_TRUE((*contacts)[1].is_explicit);
  EXPECT_EQ(s.explicit_interfaces().size(), 1u);
}

TEST(StructureRemove, DropsTheExplicitInterfacesOfTheBlockAndKeepsTheRestSeparate) {
  Structure s = three_boxes();
  s.remove(4);  // cube 4: its load, the cable to it and the explicit interface go
  EXPECT_EQ(s.size(), 4);
  EXPECT_EQ(s.loads().size(), 2u);
  ASSERT_EQ(s.cables().size(), 1u);
  EXPECT_EQ(s.cables()[0].to.block, 2);
  EXPECT_TRUE(s.explicit_interfaces().empty());
  // Cubes 2 and 3 touch again by detection: ground-1, 1-2, 2-3.
  EXPECT_EQ(s.interfaces()->size(), 3u);
  // Adding a block afterwards numbers it after the others and finds it by name.
  EXPECT_EQ(s.add(box({1, 1, 1}, {0, 0, 3.5}), false, "cube 5"), 4);
  EXPECT_EQ(s.find("cube 5"), 4);
  EXPECT_EQ(s.interfaces()->size(), 4u);
}

TEST(StructureRemove, RefusesABadIndex) {
  Structure s = three_boxes();
  EXPECT_EQ(error_of([&] { s.remove(5); }), "remove: block 6 does not exist (the structure has 5 blocks)");
  EXPECT_EQ(error_of([&] { s.remove(-1); }), "remove: block 0 does not exist (the structure has 5 blocks)");
  EXPECT_EQ(s.size(), 5);
}
