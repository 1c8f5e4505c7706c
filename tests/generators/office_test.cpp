// Tests for the office generator: counts, validity, enclosed volume, and ray-cast occlusion facts.
#include "generators/office.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "generators/scene_oracle.h"

namespace gv {
namespace {

// Explicit dimensions, so that the hand computations below do not depend on the defaults.
OfficeOptions smallOffice() {
  OfficeOptions o;
  o.floors = 1;
  o.rows = 1;
  o.columns = 2;
  o.roomWidth = 4;
  o.roomDepth = 5;
  o.corridorWidth = 2;
  o.storeyHeight = 3;
  o.slabThickness = 0.25;
  o.wallThickness = 0.2;
  o.doorWidth = 1;
  o.doorHeight = 2;
  o.windowWidth = 1.5;
  o.windowSill = 1;
  o.windowHead = 2;
  return o;
}

// The room and corridor air boxes, recomputed from the layout documented in office.h.
struct HandLayout {
  OfficeOptions o;
  double t() const { return o.wallThickness; }
  double pitchY() const { return o.corridorWidth + 2 * t() + o.roomDepth; }
  double z0(int f) const { return f * (o.storeyHeight + o.slabThickness) + o.slabThickness; }
  Aabb room(int f, int r, int c) const {
    Aabb b;
    const double x0 = t() + c * (o.roomWidth + t());
    const double y0 = t() + r * pitchY() + o.corridorWidth + t();
    b.add(Vec3{x0, y0, z0(f)});
    b.add(Vec3{x0 + o.roomWidth, y0 + o.roomDepth, z0(f) + o.storeyHeight});
    return b;
  }
  Aabb corridor(int f, int r) const {
    Aabb b;
    const double sizeX = t() + o.columns * (o.roomWidth + t());
    b.add(Vec3{t(), t() + r * pitchY(), z0(f)});
    b.add(Vec3{sizeX - t(), t() + r * pitchY() + o.corridorWidth, z0(f) + o.storeyHeight});
    return b;
  }
};

void expectSameBox(const Aabb& a, const Aabb& b) {
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(a.lo[i], b.lo[i], 1e-12);
    EXPECT_NEAR(a.hi[i], b.hi[i], 1e-12);
  }
}

TEST(OfficeTest, DefaultIsPaperScaleAndValid) {
  const Scene scene = generateOffice();
  EXPECT_GE(scene.patches.size(), 350u);
  EXPECT_LE(scene.patches.size(), 450u);
  EXPECT_EQ(scene.patches.size(), officePatchCount(OfficeOptions{}));
  const double scale = scene.bounds().diagonal();
  for (const Patch& p : scene.patches) ASSERT_TRUE(testing::isValidPatch(p, scale));
  // z up, everything at z >= 0: the floor of the building is the bottom of slab 0.
  EXPECT_NEAR(scene.bounds().lo.z, 0.0, 1e-12);
  EXPECT_EQ(scene.emitterCount(), 16u);  // one per room and one per room in the corridor
}

TEST(OfficeTest, CountGrowsWithSize) {
  OfficeOptions o;
  const double base = static_cast<double>(generateOffice(o).patches.size());
  o.floors = 2;
  const double twoFloors = static_cast<double>(generateOffice(o).patches.size());
  EXPECT_NEAR(twoFloors / base, 2.0, 0.1);
  o.floors = 1;
  o.columns = 8;
  const double twiceColumns = static_cast<double>(generateOffice(o).patches.size());
  EXPECT_NEAR(twiceColumns / base, 2.0, 0.15);
  o.columns = 4;
  o.rows = 4;
  const double twiceRows = static_cast<double>(generateOffice(o).patches.size());
  EXPECT_NEAR(twiceRows / base, 2.0, 0.15);
  o.rows = 2;
  o.furniture = false;
  o.windows = false;
  EXPECT_LT(generateOffice(o).patches.size(), base);
}

TEST(OfficeTest, OptionsForPatchCountHitTheTarget) {
  for (size_t target : {400u, 2000u, 10000u, 100000u, 1000000u}) {
    const OfficeOptions o = officeOptionsForPatchCount(target);
    const double count = static_cast<double>(officePatchCount(o));
    EXPECT_NEAR(count / static_cast<double>(target), 1.0, 0.05) << target;
  }
  const OfficeOptions o = officeOptionsForPatchCount(10000);
  EXPECT_EQ(generateOffice(o).patches.size(), officePatchCount(o));
}

TEST(OfficeTest, EnclosedVolumeMatchesTheBuildingMinusItsAir) {
  // Divergence theorem: closed outward boxes enclose the building's solid volume, computed here
  // as the bounding box minus the air (rooms, corridor, door and window openings). Overlapping
  // boxes or missing/flipped faces would change the sum.
  for (int floors : {1, 2}) {
    OfficeOptions o = smallOffice();
    o.floors = floors;
    o.furniture = false;
    o.lights = false;
    const double t = o.wallThickness, W = o.roomWidth, D = o.roomDepth, C = o.corridorWidth;
    const double H = o.storeyHeight, s = o.slabThickness;
    const double X = t + 2 * (W + t), Y = t + C + t + D + t, Z = floors * (H + s) + s;
    const double airPerStorey = (X - 2 * t) * C * H + 2 * W * D * H +
                                2 * o.doorWidth * t * o.doorHeight +
                                o.windowWidth * t * (o.windowHead - o.windowSill);
    const Scene scene = generateOffice(o);
    EXPECT_NEAR(testing::divergenceVolume(scene), X * Y * Z - floors * airPerStorey, 1e-9)
        << floors;
  }
}

TEST(OfficeTest, InteriorHelpersMatchTheDocumentedLayout) {
  OfficeOptions o = smallOffice();
  o.floors = 3;
  o.rows = 2;
  const HandLayout hand{o};
  for (int f = 0; f < 3; ++f) {
    for (int r = 0; r < 2; ++r) {
      expectSameBox(officeCorridorInterior(o, f, r), hand.corridor(f, r));
      for (int c = 0; c < 2; ++c) expectSameBox(officeRoomInterior(o, f, r, c), hand.room(f, r, c));
    }
  }
}

// All air regions (rooms and corridors) of an office, by the hand layout.
std::vector<Aabb> airRegions(const OfficeOptions& o, std::vector<int>* floorOf = nullptr) {
  const HandLayout hand{o};
  std::vector<Aabb> regions;
  for (int f = 0; f < o.floors; ++f) {
    for (int r = 0; r < o.rows; ++r) {
      regions.push_back(hand.corridor(f, r));
      if (floorOf) floorOf->push_back(f);
      for (int c = 0; c < o.columns; ++c) {
        regions.push_back(hand.room(f, r, c));
        if (floorOf) floorOf->push_back(f);
      }
    }
  }
  return regions;
}

TEST(OfficeTest, SealedRoomsNeverSeeEachOther) {
  OfficeOptions o;
  o.floors = 2;
  o.rows = 2;
  o.columns = 3;
  o.doors = false;
  o.windows = false;
  const Scene scene = generateOffice(o);
  const std::vector<Aabb> regions = airRegions(o);
  std::mt19937 rng(3);
  for (int k = 0; k < 3000; ++k) {
    const size_t a = rng() % regions.size();
    size_t b = rng() % regions.size();
    if (a == b) b = (b + 1) % regions.size();
    const Vec3 p = testing::pointIn(rng, regions[a].lo, regions[a].hi, 0.01);
    const Vec3 q = testing::pointIn(rng, regions[b].lo, regions[b].hi, 0.01);
    ASSERT_TRUE(testing::segmentBlocked(scene, p, q)) << p << " -> " << q;
  }
}

TEST(OfficeTest, DoorsAndWindowsLetSomeSightLinesThrough) {
  const OfficeOptions o;  // default: doors, windows, furniture, lights
  const Scene scene = generateOffice(o);
  const HandLayout hand{o};
  std::mt19937 rng(5);
  int throughDoor = 0, throughWindow = 0;
  for (int k = 0; k < 4000; ++k) {
    const int r = static_cast<int>(rng() % 2), c = static_cast<int>(rng() % 3);
    // Room -> its corridor, at door height; room -> the next room, at window height.
    const Aabb room = hand.room(0, r, c);
    Vec3 p = testing::pointIn(rng, room.lo, room.hi, 0.01);
    Vec3 q = testing::pointIn(rng, hand.corridor(0, r).lo, hand.corridor(0, r).hi, 0.01);
    p.z = q.z = room.lo.z + testing::uniform(rng, 0.8, 1.9);
    if (!testing::segmentBlocked(scene, p, q)) ++throughDoor;
    const Aabb next = hand.room(0, r, c + 1);
    p = testing::pointIn(rng, room.lo, room.hi, 0.01);
    q = testing::pointIn(rng, next.lo, next.hi, 0.01);
    p.z = q.z = room.lo.z + testing::uniform(rng, o.windowSill + 0.05, o.windowHead - 0.05);
    if (!testing::segmentBlocked(scene, p, q)) ++throughWindow;
  }
  EXPECT_GT(throughDoor, 10);
  EXPECT_GT(throughWindow, 10);
}

TEST(OfficeTest, StoreysNeverSeeEachOther) {
  OfficeOptions o;
  o.floors = 3;
  o.rows = 1;
  o.columns = 3;
  const Scene scene = generateOffice(o);
  std::vector<int> floorOf;
  const std::vector<Aabb> regions = airRegions(o, &floorOf);
  std::mt19937 rng(11);
  int tried = 0;
  for (int k = 0; k < 3000; ++k) {
    const size_t a = rng() % regions.size(), b = rng() % regions.size();
    if (floorOf[a] == floorOf[b]) continue;
    ++tried;
    const Vec3 p = testing::pointIn(rng, regions[a].lo, regions[a].hi, 0.01);
    const Vec3 q = testing::pointIn(rng, regions[b].lo, regions[b].hi, 0.01);
    ASSERT_TRUE(testing::segmentBlocked(scene, p, q)) << p << " -> " << q;
  }
  EXPECT_GT(tried, 1000);
}

TEST(OfficeTest, FurnitureStandsInsideRoomsClearOfTheDoorWall) {
  OfficeOptions o;
  o.rows = 3;
  o.columns = 5;
  o.furniturePerRoom = 3;
  const Scene scene = generateOffice(o);
  const uint32_t desk = testing::materialNamed(scene, "desk");
  const uint32_t cabinet = testing::materialNamed(scene, "cabinet");
  const HandLayout hand{o};
  size_t furniturePatches = 0;
  for (const Patch& p : scene.patches) {
    if (p.material != desk && p.material != cabinet) continue;
    ++furniturePatches;
    const Aabb b = p.polygon.bounds();
    bool inside = false;
    for (int r = 0; r < o.rows; ++r) {
      for (int c = 0; c < o.columns; ++c) {
        const Aabb room = hand.room(0, r, c);
        if (b.lo.x > room.lo.x && b.hi.x < room.hi.x && b.lo.y > room.lo.y + 1.0 &&
            b.hi.y < room.hi.y && b.lo.z >= room.lo.z - 1e-12 && b.hi.z < room.hi.z - 0.5) {
          inside = true;
        }
      }
    }
    EXPECT_TRUE(inside) << b.lo << " " << b.hi;
  }
  EXPECT_EQ(furniturePatches, 6u * 3 * 5 * 3);
}

TEST(OfficeTest, SeedDeterminesTheScene) {
  OfficeOptions o;
  const Scene a = generateOffice(o), b = generateOffice(o);
  o.seed = 2;
  const Scene c = generateOffice(o);
  ASSERT_EQ(a.patches.size(), b.patches.size());
  ASSERT_EQ(a.patches.size(), c.patches.size());
  bool differs = false;
  for (size_t i = 0; i < a.patches.size(); ++i) {
    EXPECT_EQ(a.patches[i].polygon.vertices, b.patches[i].polygon.vertices);
    differs |= a.patches[i].polygon.vertices != c.patches[i].polygon.vertices;
  }
  EXPECT_TRUE(differs);
}

TEST(OfficeTest, InvalidOptionsThrow) {
  OfficeOptions o;
  o.floors = 0;
  EXPECT_THROW(generateOffice(o), std::invalid_argument);
  o = OfficeOptions{};
  o.doorWidth = 5;
  EXPECT_THROW(generateOffice(o), std::invalid_argument);
}

}  // namespace
}  // namespace gv
