// Tests for the furnished room: valid closed geometry, the documented counts, and bad options.
#include "generators/furnished_room.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "generators/scene_oracle.h"

namespace gv {
namespace {

TEST(FurnishedRoomTest, PatchesAreValidAndCountsAsDocumented) {
  const Scene scene = generateFurnishedRoom();
  EXPECT_EQ(scene.patches.size(), 224u);
  EXPECT_EQ(scene.emitterCount(), 2u);
  const double scale = scene.bounds().diagonal();
  for (const Patch& p : scene.patches) ASSERT_TRUE(testing::isValidPatch(p, scale));
  // One box (6 faces) per chair part less: 6 boxes per chair.
  EXPECT_EQ(generateFurnishedRoom({.chairs = 1, .bookcase = false}).patches.size(),
            6u + 2u + 30u + 36u);
}

// The six room faces face inward and the furniture solids outward, so the divergence theorem
// gives the room's volume minus the furniture's: positive and just under width x depth x height.
TEST(FurnishedRoomTest, SurfacesBoundTheAirInside) {
  const Scene scene = generateFurnishedRoom();
  const double air = -testing::divergenceVolume(scene);
  EXPECT_GT(air, 0.97 * 6 * 5 * 3);
  EXPECT_LT(air, 6 * 5 * 3);
}

// Every furniture part stands on the floor or on another part: a downward segment from the
// middle of the table top and of each chair seat hits furniture before the floor.
TEST(FurnishedRoomTest, FurnitureIsSupported) {
  const Scene scene = generateFurnishedRoom();
  EXPECT_TRUE(testing::segmentBlocked(scene, {3, 2.5, 2.5}, {3, 2.5, 0.5}));        // table top
  EXPECT_TRUE(testing::segmentBlocked(scene, {3, 1.75, 0.6}, {3, 1.75, 0.01}));     // a seat
  EXPECT_FALSE(testing::segmentBlocked(scene, {0.5, 0.5, 2.5}, {0.5, 0.5, 0.01}));  // free floor
}

TEST(FurnishedRoomTest, RejectsRoomsTooSmallOrAbsurd) {
  EXPECT_THROW(generateFurnishedRoom({.width = 2}), std::invalid_argument);
  EXPECT_THROW(generateFurnishedRoom({.chairs = 5}), std::invalid_argument);
  EXPECT_THROW(generateFurnishedRoom({.height = 1e9}), std::invalid_argument);
  EXPECT_THROW(generateFurnishedRoom({.lightEmission = -1}), std::invalid_argument);
}

}  // namespace
}  // namespace gv
