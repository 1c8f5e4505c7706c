// `blockers` visibility mode (paper §6, §7.4) against independent answers: refined links checked
// by brute-force segment sampling (VISIBLE never blocked, INVISIBLE never free), a sealed
// neighbour room exactly black, the Cornell box agreeing with `rays` mode at many rays, and an
// emitter over a receiver giving ρ·E·F.
#include "radiosity/blocker_visibility.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>

#include "bsp/subdivision.h"
#include "generators/cornell_box.h"
#include "generators/scene_builder.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/ray_visibility.h"
#include "raycast/embree_scene.h"
#include "support/run_cli.h"
#include "support/temp_dir.h"
#include "visibility/propagation.h"
#include "visibility/ray_oracle.h"

namespace gv {
namespace {

VisibilityGraph graphOf(const Scene& scene) {
  PropagationOptions p;
  p.threads = 1;
  return computeVisibility(scene, buildSubdivision(scene), p);
}

double luminance(const Rgb& c) {
  return (c.r + c.g + c.b) / 3;
}

/// Is the open segment p → q blocked by a patch other than a and b? (double-precision brute
/// force; the segment's ends on a and b are excluded)
bool blockedBruteForce(const Scene& scene, const Vec3& p, const Vec3& q, uint32_t a, uint32_t b) {
  const auto h = test::firstHit(scene, p, q - p, 1e-9, 1 - 1e-9, a);
  return h && h->patch != b;
}

/// Adds the six inward-facing faces of the box [lo, hi].
void addInwardBox(SceneBuilder& b, const Vec3& lo, const Vec3& hi, uint32_t material) {
  for (int axis = 0; axis < 3; ++axis) {
    Vec3 hiLow = hi, loHigh = lo;
    hiLow[axis] = lo[axis];
    loHigh[axis] = hi[axis];
    ASSERT_TRUE(b.addAxisRect(axis, true, lo, hiLow, material));
    ASSERT_TRUE(b.addAxisRect(axis, false, loHigh, hi, material));
  }
}

TEST(BlockerVisibilityTest, RefinedLinksAgreeWithBruteForceSampling) {
  // Every link of the Cornell box's graph refined three levels (alternating ends), each child
  // estimated from its parent's tube: VISIBLE children must have no blocked light-carrying
  // segment, INVISIBLE ones no free segment; PARTIAL fractions near the sampled ones.
  const Scene scene = generateCornellBox();
  const VisibilityGraph graph = graphOf(scene);
  BlockerVisibility vis(scene, graph, 64);
  ElementTree tree(scene);
  std::mt19937 rng(3);
  std::vector<std::tuple<uint32_t, uint32_t, TubeId>> roots;
  vis.forEachCandidatePair([&](uint32_t a, uint32_t b, TubeId t) { roots.emplace_back(a, b, t); });
  ASSERT_EQ(roots.size(), graph.interactions.size());
  int counts[3] = {0, 0, 0};
  double fractionError = 0;
  int partialSampled = 0;
  std::function<void(uint32_t, uint32_t, TubeId, int)> visit = [&](uint32_t a, uint32_t b, TubeId t,
                                                                   int depth) {
    const Element ea = tree[a], eb = tree[b];
    const VisibilityEstimate e = vis.estimate(ea, eb, t, 7);
    ++counts[static_cast<int>(e.status)];
    int n = 0, blocked = 0;
    for (int i = 0; i < 200; ++i) {
      const Vec3 p = test::randomPointOn(ea.polygon, rng), q = test::randomPointOn(eb.polygon, rng);
      if (ea.polygon.plane.distance(q) <= 0 || eb.polygon.plane.distance(p) <= 0) continue;
      ++n;
      blocked += blockedBruteForce(scene, p, q, ea.patch, eb.patch);
    }
    if (e.status == VisibilityStatus::Visible) {
      EXPECT_EQ(blocked, 0) << "patches " << ea.patch << " " << eb.patch << " depth " << depth;
    }
    if (e.status == VisibilityStatus::Invisible) {
      EXPECT_EQ(blocked, n) << "patches " << ea.patch << " " << eb.patch << " depth " << depth;
    }
    if (e.status == VisibilityStatus::Partial && n >= 50) {
      fractionError += std::abs(e.fraction - (1.0 - double(blocked) / n));
      ++partialSampled;
    }
    if (e.status == VisibilityStatus::Invisible || depth >= 3) return;
    const uint32_t split = depth % 2 == 0 ? a : b;
    if (!tree.subdivide(split)) return;
    const uint32_t first = tree[split].firstChild, count = tree[split].childCount;
    for (uint32_t c = first; c < first + count; ++c)
      visit(split == a ? c : a, split == a ? b : c, e.tube, depth + 1);
  };
  for (const auto& [a, b, t] : roots) visit(a, b, t, 0);
  EXPECT_GT(counts[0], 0);
  EXPECT_GT(counts[1], 0);
  EXPECT_GT(counts[2], 0);
  ASSERT_GT(partialSampled, 100);
  // 64 stratified rays vs 200 random ones per link: the mean difference is sampling noise.
  EXPECT_LT(fractionError / partialSampled, 0.06);
  const LevelStats total = vis.stats().total();
  EXPECT_EQ(total.invisible, static_cast<uint64_t>(counts[0]));
  EXPECT_EQ(vis.proofs().size(), static_cast<size_t>(counts[0]));
  std::printf(
      "links I/P/V %d/%d/%d, mean |fraction error| %.4f; blocker tests %llu, punts %llu "
      "(removed by stabbing %llu)\n",
      counts[0], counts[1], counts[2], fractionError / partialSampled,
      static_cast<unsigned long long>(total.blockers.total()),
      static_cast<unsigned long long>(total.blockers.puntsTested),
      static_cast<unsigned long long>(total.blockers.puntsRemoved));
}

TEST(BlockerVisibilityTest, SealedNeighbourRoomStaysExactlyBlack) {
  // Two 1 m rooms along x with a 0.1 m solid wall between them (both its faces are patches of
  // the rooms' inward boxes), a light panel under room A's ceiling, a box standing in room A.
  Scene scene;
  const uint32_t white = scene.addMaterial({"white", {0.7, 0.7, 0.7}, {}});
  const uint32_t light = scene.addMaterial({"light", {0.8, 0.8, 0.8}, {5, 5, 5}});
  SceneBuilder builder(scene, Tolerance{3.0});
  addInwardBox(builder, {0, 0, 0}, {1, 1, 1}, white);
  builder.addBox({0.2, 0.2, 0}, {0.5, 0.6, 0.4}, white, kBoxAllFaces & ~kBoxMinZ);
  const size_t roomA = scene.patches.size();
  addInwardBox(builder, {1.1, 0, 0}, {2.1, 1, 1}, white);
  const size_t roomB = scene.patches.size();
  ASSERT_TRUE(builder.addAxisRect(2, false, {0.3, 0.3, 0.98}, {0.7, 0.7, 0.98}, light));
  const VisibilityGraph graph = graphOf(scene);
  BlockerVisibility vis(scene, graph, 16);
  RadiosityOptions options;
  options.epsilon = 1e-4;
  const RadiosityResult r = solveRadiosity(scene, vis, options);
  EXPECT_TRUE(r.stats.converged);
  for (size_t p = 0; p < roomA; ++p) EXPECT_GT(luminance(r.patchRadiosity[p]), 0.01) << p;
  for (size_t p = roomA; p < roomB; ++p) EXPECT_EQ(r.patchRadiosity[p], Rgb{}) << p;
  for (size_t e = 0; e < r.elements.size(); ++e) {
    const uint32_t patch = r.elements[static_cast<uint32_t>(e)].patch;
    if (patch >= roomA && patch < roomB) {
      ASSERT_EQ(r.elementRadiosity[e], Rgb{});
    }
  }
  // The box makes PARTIAL links, some of whose children are INVISIBLE.
  EXPECT_GT(vis.stats().total().partial, 0u);
  EXPECT_GT(vis.stats().total().invisible, 0u);
  // Clustered: the graph lists no pair across the wall, so cluster pairs of the two rooms are
  // dropped whole (the visibility graph decides them) rather than split down to patch pairs.
  BlockerVisibility again(scene, graph, 16);
  options.clusterSamples = 2;
  const RadiosityResult c = solveRadiosity(scene, again, options);
  ASSERT_TRUE(c.stats.clustered);
  size_t dropped = 0;
  for (const RefinementStats& round : c.stats.rounds) dropped += round.clusterPairsInvisible;
  EXPECT_GT(dropped, 0u);
  for (size_t p = 0; p < roomA; ++p) EXPECT_GT(luminance(c.patchRadiosity[p]), 0.01) << p;
  for (size_t p = roomA; p < roomB; ++p) EXPECT_EQ(c.patchRadiosity[p], Rgb{}) << p;
}

TEST(BlockerVisibilityTest, CornellBoxAgreesWithRaysModeAtManyRays) {
  // Same solver, same sampling of PARTIAL links; `rays` tests them against the whole scene with
  // Embree and links all pairs, `blockers` only the graph's pairs against their blockers. With
  // 256 rays per link the two must agree per patch within a few percent.
  const Scene scene = generateCornellBox();
  RadiosityOptions options;
  options.epsilon = 5e-5;
  const VisibilityGraph graph = graphOf(scene);
  BlockerVisibility blockers(scene, graph, 256);
  const RadiosityResult b = solveRadiosity(scene, blockers, options);
  const EmbreeScene bvh(scene);
  RayVisibility rays(scene, bvh, 256);
  const RadiosityResult r = solveRadiosity(scene, rays, options);
  ASSERT_TRUE(b.stats.converged);
  ASSERT_TRUE(r.stats.converged);
  double worst = 0;
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const double lb = luminance(b.patchRadiosity[p]), lr = luminance(r.patchRadiosity[p]);
    if (lr == 0) {
      EXPECT_EQ(lb, 0) << p;  // the blocks' bottom faces on the floor
      continue;
    }
    EXPECT_NEAR(lb / lr, 1.0, 0.03) << "patch " << p;
    worst = std::max(worst, std::abs(lb / lr - 1));
  }
  EXPECT_LT(b.stats.rays, r.stats.rays);
  std::printf(
      "worst per-patch difference %.4f; rays %llu (blockers) vs %llu (rays); links %zu vs %zu\n",
      worst, static_cast<unsigned long long>(b.stats.rays),
      static_cast<unsigned long long>(r.stats.rays), b.stats.rounds.back().links.total(),
      r.stats.rounds.back().links.total());
}

TEST(BlockerVisibilityTest, EmitterOverReceiverGivesRhoEF) {
  // A non-reflecting emitter (unit square at z = 1 facing down) over a receiver (unit square at
  // z = 0 facing up, ρ = 0.6): Howell C-11, X = Y = 1: F = 0.19982. The pair is VISIBLE in the
  // graph, so the link is exact and casts no ray.
  Scene scene;
  const uint32_t lightM = scene.addMaterial({"light", {0, 0, 0}, {3, 2, 1}});
  const uint32_t grey = scene.addMaterial({"grey", {0.6, 0.6, 0.6}, {}});
  SceneBuilder builder(scene, Tolerance{2.0});
  ASSERT_TRUE(builder.addAxisRect(2, true, {0, 0, 0}, {1, 1, 0}, grey));
  ASSERT_TRUE(builder.addAxisRect(2, false, {0, 0, 1}, {1, 1, 1}, lightM));
  const VisibilityGraph graph = graphOf(scene);
  ASSERT_EQ(graph.interactions.size(), 1u);
  BlockerVisibility vis(scene, graph, 16);
  const RadiosityResult r = solveRadiosity(scene, vis, {});
  const double f = 0.19982;
  EXPECT_NEAR(r.patchRadiosity[0].r, 0.6 * 3 * f, 2e-3 * 0.6 * 3 * f);
  EXPECT_NEAR(r.patchRadiosity[0].b, 0.6 * 1 * f, 2e-3 * 0.6 * 1 * f);
  EXPECT_EQ(r.stats.rays, 0u);  // VISIBLE: no ray is ever cast
}

TEST(BlockerVisibilityTest, CliRunsBlockersModeAndWritesLinespaceStats) {
  // `globalvis radiosity --visibility blockers` on the Cornell box: BSP + propagation first, the
  // same output files, and the linespace statistics in stats.json.
  const auto dir = test::scratchDir();
  const auto obj = dir / "cornell.obj";
  ASSERT_EQ(test::runCli("gen cornell -o '" + obj.string() + "'").exitCode, 0);
  const auto out = dir / "out";
  const test::CliResult r = test::runCli("radiosity '" + obj.string() + "' -o '" + out.string() +
                                         "' --visibility blockers --epsilon 2e-4 -q");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_TRUE(std::filesystem::exists(out / "radiosity.txt"));
  EXPECT_TRUE(std::filesystem::exists(out / "patches.obj"));
  std::ifstream stats(out / "stats.json");
  const nlohmann::json j = nlohmann::json::parse(stats);
  EXPECT_EQ(j["visibility"], "blockers");
  EXPECT_GT(j["linespace"]["total"]["tubes"].get<uint64_t>(), 0u);
  EXPECT_GT(j["linespace"]["total"]["invisible"].get<uint64_t>(), 0u);
  EXPECT_GE(j["linespace"]["levels"].size(), 2u);
  EXPECT_GT(j["linespace"]["visibility_graph_seconds"].get<double>(), 0.0);
}

}  // namespace
}  // namespace gv
