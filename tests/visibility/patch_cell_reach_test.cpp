// PatchCellReach: patch pairs bounded by cell-to-cell visibility. Checked against rooms sealed by
// construction (no pair between them, each room's patches seeing exactly its own lamps' power)
// and against a brute-force ray caster written apart from the visibility code (every segment
// that runs clear from one patch's front to another's is a pair), on the office and on shared
// real levels (every path light takes from a patch to the first front it meets is a pair).
#include "visibility/patch_cell_reach.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <random>
#include <set>
#include <string>

#include "input/load_scene.h"
#include "radiosity/polygon_sampling.h"
#include "raycast/embree_scene.h"
#include "support/office_cells.h"
#include "support/shared_levels.h"
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

/// Light's own paths on a real level: cosine-distributed rays from area-sampled points of every
/// patch (what the photon tracer shoots and what a form factor weighs), each first hit on a
/// patch's front beyond the contact distance (1e-6 of the diagonal, as `verify`) a pair that the
/// cull must keep. Embree finds the hits; a culled one counts only if the brute-force caster
/// (double precision, apart from the visibility code) agrees, so single-precision slips through
/// cracks are not blamed on the cull. The level as `radiosity` reads it (contact split, hidden
/// faces dropped), with `vis`'s cells, as the command builds them.
void expectLightPathsKept(const std::string& name, size_t rays) {
  const std::string path = test::sharedLevelPath(name);
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const Scene scene = test::asRadiosityReadsIt(loadScene(path));
  const PatchCellReach reach = test::cellReachOf(scene);
  ASSERT_TRUE(reach.known());
  EXPECT_EQ(reach.unplacedPatches(), 0u);
  const EmbreeScene bvh(scene);
  std::vector<double> cdf;
  double total = 0;
  for (const Patch& p : scene.patches) cdf.push_back(total += p.polygon.area());
  SplitMix64 rng(2026);
  const double contact = 1e-6 * scene.bounds().diagonal();
  // Left out, and counted: rays that leave the level or end on a back (no pair), and hits within
  // the contact distance (the contract's contact rule).
  size_t frontHits = 0, culledByEmbree = 0, noPair = 0, inContact = 0;
  std::set<std::pair<uint32_t, uint32_t>> missed;
  for (size_t k = 0; k < rays; ++k) {
    const double u = total * (static_cast<double>(rng.next() >> 11) * 0x1.0p-53);
    const auto s = static_cast<uint32_t>(std::min<size_t>(
        std::lower_bound(cdf.begin(), cdf.end(), u) - cdf.begin(), cdf.size() - 1));
    const ConvexPolygon& sp = scene.patches[s].polygon;
    const Vec3 x = uniformPoint(sp.vertices, rng);
    const Vec3 d = cosineDirection(sp.plane.normal, rng);
    const std::optional<RayHit> hit = bvh.firstHit(x, d, INFINITY, s);
    if (!hit || dot(d, scene.patches[hit->patch].polygon.plane.normal) >= 0) {
      ++noPair;  // the void, or a back (absorbed)
      continue;
    }
    if (hit->t <= contact) {
      ++inContact;
      continue;
    }
    const uint32_t r = hit->patch;
    ++frontHits;
    if (reach.maySee(s, r)) continue;
    ++culledByEmbree;
    const std::optional<test::RayHit> exact = test::firstHit(scene, x, d, contact, INFINITY, s);
    if (exact && exact->patch == r && exact->front) missed.insert({std::min(s, r), std::max(s, r)});
  }
  std::printf(
      "%s: %zu patches, %zu cells, %zu rays: %zu front hits checked, %zu left out (void or a "
      "back), %zu within contact; culled by the Embree hit %zu, confirmed by brute force in %zu "
      "pairs; the cull keeps %.2f %% of all pairs\n",
      name.c_str(), scene.patches.size(), reach.cellCount(), rays, frontHits, noPair, inContact,
      culledByEmbree, missed.size(),
      100.0 * static_cast<double>(reach.countPairs()) /
          (0.5 * static_cast<double>(scene.patches.size()) *
           static_cast<double>(scene.patches.size() - 1)));
  EXPECT_TRUE(missed.empty()) << missed.size() << " pairs light reaches were culled, e.g. "
                              << missed.begin()->first << " " << missed.begin()->second;
  // The check has something to find: most rays land on a front, and the cull drops more than
  // half of all pairs.
  EXPECT_GT(frontHits, rays / 2);
  EXPECT_LT(reach.countPairs(), scene.patches.size() * (scene.patches.size() - 1) / 4);
}

TEST(PatchCellReachTest, LightPathsOnAnArenaLevelStayWithinTheReach) {
  expectLightPathsKept("lit-q3-dm4ish", 1'000'000);
}

TEST(PatchCellReachTest, LightPathsOnASectorLevelStayWithinTheReach) {
  expectLightPathsKept("lit-doom-fd2-map01", 1'000'000);
}

}  // namespace
}  // namespace gv
