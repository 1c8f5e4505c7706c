// The subdivision as a whole (paper §3, §7.1): office buildings whose sealed rooms stay apart,
// messy input, huge and tiny coordinates, and the statistics.
#include "bsp/subdivision.h"

#include <gtest/gtest.h>

#include "bsp/bsp_oracle.h"
#include "bsp/bsp_scenes.h"
#include "generators/office.h"

namespace gv {
namespace {

using namespace bsptest;

bool inside(const Aabb& box, const Vec3& p) {
  return p.x > box.lo.x && p.x < box.hi.x && p.y > box.lo.y && p.y < box.hi.y && p.z > box.lo.z &&
         p.z < box.hi.z;
}

/// A point of room (floor, row, column)'s air clear of furniture and lights: mid-width, 0.6 m
/// from the door wall, 1.4 m up.
Vec3 roomPoint(const OfficeOptions& o, int floor, int row, int column) {
  const Aabb r = officeRoomInterior(o, floor, row, column);
  return {0.5 * (r.lo.x + r.hi.x), r.lo.y + 0.6, r.lo.z + 1.4};
}

/// Which rooms and corridors the air of room (0, 0, 0) reaches through portals.
struct Reach {
  int rooms = 0, corridors = 0;
};
Reach reachFromFirstRoom(const OfficeOptions& o, const Subdivision& sub) {
  const int start = cellStrictlyAt(sub, roomPoint(o, 0, 0, 0), 1e-6);
  EXPECT_GE(start, 0);
  const std::vector<bool> seen = reachable(sub, static_cast<uint32_t>(std::max(start, 0)));
  Reach r;
  for (int f = 0; f < o.floors; ++f) {
    for (int row = 0; row < o.rows; ++row) {
      const int corridor = cellStrictlyAt(
          sub,
          [&] {
            const Aabb c = officeCorridorInterior(o, f, row);
            return Vec3{0.5 * (c.lo.x + c.hi.x), 0.5 * (c.lo.y + c.hi.y), c.lo.z + 1.4};
          }(),
          1e-6);
      r.corridors += corridor >= 0 && seen[static_cast<size_t>(corridor)];
      for (int col = 0; col < o.columns; ++col) {
        if (f == 0 && row == 0 && col == 0) continue;
        const int cell = cellStrictlyAt(sub, roomPoint(o, f, row, col), 1e-6);
        r.rooms += cell >= 0 && seen[static_cast<size_t>(cell)];
      }
    }
  }
  return r;
}

TEST(SubdivisionOffice, SealedRoomsAreNotConnected) {
  OfficeOptions o;
  o.doors = false;
  o.windows = false;
  const Scene s = generateOffice(o);
  const Subdivision sub = buildSubdivision(s);
  const Reach r = reachFromFirstRoom(o, sub);
  EXPECT_EQ(r.rooms, 0);
  EXPECT_EQ(r.corridors, 0);
  // Nothing the room reaches has its centroid outside the room.
  const int start = cellStrictlyAt(sub, roomPoint(o, 0, 0, 0), 1e-6);
  const std::vector<bool> seen = reachable(sub, static_cast<uint32_t>(start));
  const Aabb room = officeRoomInterior(o, 0, 0, 0);
  for (size_t c = 0; c < sub.cells.size(); ++c) {
    if (seen[c]) {
      EXPECT_TRUE(inside(room, sub.cells[c].shape.centroid())) << "cell " << c;
    }
  }
}

TEST(SubdivisionOffice, WindowsJoinRoomsOfARowButNotTheCorridor) {
  OfficeOptions o;
  o.doors = false;
  const Subdivision sub = buildSubdivision(generateOffice(o));
  const Reach r = reachFromFirstRoom(o, sub);
  EXPECT_EQ(r.rooms, o.columns - 1);  // its row, through the interior windows
  EXPECT_EQ(r.corridors, 0);
}

TEST(SubdivisionOffice, DoorsConnectEveryRoomOfAStorey) {
  OfficeOptions o;
  o.floors = 2;
  const Scene s = generateOffice(o);
  const Subdivision sub = buildSubdivision(s);
  const Reach r = reachFromFirstRoom(o, sub);
  // The rooms of its row (doors and windows) and its row's corridor; the next row's corridor is
  // behind this row's back wall and storeys are separated by slabs (no stairs).
  EXPECT_EQ(r.corridors, 1);
  EXPECT_EQ(r.rooms, o.columns - 1);
}

TEST(SubdivisionOffice, DefaultOfficeKeepsEveryInvariant) {
  const Scene s = generateOffice();
  const Subdivision sub = buildSubdivision(s);
  expectInvariants(s, sub, 4, 200);
  EXPECT_GT(expectSegmentsCrossOnlyThroughPortals(s, sub, 4, 1500), 100);
  const SubdivisionStats& st = sub.stats;
  EXPECT_EQ(st.cells, sub.cells.size());
  EXPECT_EQ(st.portals, sub.portals.size());
  EXPECT_GT(st.meanFacesPerCell, 4);
  EXPECT_GT(st.meanCoaffinePatchesPerCell, 0);
  // Every patch is recorded by some cell, on whose boundary (or inside which) it lies.
  std::vector<bool> recorded(s.patches.size(), false);
  for (const Cell& c : sub.cells)
    for (uint32_t p : c.patches) recorded[p] = true;
  EXPECT_EQ(std::count(recorded.begin(), recorded.end(), false), 0);
}

TEST(SubdivisionDegenerate, MessyInputKeepsTheInvariants) {
  const Scene s = messy();
  ASSERT_EQ(s.patches.size(), 11u);  // the sliver survived the builder
  const Subdivision sub = buildSubdivision(s);
  expectInvariants(s, sub, 5, 1000);
  // The overlapping quads in z = 0 are opaque where any of them is: no portal crosses their union.
  for (const Portal& p : sub.portals) {
    const Vec3 c = p.polygon.centroid();
    if (std::abs(c.z) > 1e-9 || std::abs(p.polygon.normal().z) < 0.99) continue;
    const bool inUnion = (c.x > 0 && c.x < 2 && c.y > 0 && c.y < 2) ||
                         (c.x > 1 && c.x < 3 && c.y > 1 && c.y < 3) ||
                         (c.x > 0.5 && c.x < 2.5 && c.y > 0.5 && c.y < 2.5);
    EXPECT_FALSE(inUnion) << c;
  }
}

TEST(SubdivisionDegenerate, SeededRandomClutter) {
  for (uint32_t seed = 10; seed < 16; ++seed) {
    const Scene s = randomClutter(seed, 10, 10);
    const Subdivision sub = buildSubdivision(s);
    expectInvariants(s, sub, seed, 200);
    EXPECT_GT(sub.cells.size(), 20u) << "the generator should not be trivial";
    EXPECT_GT(sub.portals.size(), 20u);
  }
}

TEST(SubdivisionDegenerate, TriangleSoupWithSharedEdgesAndCrossings) {
  // Random triangles, some sharing an edge with the previous one (a fan, folded), many crossing.
  std::mt19937 rng(21);
  SceneMaker m(boxOf({0, 0, 0}, {10, 10, 10}));
  Vec3 a{5, 5, 5}, b{6, 5, 5};
  auto point = [&] { return Vec3{uniform(rng, 1, 9), uniform(rng, 1, 9), uniform(rng, 1, 9)}; };
  for (int i = 0; i < 40; ++i) {
    const Vec3 c = point();
    m.builder.addPolygon({a, b, c}, m.grey);
    if (i % 3 == 2) {
      a = point(), b = point();
    } else {
      a = b, b = c;  // the next triangle shares edge b-c
    }
  }
  const Subdivision sub = buildSubdivision(m.scene);
  expectInvariants(m.scene, sub, 21, 300);
  EXPECT_GT(expectSegmentsCrossOnlyThroughPortals(m.scene, sub, 21, 400), 50);
}

TEST(SubdivisionDegenerate, HugeAndTinyCoordinates) {
  const Scene base = twoRoomsWithDoor();
  const Subdivision ref = buildSubdivision(base);
  for (auto [scale, origin] :
       {std::pair{1e-4, Vec3{0, 0, 0}}, std::pair{1e4, Vec3{0, 0, 0}},
        std::pair{1.0, Vec3{1e5, -2e5, 3e4}}, std::pair{1e-3, Vec3{-1e3, 1e3, 0}}}) {
    const Scene s = transformed(base, scale, origin);
    const Subdivision sub = buildSubdivision(s);
    expectInvariants(s, sub, 6, 200);
    EXPECT_EQ(sub.cells.size(), ref.cells.size()) << scale << " " << origin;
    // Portal counts may differ by how rounding orders the convex pieces; their area may not.
    double area = 0, refArea = 0;
    for (const Portal& p : sub.portals) area += areaOf(p.polygon.vertices);
    for (const Portal& p : ref.portals) refArea += areaOf(p.polygon.vertices);
    EXPECT_NEAR(area / (scale * scale), refArea, 1e-6 * refArea) << scale << " " << origin;
    const int a = cellStrictlyAt(sub, origin + Vec3{0.5, 0.5, 1.5} * scale, 1e-7 * scale);
    const int b = cellStrictlyAt(sub, origin + Vec3{7.5, 3.5, 1.5} * scale, 1e-7 * scale);
    const int out = cellStrictlyAt(sub, origin + Vec3{-0.5, -0.5, -0.5} * scale, 1e-7 * scale);
    ASSERT_TRUE(a >= 0 && b >= 0 && out >= 0);
    const std::vector<bool> seen = reachable(sub, static_cast<uint32_t>(a));
    EXPECT_TRUE(seen[static_cast<size_t>(b)]);
    EXPECT_FALSE(seen[static_cast<size_t>(out)]);
  }
}

TEST(SubdivisionGraph, NeighboursAreSymmetric) {
  const Subdivision sub = buildSubdivision(twoRoomsWithDoor());
  for (uint32_t c = 0; c < sub.cells.size(); ++c) {
    for (uint32_t n : sub.neighbours(c)) {
      const std::vector<uint32_t> back = sub.neighbours(n);
      EXPECT_TRUE(std::binary_search(back.begin(), back.end(), c));
    }
  }
}

}  // namespace
}  // namespace gv
