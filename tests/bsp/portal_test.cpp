// Portals of paper §3: on both cells' boundaries, never over a patch, tiling each boundary face
// with its coaffine patches, and the only way a free segment passes from cell to cell.
#include <gtest/gtest.h>

#include "bsp/bsp_oracle.h"
#include "bsp/bsp_scenes.h"
#include "bsp/subdivision.h"

namespace gv {
namespace {

using namespace bsptest;

TEST(PortalInvariants, OnePatch) {
  const Scene s = onePatch();
  const Subdivision sub = buildSubdivision(s);
  expectInvariants(s, sub, 1);
  ASSERT_EQ(sub.cells.size(), 2u);
  // The section of the root minus the patch: a ring around it, so the two halves are linked,
  // and the portals' area is the section's minus the patch's.
  ASSERT_FALSE(sub.portals.empty());
  double area = 0;
  for (const Portal& p : sub.portals) area += areaOf(p.polygon.vertices);
  const Aabb root = cellsBounds(sub);
  const Vec3 e = root.extent();
  EXPECT_NEAR(area, e.x * e.y - 2.0, 1e-9 * e.x * e.y);
}

TEST(PortalInvariants, ClosedRoomHasNoWayOut) {
  const Scene s = closedRoom();
  const Subdivision sub = buildSubdivision(s);
  expectInvariants(s, sub, 2);
  const int inside = cellStrictlyAt(sub, {2, 2, 1.5}, 1e-6);
  const int outside = cellStrictlyAt(sub, {-0.25, -0.25, -0.25}, 1e-6);
  const int inWall = cellStrictlyAt(sub, {-0.1, 2, 1.5}, 1e-6);
  ASSERT_GE(inside, 0);
  ASSERT_GE(outside, 0);
  ASSERT_GE(inWall, 0);
  const std::vector<bool> fromInside = reachable(sub, static_cast<uint32_t>(inside));
  EXPECT_FALSE(fromInside[static_cast<size_t>(outside)]);
  EXPECT_FALSE(fromInside[static_cast<size_t>(inWall)]);
  // The room's air is one cell (its six walls cover every section), and the solid walls are
  // linked neither to the room nor to the outside.
  EXPECT_EQ(std::count(fromInside.begin(), fromInside.end(), true), 1);
  const std::vector<bool> fromWall = reachable(sub, static_cast<uint32_t>(inWall));
  EXPECT_FALSE(fromWall[static_cast<size_t>(outside)]);
}

TEST(PortalInvariants, TwoRoomsMeetOnlyInTheDoor) {
  const Scene s = twoRoomsWithDoor();
  const Subdivision sub = buildSubdivision(s);
  expectInvariants(s, sub, 3);
  auto inRoom = [&](uint32_t cell, double x0, double x1) {
    const Vec3 c = sub.cells[cell].shape.centroid();
    return c.x > x0 && c.x < x1 && c.y > 0 && c.y < 4 && c.z > 0 && c.z < 3;
  };
  auto inA = [&](uint32_t c) { return inRoom(c, 0, 4); };
  auto inB = [&](uint32_t c) { return inRoom(c, 4.2, 8.2); };
  const int a = cellStrictlyAt(sub, {0.5, 0.5, 1.5}, 1e-6);
  const int b = cellStrictlyAt(sub, {7.5, 3.5, 1.5}, 1e-6);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  EXPECT_TRUE(reachable(sub, static_cast<uint32_t>(a))[static_cast<size_t>(b)]);

  // Every portal leaving room A's air (or B's) lies in the door opening, and together those
  // portals fill it exactly.
  double doorAreaA = 0, doorAreaB = 0;
  for (const Portal& p : sub.portals) {
    for (auto [room, x, area] : {std::tuple{0, 4.0, &doorAreaA}, std::tuple{1, 4.2, &doorAreaB}}) {
      auto inside = [&](uint32_t c) { return room == 0 ? inA(c) : inB(c); };
      if (inside(p.back) == inside(p.front)) continue;
      for (const Vec3& v : p.polygon.vertices) {
        EXPECT_NEAR(v.x, x, 1e-9);
        EXPECT_GE(v.y, kDoorY0 - 1e-9);
        EXPECT_LE(v.y, kDoorY1 + 1e-9);
        EXPECT_GE(v.z, -1e-9);
        EXPECT_LE(v.z, kDoorTop + 1e-9);
      }
      *area += areaOf(p.polygon.vertices);
    }
  }
  const double door = (kDoorY1 - kDoorY0) * kDoorTop;
  EXPECT_NEAR(doorAreaA, door, 1e-9);
  EXPECT_NEAR(doorAreaB, door, 1e-9);
  // No cell of either room is linked to the outside or to a wall's inside.
  const int outside = cellStrictlyAt(sub, {-0.5, -0.5, -0.5}, 1e-6);
  ASSERT_GE(outside, 0);
  EXPECT_FALSE(reachable(sub, static_cast<uint32_t>(a))[static_cast<size_t>(outside)]);
}

TEST(PortalSegments, FreeSegmentsCrossCellsOnlyThroughPortals) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const Scene s = randomClutter(seed, 6, 6);
    const Subdivision sub = buildSubdivision(s);
    expectInvariants(s, sub, seed);
    const int crossings = expectSegmentsCrossOnlyThroughPortals(s, sub, seed, 300);
    EXPECT_GT(crossings, 100) << "the check must not be vacuous";
  }
}

TEST(PortalSegments, TwoRoomsAndMessyScene) {
  for (const Scene& s : {twoRoomsWithDoor(), messy()}) {
    const Subdivision sub = buildSubdivision(s);
    const int crossings = expectSegmentsCrossOnlyThroughPortals(s, sub, 9, 2000);
    EXPECT_GT(crossings, 50);
  }
}

}  // namespace
}  // namespace gv
