// `rays` radiosity with cell culling (visibility/patch_cell_reach.h): candidates looked up through
// the cells instead of listed, the solution the same as with every pair linked up to sampling,
// and the BF threshold taken per room (RadiosityOptions::thresholdPower) so that a room is
// refined the same alone and inside a bigger building.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "radiosity/cluster_links.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/patch_clusters.h"
#include "radiosity/ray_visibility.h"
#include "raycast/embree_scene.h"
#include "support/office_cells.h"
#include "visibility/patch_cell_reach.h"

namespace gv {
namespace {

double luminance(const Rgb& c) {
  return (c.r + c.g + c.b) / 3;
}

TEST(CellCullingTest, CandidateLookupsThroughTheCellsAgreeWithThePairsByBruteForce) {
  const OfficeOptions o = test::twoStoreysOfThreeRooms();
  const Scene scene = test::radiosityOffice(o);
  const PatchCellReach reach = test::cellReachOf(scene);
  ASSERT_TRUE(reach.known());
  const EmbreeScene bvh(scene);
  RayVisibility visibility(scene, bvh, 4, &reach);
  EXPECT_FALSE(visibility.everyPairIsCandidate());
  ASSERT_EQ(visibility.candidateCells(), &reach);
  const ClusterTree tree(scene);
  const CandidatePairs candidates(visibility, tree);
  EXPECT_EQ(candidates.count(), reach.countPairs());
  const auto n = static_cast<uint32_t>(scene.patches.size());
  for (uint32_t a = 0; a < n; ++a)
    for (uint32_t b = 0; b < n; ++b) {
      if (a != b) {
        ASSERT_EQ(candidates.find(a, b).has_value(), reach.maySee(a, b)) << a << " " << b;
      }
    }
  // Disjoint clusters, sampled: any candidate between them exactly when some pair of their
  // patches may see each other.
  std::mt19937 rng(3);
  std::uniform_int_distribution<uint32_t> pick(0, static_cast<uint32_t>(tree.size() - 1));
  size_t checked = 0, without = 0, large = 0;
  for (int i = 0; i < 4000; ++i) {
    const uint32_t x = pick(rng), y = pick(rng);
    const Cluster& cx = tree[x];
    const Cluster& cy = tree[y];
    if (cx.begin < cy.end && cy.begin < cx.end) continue;  // nested or the same
    bool any = false;
    for (const uint32_t p : tree.patchesOf(x))
      for (const uint32_t q : tree.patchesOf(y)) any = any || reach.maySee(p, q);
    ASSERT_EQ(candidates.anyBetween(x, y), any) << x << " " << y;
    ++checked;
    without += any ? 0 : 1;
    large += cx.size() > 8 && cy.size() > 8;
  }
  EXPECT_GT(checked, 1000u);
  EXPECT_GT(without, 100u);  // the storeys never see each other
  EXPECT_GT(large, 20u);     // clusters that may test through their reach sets
}

TEST(CellCullingTest, CulledLinksGiveTheSolutionOfEveryPairLinked) {
  // Culling drops pairs whose every segment is blocked: the solution is the one with every pair
  // linked, up to the sampling of the links and cluster links the two runs make differently.
  OfficeOptions o = test::twoStoreysOfThreeRooms();
  o.furniture = false;
  const Scene scene = test::radiosityOffice(o);
  const PatchCellReach reach = test::cellReachOf(scene);
  const EmbreeScene bvh(scene);
  RadiosityOptions options;
  options.epsilon = 2e-4;
  options.clusterSamples = 2;
  RayVisibility every(scene, bvh, 16);
  const RadiosityResult all = solveRadiosity(scene, every, options);
  RayVisibility culled(scene, bvh, 16, &reach);
  const RadiosityResult cut = solveRadiosity(scene, culled, options);
  EXPECT_LT(cut.stats.candidatePairs, all.stats.candidatePairs * 6 / 10);
  EXPECT_LT(cut.stats.rays, all.stats.rays);
  double diff2 = 0, ref2 = 0;
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const double area = scene.patches[p].polygon.area();
    const double e = luminance(scene.materials[scene.patches[p].material].emission);
    const double x = luminance(all.patchRadiosity[p]) - e;
    const double y = luminance(cut.patchRadiosity[p]) - e;
    diff2 += area * (x - y) * (x - y);
    ref2 += area * x * x;
  }
  const double l2 = std::sqrt(diff2 / ref2);
  std::printf("candidates %zu -> %zu, rays %llu -> %llu, L2 of the difference %.3f %%\n",
              all.stats.candidatePairs, cut.stats.candidatePairs,
              static_cast<unsigned long long>(all.stats.rays),
              static_cast<unsigned long long>(cut.stats.rays), 100 * l2);
  // A bound on sampling noise between two runs of the same solution (each ~1-2 % from light
  // tracing on the office: docs/BENCHMARKS.md), not a measured error copied.
  EXPECT_LT(l2, 0.02);
}

/// Leaves on the patches of room (0, 0, 0) of an office.
size_t leavesInFirstRoom(const OfficeOptions& o, const Scene& scene, const RadiosityResult& r) {
  const Aabb room = officeRoomInterior(o, 0, 0, 0);
  size_t leaves = 0;
  for (size_t e = 0; e < r.elements.size(); ++e) {
    const Element& el = r.elements[static_cast<uint32_t>(e)];
    if (el.isLeaf() &&
        test::insideGrown(room, scene.patches[el.patch].polygon.centroid(), o.wallThickness / 3))
      ++leaves;
  }
  return leaves;
}

TEST(CellCullingTest, ARoomIsRefinedAlikeAloneAndInsideABuildingWithThresholdsPerRoom) {
  // Sealed rooms (no doors, no windows): with one BF threshold for the whole scene, the same room
  // inside a building of four is judged against the lamps of four rooms and their corridor, and
  // refined less; with the threshold of the power its cells see, as when alone.
  RadiosityOptions options;
  options.epsilon = 2e-4;
  options.clusterSamples = 2;
  auto solve = [&](const OfficeOptions& o, bool perRoom, const Scene& scene) {
    const PatchCellReach reach = test::cellReachOf(scene);
    const EmbreeScene bvh(scene);
    RayVisibility visibility(scene, bvh, 16, &reach);
    RadiosityOptions opt = options;
    if (perRoom) opt.thresholdPower = reach.powerInView(scene.emittedPower());
    const RadiosityResult r = solveRadiosity(scene, visibility, opt);
    EXPECT_TRUE(r.stats.converged);
    return leavesInFirstRoom(o, scene, r);
  };
  OfficeOptions one;
  one.rows = 1;
  one.columns = 1;
  one.doors = false;
  one.windows = false;
  one.furniture = false;
  OfficeOptions four = one;
  four.columns = 4;
  const Scene alone = test::radiosityOffice(one), building = test::radiosityOffice(four);
  // Alone, the room is judged against its own lamp too (its sealed corridor's lamp left out).
  const size_t aloneLeaves = solve(one, true, alone);
  const size_t sceneThreshold = solve(four, false, building);
  const size_t roomThreshold = solve(four, true, building);
  std::printf(
      "leaves in the first room: alone %zu; in four rooms %zu (scene threshold), %zu "
      "(room threshold)\n",
      aloneLeaves, sceneThreshold, roomThreshold);
  EXPECT_LT(sceneThreshold * 10, aloneLeaves * 8);
  EXPECT_GT(roomThreshold * 10, aloneLeaves * 9);
  EXPECT_LT(roomThreshold * 10, aloneLeaves * 11);
}

TEST(CellCullingTest, ThresholdPowerOfTheWholeSceneEverywhereChangesNothing) {
  OfficeOptions o;
  o.rows = 1;
  o.columns = 2;
  o.furniture = false;
  const Scene scene = test::radiosityOffice(o);
  const EmbreeScene bvh(scene);
  RayVisibility visibility(scene, bvh, 16);
  RadiosityOptions options;
  options.epsilon = 2e-4;
  options.clusterSamples = 2;
  const RadiosityResult plain = solveRadiosity(scene, visibility, options);
  const double total = plain.stats.emittedPower;
  options.thresholdPower.assign(scene.patches.size(), total);
  const RadiosityResult same = solveRadiosity(scene, visibility, options);
  EXPECT_EQ(plain.patchRadiosity, same.patchRadiosity);
  EXPECT_EQ(plain.elements.size(), same.elements.size());
  options.thresholdPower.assign(scene.patches.size(), total / 4);
  const RadiosityResult finer = solveRadiosity(scene, visibility, options);
  EXPECT_GT(finer.elements.size(), plain.elements.size());
}

}  // namespace
}  // namespace gv
