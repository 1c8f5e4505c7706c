// PatchCellReach: patch pairs bounded by cell-to-cell visibility. Checked against rooms sealed by
// construction (no pair between them, each room's patches seeing exactly its own lamps' power)
// and against a brute-force ray caster written apart from the visibility code (every segment
// that runs clear from one patch's front to another's is a pair).
#include "visibility/patch_cell_reach.h"

#include <gtest/gtest.h>

#include <optional>
#include <random>

#include "support/office_cells.h"
#include "visibility/ray_oracle.h"

namespace gv {
namespace {

/// The room or corridor (index into `boxes`) whose air the patch's centroid borders (the box
/// grown by less than half a wall); nullopt for the building's outer faces.
std::optional<size_t> spaceOf(const Patch& p, const std::vector<Aabb>& boxes, double margin) {
  for (size_t i = 0; i < boxes.size(); ++i)
    if (test::insideGrown(boxes[i], p.polygon.centroid(), margin)) return i;
  return std::nullopt;
}

TEST(PatchCellReachTest, SealedRoomsNeverPairAndSeeOnlyTheirOwnLamps) {
  OfficeOptions o;
  o.rows = 1;
  o.columns = 3;
  o.doors = false;
  o.windows = false;
  const Scene scene = test::radiosityOffice(o);
  const PatchCellReach reach = test::cellReachOf(scene);
  ASSERT_TRUE(reach.known());
  EXPECT_EQ(reach.unplacedPatches(), 0u);
  std::vector<Aabb> spaces;
  for (int c = 0; c < o.columns; ++c) spaces.push_back(officeRoomInterior(o, 0, 0, c));
  spaces.push_back(officeCorridorInterior(o, 0, 0));
  const double margin = o.wallThickness / 3;
  std::vector<std::optional<size_t>> space;
  size_t inside = 0;
  for (const Patch& p : scene.patches) {
    space.push_back(spaceOf(p, spaces, margin));
    inside += space.back().has_value();
  }
  // Most patches face into a room or the corridor; the rest are the building's outer faces.
  EXPECT_GT(inside, scene.patches.size() / 2);
  size_t pairs = 0, sameSpace = 0;
  reach.forEachPair([&](uint32_t a, uint32_t b) {
    ++pairs;
    ASSERT_LT(a, b);
    EXPECT_TRUE(reach.maySee(a, b));
    // A pair between two sealed spaces, or between a space and the outside, is a leak.
    EXPECT_EQ(space[a], space[b]) << a << " " << b;
    sameSpace += space[a].has_value();
  });
  EXPECT_EQ(reach.countPairs(), pairs);
  EXPECT_GT(sameSpace, 0u);
  // And the other way: within one space every facing pair stays (their cells see each other).
  for (uint32_t a = 0; a < scene.patches.size(); ++a)
    for (uint32_t b = a + 1; b < scene.patches.size(); ++b) {
      if (space[a] && space[a] == space[b]) {
        EXPECT_TRUE(reach.maySee(a, b)) << a << " " << b;
      }
    }

  // Each space's patches see exactly the power of the lamps in it.
  const std::vector<double> power = scene.emittedPower();
  std::vector<double> spacePower(spaces.size(), 0.0);
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    if (power[p] > 0) {
      ASSERT_TRUE(space[p].has_value()) << p;  // the lamps hang inside
      spacePower[*space[p]] += power[p];
    }
  }
  const std::vector<double> inView = reach.powerInView(power);
  for (size_t i = 0; i < spaces.size(); ++i) EXPECT_GT(spacePower[i], 0.0) << i;
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    if (space[p]) {
      EXPECT_NEAR(inView[p], spacePower[*space[p]], 1e-9 * spacePower[*space[p]]) << p;
    }
  }
}

TEST(PatchCellReachTest, EverySegmentClearFromFrontToFrontJoinsAPair) {
  const OfficeOptions o = test::twoStoreysOfThreeRooms();
  const Scene scene = test::radiosityOffice(o);
  const PatchCellReach reach = test::cellReachOf(scene);
  ASSERT_TRUE(reach.known());
  const size_t n = scene.patches.size();
  EXPECT_LT(reach.countPairs(), n * (n - 1) / 2 * 6 / 10);  // the storeys alone halve them
  std::mt19937 rng(7);
  std::uniform_int_distribution<uint32_t> pick(0, static_cast<uint32_t>(n - 1));
  size_t clear = 0, clearBetweenSpaces = 0, culled = 0;
  std::vector<Aabb> spaces;
  for (int f = 0; f < o.floors; ++f) {
    for (int c = 0; c < o.columns; ++c) spaces.push_back(officeRoomInterior(o, f, 0, c));
    spaces.push_back(officeCorridorInterior(o, f, 0));
  }
  for (int i = 0; i < 60000; ++i) {
    const uint32_t a = pick(rng), b = pick(rng);
    if (a == b) continue;
    const ConvexPolygon& pa = scene.patches[a].polygon;
    const ConvexPolygon& pb = scene.patches[b].polygon;
    const Vec3 from = test::randomPointOn(pa, rng), to = test::randomPointOn(pb, rng);
    const Vec3 d = to - from;
    const double len = length(d);
    if (!(len > 1e-6) || dot(d, pa.plane.normal) <= 0 || dot(d, pb.plane.normal) >= 0) continue;
    if (!reach.maySee(a, b)) ++culled;
    // Clear beyond a contact margin at both ends (the rule `verify` uses).
    const double margin = 1e-5;
    if (test::firstHit(scene, from, d / len, margin, len - margin, a)) continue;
    ++clear;
    EXPECT_TRUE(reach.maySee(a, b)) << a << " " << b;
    if (spaceOf(scene.patches[a], spaces, o.wallThickness / 3) !=
        spaceOf(scene.patches[b], spaces, o.wallThickness / 3))
      ++clearBetweenSpaces;
  }
  // The sample holds both kinds: sightlines through doors and windows, and pairs culled.
  EXPECT_GT(clear, 500u);
  EXPECT_GT(clearBetweenSpaces, 20u);
  EXPECT_GT(culled, 5000u);
}

}  // namespace
}  // namespace gv
