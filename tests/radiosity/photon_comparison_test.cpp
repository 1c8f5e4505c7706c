// comparePhotons on hand-made solutions and photon estimates: leaks told apart from channels too
// dim to tell, a region off as a whole while the global L2 is small, coincident twins compared as
// one surface, and the photon power the leak rule divides by (photonReference's).
#include "radiosity/photon_comparison.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "generators/cornell_box.h"
#include "radiosity/photon_reference.h"
#include "raycast/embree_scene.h"

namespace gv {
namespace {

constexpr double kRho = 0.5;

/// Axis-aligned squares in the plane z = 0 facing up (or down), side `size`, lower corner (x, y).
void addSquare(Scene& scene, double x, double y, double size, bool up = true, double z = 0) {
  std::vector<Vec3> v{{x, y, z}, {x + size, y, z}, {x + size, y + size, z}, {x, y + size, z}};
  if (!up) std::reverse(v.begin(), v.end());
  scene.patches.push_back({*ConvexPolygon::fromVertices(v, Tolerance{100}), 0});
}

Scene greyScene() {
  Scene scene;
  scene.addMaterial({"grey", {kRho, kRho, kRho}, {}});
  return scene;
}

Rgb grey(double v) {
  return {v, v, v};
}

/// A photon estimate of `values` (B, no emitters) with relative standard error `noise` (0 where
/// the value is 0: no photon came), from `photons` photons of `power` each.
PhotonResult estimate(const std::vector<double>& values, double noise, double power) {
  PhotonResult r;
  for (const double v : values) {
    r.radiosity.push_back(grey(v));
    r.standardError.push_back(grey(noise * v));
  }
  r.photons = 1'000'000;
  r.photonPower = grey(power);
  return r;
}

TEST(PhotonComparisonTest, LitPatchWithoutPhotonsIsALeakUnlessTooDimToTell) {
  Scene scene = greyScene();
  addSquare(scene, 0, 0, 10);     // 0: lit by the solver, no photon: leak
  addSquare(scene, 20, 0, 0.01);  // 1: the same, but tiny: too dim to tell
  addSquare(scene, 40, 0, 1);     // 2: photons agree
  addSquare(scene, 60, 0, 1);     // 3: dark in both
  const std::vector<Rgb> solver{grey(1), grey(1), grey(1), grey(0)};
  const double power = 0.01;
  const PhotonResult ref = estimate({0, 0, 1, 0}, 0.001, power);
  const PhotonComparison c = comparePhotons(scene, solver, ref, 4, 0.01);
  // Expected hits: (B − Ke) / ρ · A / photon power.
  const double bigHits = 1 / kRho * 100 / power, tinyHits = 1 / kRho * 1e-4 / power;
  ASSERT_GE(bigHits, kLeakExpectedHits);
  ASSERT_LT(tinyHits, kLeakExpectedHits);
  EXPECT_EQ(c.channels.total, 12u);
  EXPECT_EQ(c.channels.compared, 3u);
  EXPECT_EQ(c.channels.noisy, 0u);
  EXPECT_EQ(c.channels.zeroPhoton, 9u);
  EXPECT_EQ(c.channels.leaks, 3u);
  EXPECT_EQ(c.channels.tooDim, 3u);
  EXPECT_EQ(c.channels.unlit, 3u);
  EXPECT_EQ(c.leakPatches, 1u);
  EXPECT_EQ(c.leakSurfaces, 1u);
  ASSERT_EQ(c.worstLeaks.size(), 3u);
  EXPECT_EQ(c.worstLeaks[0].patch, 0u);
  EXPECT_NEAR(c.worstLeaks[0].expectedHits, bigHits, 1e-9 * bigHits);
  EXPECT_DOUBLE_EQ(c.worstLeaks[0].solver, 1.0);
  // The leak holds 100 of the solution's 101.01 units of reflected power per channel.
  EXPECT_NEAR(c.leakedPowerShare, 100 / 101.0001, 1e-9);
  EXPECT_EQ(c.failures, 0u);
  // Nothing left out of the L2: the leak dominates it (Σ A b² = 300 against Σ A p² = 3).
  EXPECT_NEAR(c.l2Reflected, std::sqrt((300 + 3e-4) / 3), 1e-9);

  // Photons of 10^5 times the power (10^5 times fewer of them): the big patch is too dim too.
  const PhotonComparison dim =
      comparePhotons(scene, solver, estimate({0, 0, 1, 0}, 0.001, 1e3), 4, 0.01);
  EXPECT_EQ(dim.channels.leaks, 0u);
  EXPECT_EQ(dim.channels.tooDim, 6u);
  EXPECT_EQ(dim.leakPatches, 0u);
}

TEST(PhotonComparisonTest, RegionOffAsAWholeIsFoundWhenTheL2IsSmall) {
  Scene scene = greyScene();
  std::vector<Rgb> solver;
  std::vector<double> photons;
  auto add = [&](double x, double y, double size, double photon, double solution) {
    addSquare(scene, x, y, size);
    photons.push_back(photon);
    solver.push_back(grey(solution));
  };
  // Region (0,0,0): one 3 × 3 floor in 9 unit patches, each ±10 % (alternating), exact as a whole
  // but for the middle one.
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      add(i, j, 1, 1, (i * 3 + j) == 4 ? 1.0 : ((i * 3 + j) % 2 ? 1.1 : 0.9));
  add(3.5, 0.5, 1, 2, 2.4);  // region (1,0,0): a small room, 20 % too bright
  add(6, 0, 30, 1, 1);       // region (7,5,0): big and right
  // A noisy region (20 % photon error, below) and one below 0.1 % of the power.
  add(100, 0, 1, 1, 1.5);
  add(200, 0, 0.01, 1, 3);
  PhotonResult ref = estimate(photons, 0.001, 1e-6);
  ref.standardError[11] = grey(0.2);
  const PhotonComparison c = comparePhotons(scene, solver, ref, 4, 0.01);
  // Σ A (b − p)² = 8 × 0.01 + 0.16 + 0.25 + 4e-4 (the L2 leaves the noisy and the small
  // patch in), over Σ A p² = 9 + 4 + 900 + 1 + 1e-4.
  const double l2 = std::sqrt((8 * 0.01 + 0.16 + 0.25 + 4e-4) / (9 + 4 + 900 + 1 + 1e-4));
  EXPECT_NEAR(c.l2Reflected, l2, 1e-9);
  EXPECT_LT(c.l2Reflected, 0.03);
  // The photons' own noise: Σ A σ² = 9 × 1e-6 + 4e-6 + 900 × 1e-6 + 0.04 + 1e-4 × 1e-6, over the
  // same Σ A p².
  EXPECT_NEAR(c.l2PhotonNoise, std::sqrt((9e-6 + 4e-6 + 9e-4 + 0.04 + 1e-10) / (914 + 1e-4)),
              1e-12);
  ASSERT_TRUE(c.worstRegion.has_value());
  EXPECT_NEAR(c.worstRegion->relative, 0.2, 1e-9);
  EXPECT_EQ(c.worstRegion->low, (Vec3{3, 0, 0}));
  EXPECT_EQ(c.worstRegion->patches, 1u);
  EXPECT_NEAR(c.worstRegion->solver, 2.4, 1e-9);
  EXPECT_NEAR(c.worstRegion->photons, 2.0, 1e-9);
  EXPECT_EQ(c.regionSize, kDefaultRegionSize);
  // Five occupied cubes (the 30 × 30 floor's centroid is in one), three channels each.
  EXPECT_EQ(c.regionChannels, 15u);
  EXPECT_EQ(c.regionsCompared, 9u);
  EXPECT_EQ(c.regionsNoisy, 3u);
  EXPECT_EQ(c.regionsSmall, 3u);

  // Cubes of 10: the bright room joins the floor; the worst is then 0.4 / 11 of it.
  const PhotonComparison big = comparePhotons(scene, solver, ref, 4, 0.01, 10);
  ASSERT_TRUE(big.worstRegion.has_value());
  EXPECT_NEAR(big.worstRegion->relative, 0.4 / 11, 1e-9);
  EXPECT_EQ(big.worstRegion->patches, 10u);
}

/// The Cornell box with every patch cut by the planes x, y, z = k · `cell` (mm): many patches of
/// comparable size, so that no few of them dominate an area-weighted figure.
Scene finelyCutCornellBox(double cell) {
  const Scene box = generateCornellBox();
  const Tolerance tol = box.tolerance();
  Scene out = box;
  out.patches.clear();
  for (const Patch& patch : box.patches) {
    std::vector<ConvexPolygon> pieces{patch.polygon};
    for (int axis = 0; axis < 3; ++axis)
      for (double at = cell; at < 600; at += cell) {
        Vec3 n{0, 0, 0};
        (axis == 0 ? n.x : axis == 1 ? n.y : n.z) = 1;
        std::vector<ConvexPolygon> next;
        for (const ConvexPolygon& piece : pieces) {
          const PolygonSplit cut = split(piece, Plane{n, at}, tol);
          if (cut.on) next.push_back(*cut.on);
          if (cut.front) next.push_back(*cut.front);
          if (cut.back) next.push_back(*cut.back);
        }
        pieces = std::move(next);
      }
    for (ConvexPolygon& piece : pieces) out.patches.push_back({std::move(piece), patch.material});
  }
  return out;
}

TEST(PhotonComparisonTest, PhotonNoiseIsWhatASecondPhotonRunScores) {
  // Two independent light-tracing runs of one scene: the second, held to the first as a solution
  // would be, differs by both runs' noise, so its squared L2 should be twice the first's
  // l2PhotonNoise², in expectation (each patch is its own surface here: no twins). On the box's
  // own 19 patches one pair scattered from 0.63 to 1.36 times √2 × noise (the area weights make
  // a few big patches count most); cut into 100 mm pieces it has hundreds of comparable
  // patches, and four independent pairs are pooled. The bound holds the spread measured over
  // twelve pairs of seeds (0.87 to 1.11 per pair, so ~±6 % pooled over four) with room; it is not
  // a ratchet: a figure off by √2 (one run's noise taken for two runs') lands outside it.
  const Scene scene = finelyCutCornellBox(100);
  ASSERT_GT(scene.patches.size(), 200u);
  const EmbreeScene bvh(scene);
  double pooled = 0;
  for (uint64_t seed = 1; seed <= 7; seed += 2) {
    PhotonOptions first, second;
    first.photons = second.photons = 400'000;
    first.seed = seed;
    second.seed = seed + 1;
    const PhotonResult a = photonReference(scene, bvh, first);
    const PhotonResult b = photonReference(scene, bvh, second);
    const PhotonComparison c = comparePhotons(scene, b.radiosity, a, 4, 0.01);
    ASSERT_EQ(c.twinGroups, 0u);
    ASSERT_GT(c.l2PhotonNoise, 0);
    const double ratio = c.l2Reflected / (std::sqrt(2.0) * c.l2PhotonNoise);
    std::printf("seeds %llu, %llu: L2 %.4f, noise alone %.4f, L2 / (sqrt(2) noise) %.3f\n",
                static_cast<unsigned long long>(seed), static_cast<unsigned long long>(seed + 1),
                c.l2Reflected, c.l2PhotonNoise, ratio);
    pooled += ratio * ratio / 4;
  }
  std::printf("%zu patches; pooled: %.3f\n", scene.patches.size(), std::sqrt(pooled));
  EXPECT_GT(std::sqrt(pooled), 0.85);
  EXPECT_LT(std::sqrt(pooled), 1.15);
}

TEST(PhotonComparisonTest, CoincidentTwinsAreOneSurface) {
  Scene scene = greyScene();
  addSquare(scene, 0, 0, 2);            // 0: photons land here
  addSquare(scene, 0, 0, 2);            // 1: its twin: none land here
  addSquare(scene, 0, 0, 2, false, 0);  // 2: back to back with them: a surface of its own
  addSquare(scene, 5, 0, 1);            // 3: alone
  // The solver lights both twins alike; the photons put the surface's light on one.
  const std::vector<Rgb> solver{grey(1), grey(1), grey(0.5), grey(0.7)};
  const PhotonResult ref = estimate({1, 0, 0.5, 0.7}, 0.001, 1e-3);
  const PhotonComparison c = comparePhotons(scene, solver, ref, 4, 0.01);
  EXPECT_EQ(c.surfaces, 3u);
  EXPECT_EQ(c.twinGroups, 1u);
  EXPECT_EQ(c.twinPatches, 2u);
  EXPECT_EQ(c.channels.total, 9u);
  EXPECT_EQ(c.channels.compared, 9u);
  EXPECT_EQ(c.channels.zeroPhoton, 0u);
  EXPECT_EQ(c.channels.leaks, 0u);
  EXPECT_EQ(c.failures, 0u);
  EXPECT_NEAR(c.maxRelative, 0, 1e-12);
  EXPECT_NEAR(c.l2Reflected, 0, 1e-12);
  ASSERT_TRUE(c.worstRegion.has_value());
  EXPECT_NEAR(c.worstRegion->relative, 0, 1e-12);

  // Moved off by half its side, the empty one is a surface of its own: a leak (2 · 4 / 1e-3 =
  // 8000 hits expected).
  Scene apart = greyScene();
  addSquare(apart, 0, 0, 2);
  addSquare(apart, 0.5, 0, 2);
  addSquare(apart, 0, 0, 2, false, 0);
  addSquare(apart, 5, 0, 1);
  const PhotonComparison a = comparePhotons(apart, solver, ref, 4, 0.01);
  EXPECT_EQ(a.twinGroups, 0u);
  EXPECT_EQ(a.channels.leaks, 3u);
}

TEST(PhotonComparisonTest, PhotonPowerIsWhatOnePhotonCarries) {
  // A unit emitter (Ke 3 2 1) over a unit receiver: W = 6 summed over channels, so one photon
  // carries W · e_c / Σ e / N = e_c / N; its tally on the receiver is ρ times that.
  Scene scene;
  const uint32_t light = scene.addMaterial({"light", {0, 0, 0}, {3, 2, 1}});
  scene.addMaterial({"grey", {kRho, kRho, kRho}, {}});
  addSquare(scene, 0, 0, 1);
  scene.patches.back().material = 1;
  addSquare(scene, 0, 0, 1, false, 1);
  scene.patches.back().material = light;
  const EmbreeScene bvh(scene);
  PhotonOptions po;
  po.photons = 1000;
  po.batches = 4;
  const PhotonResult ref = photonReference(scene, bvh, po);
  ASSERT_EQ(ref.photons, 1000u);
  EXPECT_DOUBLE_EQ(ref.photonPower.r, 3.0 / 1000);
  EXPECT_DOUBLE_EQ(ref.photonPower.g, 2.0 / 1000);
  EXPECT_DOUBLE_EQ(ref.photonPower.b, 1.0 / 1000);
  // The receiver's reflected estimate is a whole number of tallies of ρ · power: photons come
  // straight from the emitter only (it reflects nothing).
  const double hits = ref.radiosity[0].r / (kRho * ref.photonPower.r);
  EXPECT_NEAR(hits, std::round(hits), 1e-6);
  EXPECT_GT(hits, 100);
}

}  // namespace
}  // namespace gv
