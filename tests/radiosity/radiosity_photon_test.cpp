// Hierarchical radiosity against an independent Monte Carlo light tracer (photonReference: no
// form factors, no mesh) on real scenes: the Cornell box and the default office. Per patch and
// channel, the solver's area-weighted mean radiosity must match the photon estimate within the
// photon noise plus a small discretisation allowance.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <utility>

#include "generators/cornell_box.h"
#include "generators/office.h"
#include "generators/scene_builder.h"
#include "input/load_scene.h"
#include "radiosity/furnace_scene.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/photon_comparison.h"
#include "radiosity/photon_reference.h"
#include "radiosity/polygon_sampling.h"
#include "radiosity/radiosity_quality.h"
#include "radiosity/ray_visibility.h"
#include "raycast/embree_scene.h"
#include "scene/contact_split.h"
#include "support/shared_levels.h"

namespace gv {
namespace {

/// Allowed per-patch deviation: this many photon standard errors plus a fraction of the value
/// (the solver's discretisation error at default options; per scene below).
constexpr double kSigmas = 4.0;

/// Solver (defaults, `rays`, 16 rays per link) against photons: every meaningful patch channel
/// within kSigmas standard errors plus `allowance`; the mean signed error within `meanBias`.
void checkAgainstPhotons(const Scene& scene, uint64_t photons, size_t minCompared, double allowance,
                         double meanBias) {
  const EmbreeScene bvh(scene);
  RayVisibility visibility(scene, bvh, 16);
  const RadiosityResult r = solveRadiosity(scene, visibility);
  EXPECT_TRUE(r.stats.converged);
  PhotonOptions po;
  po.photons = photons;
  const PhotonResult ref = photonReference(scene, bvh, po);
  const PhotonComparison c = comparePhotons(scene, r.patchRadiosity, ref, kSigmas, allowance);
  std::printf(
      "compared %zu patch channels: max %.4f rms %.4f mean signed %+.4f, %zu beyond "
      "tolerance; %llu photon rays\n",
      c.compared, c.maxRelative, c.rmsRelative, c.meanSigned, c.failures,
      static_cast<unsigned long long>(ref.rays));
  ::testing::Test::RecordProperty("max_relative_error", std::to_string(c.maxRelative));
  ::testing::Test::RecordProperty("rms_relative_error", std::to_string(c.rmsRelative));
  ::testing::Test::RecordProperty("mean_signed_error", std::to_string(c.meanSigned));
  EXPECT_GE(c.compared, minCompared);
  EXPECT_EQ(c.failures, 0u);
  EXPECT_LT(std::abs(c.meanSigned), meanBias);
  // Everything counted (issue #18 item 3): no leak, and every surface channel accounted for.
  std::printf(
      "L2 of B-Ke %.4f; %zu leaks, %zu too dim, %zu unlit, %zu noisy of %zu channels; worst "
      "region %+.4f of %zu compared\n",
      c.l2Reflected, c.channels.leaks, c.channels.tooDim, c.channels.unlit, c.channels.noisy,
      c.channels.total, c.worstRegion ? c.worstRegion->relative : 0.0, c.regionsCompared);
  EXPECT_EQ(c.channels.leaks, 0u);
  EXPECT_EQ(c.channels.total, 3 * c.surfaces);
  EXPECT_EQ(c.channels.compared + c.channels.noisy + c.channels.zeroPhoton, c.channels.total);
  EXPECT_EQ(c.channels.leaks + c.channels.tooDim + c.channels.unlit, c.channels.zeroPhoton);
}

TEST(PhotonReferenceTest, EmitterOverReceiverGivesRhoEF) {
  // The photon tracer itself against Howell C-11 (unit squares 1 apart: F = 0.19982).
  Scene scene;
  const uint32_t light = scene.addMaterial({"light", {0, 0, 0}, {3, 2, 1}});
  const uint32_t grey = scene.addMaterial({"grey", {0.6, 0.6, 0.6}, {}});
  SceneBuilder builder(scene, Tolerance{2.0});
  ASSERT_TRUE(builder.addAxisRect(2, true, {0, 0, 0}, {1, 1, 0}, grey));
  ASSERT_TRUE(builder.addAxisRect(2, false, {0, 0, 1}, {1, 1, 1}, light));
  const EmbreeScene bvh(scene);
  PhotonOptions po;
  po.photons = 400'000;
  const PhotonResult ref = photonReference(scene, bvh, po);
  const double expected = 0.6 * 3 * 0.19982;
  EXPECT_NEAR(ref.radiosity[0].r, expected, 4 * ref.standardError[0].r);
  EXPECT_LT(ref.standardError[0].r, 0.01 * expected);
  EXPECT_EQ(ref.radiosity[1], (Rgb{3, 2, 1}));
}

TEST(PhotonReferenceTest, FurnaceGivesEOverOneMinusRho) {
  Scene scene;
  const uint32_t m = scene.addMaterial({"glow", {0.7, 0.5, 0.3}, {1, 1, 1}});
  SceneBuilder builder(scene, Tolerance{4.0});
  testing::addInwardBox(builder, {0, 0, 0}, {1, 2, 1.5}, m, 1);
  const EmbreeScene bvh(scene);
  PhotonOptions po;
  po.photons = 300'000;
  const PhotonResult ref = photonReference(scene, bvh, po);
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    EXPECT_NEAR(ref.radiosity[p].r, 1 / 0.3, 4 * ref.standardError[p].r + 1e-9) << p;
    EXPECT_NEAR(ref.radiosity[p].b, 1 / 0.7, 4 * ref.standardError[p].b + 1e-9) << p;
  }
}

/// The scene as `globalvis radiosity` solves it: patches cut along contacts (contact_split.h).
Scene splitAtContacts(Scene scene) {
  splitPatchesAtContacts(scene);
  return scene;
}

/// The patches of a shared level whose boxes meet `box`, split at their contacts as the
/// pipeline splits them; every emitter but `onlyLamp`'s material off when it is given.
Scene cutLevel(const std::string& path, const Aabb& box, const std::string& onlyLamp = {}) {
  const Scene level = loadScene(path);
  Scene cut;
  for (Material m : level.materials) {
    if (!onlyLamp.empty() && m.name != onlyLamp) m.emission = {};
    cut.addMaterial(m);
  }
  for (const Patch& p : level.patches) {
    Aabb b;
    for (const Vec3& v : p.polygon.vertices) b.add(v);
    if (b.lo.x <= box.hi.x && b.hi.x >= box.lo.x && b.lo.y <= box.hi.y && b.hi.y >= box.lo.y &&
        b.lo.z <= box.hi.z && b.hi.z >= box.lo.z)
      cut.patches.push_back(p);
  }
  return splitAtContacts(std::move(cut));
}

// The allowances are the measured solver-vs-photon differences at default options plus a
// margin for the photon noise of 2 M photons (measured with 4 M on 2026-12-01, rays mode:
// Cornell mean -0.1 %, RMS 1.2 %, worst patch channel 6.5 % on the dim side of the short block;
// office mean -0.8 %, RMS 1.2 %, worst 5.5 %). Without the contact split the office was 2.6 %
// dark on average: quadtree leaves straddling the foot of a wall or the outline of a light panel
// hanging under the ceiling spread the light of their open part over the covered part, which
// re-emitted it into backs.
TEST(RadiosityPhotonTest, CornellBoxMatchesLightTracing) {
  checkAgainstPhotons(splitAtContacts(generateCornellBox()), 2'000'000, 60, 0.05, 0.005);
}

TEST(RadiosityPhotonTest, DefaultOfficeMatchesLightTracing) {
  checkAgainstPhotons(splitAtContacts(generateOffice()), 2'000'000, 400, 0.04, 0.012);
}

TEST(RadiosityPhotonTest, PartialLinksGatherThePartOfTheSourceInView) {
  // One room and its corridor under one floor patch and one ceiling patch (the office
  // generator's storey slabs span both), the wall between them up to the ceiling, lights in
  // both; only floor and ceiling reflect. The ceiling's light is the floor's, through links that
  // the partition wall makes Partial. Gathering the floor element's mean through them was 5.8 %
  // dark on the ceiling against light tracing (the room's ceiling sees the room's floor, not the
  // corridor's); through the links' clear samples (taps) it is 2.1 %.
  OfficeOptions o;
  o.rows = 1;
  o.columns = 1;
  o.doors = false;
  o.windows = false;
  o.furniture = false;
  Scene scene = generateOffice(o);
  for (Material& m : scene.materials)
    if (m.name != "floor" && m.name != "ceiling") m.reflectance = {0, 0, 0};
  const EmbreeScene bvh(scene);
  RayVisibility visibility(scene, bvh, 16);
  const RadiosityResult r = solveRadiosity(scene, visibility);
  PhotonOptions po;
  po.photons = 2'000'000;
  const PhotonResult ref = photonReference(scene, bvh, po);
  size_t ceiling = 0;
  double largest = 0;
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const double a = scene.patches[p].polygon.area();
    if (scene.materials[scene.patches[p].material].name == "ceiling" && a > largest) {
      largest = a;
      ceiling = p;
    }
  }
  ASSERT_GT(largest, 0.0);
  for (int ch = 0; ch < 3; ++ch) {
    const double s = ch == 0
                         ? r.patchRadiosity[ceiling].r
                         : (ch == 1 ? r.patchRadiosity[ceiling].g : r.patchRadiosity[ceiling].b);
    const Rgb& m = ref.radiosity[ceiling];
    const Rgb& e = ref.standardError[ceiling];
    const double mv = ch == 0 ? m.r : (ch == 1 ? m.g : m.b);
    const double ev = ch == 0 ? e.r : (ch == 1 ? e.g : e.b);
    ASSERT_GT(mv, 0.0);
    EXPECT_LT(ev, 0.01 * mv);
    EXPECT_NEAR(s, mv, 0.03 * mv + 4 * ev) << "channel " << ch;
  }
}

/// bench/scenes/cabinet_slot.obj with the cabinet's back cut into three upright strips: a 5 x 5 x 3
/// room lit by a ceiling panel, and a cabinet whose back stands 0.089 from the wall x = 5,
/// across a slot open at its top and its two ends.
Scene cabinetSlotInStrips() {
  Scene scene;
  const uint32_t wall = scene.addMaterial({"wall", {0.75, 0.73, 0.68}, {}});
  const uint32_t floor = scene.addMaterial({"floor", {0.45, 0.4, 0.35}, {}});
  const uint32_t ceiling = scene.addMaterial({"ceiling", {0.8, 0.8, 0.78}, {}});
  const uint32_t cabinet = scene.addMaterial({"cabinet", {0.5, 0.55, 0.6}, {}});
  const uint32_t light = scene.addMaterial({"light", {0.8, 0.8, 0.8}, {10, 10, 10}});
  Aabb box;
  box.add({0, 0, 0});
  box.add({5, 5, 3});
  SceneBuilder b(scene, Tolerance::forBounds(box));
  b.addAxisRect(0, true, {0, 0, 0}, {0, 5, 3}, wall);
  b.addAxisRect(0, false, {5, 0, 0}, {5, 5, 3}, wall);
  b.addAxisRect(1, true, {0, 0, 0}, {5, 0, 3}, wall);
  b.addAxisRect(1, false, {0, 5, 0}, {5, 5, 3}, wall);
  b.addAxisRect(2, true, {0, 0, 0}, {5, 5, 0}, floor);
  b.addAxisRect(2, false, {0, 0, 3}, {5, 5, 3}, ceiling);
  b.addAxisRect(2, false, {2, 2, 2.98}, {3, 3, 2.98}, light);
  const double x0 = 4.2, x1 = 4.911, y0 = 2.2, y1 = 2.76, top = 1.716;
  b.addAxisRect(0, false, {x0, y0, 0}, {x0, y1, top}, cabinet);
  for (const auto& [lo, hi] : {std::pair{2.2, 2.34}, {2.34, 2.62}, {2.62, 2.76}})
    b.addAxisRect(0, true, {x1, lo, 0}, {x1, hi, top}, cabinet);
  b.addAxisRect(1, false, {x0, y0, 0}, {x1, y0, top}, cabinet);
  b.addAxisRect(1, true, {x0, y1, 0}, {x1, y1, top}, cabinet);
  b.addAxisRect(2, true, {x0, y0, top}, {x1, y1, top}, cabinet);
  return splitAtContacts(std::move(scene));
}

TEST(RadiosityPhotonTest, LightEnteringASlotLandsWhereItEnters) {
  // Light reaches the slot behind the cabinet through its mouths, mostly through links from the
  // room that are Partial, whose few clear samples pass the mouths. Each sample's light used to
  // be spread over a piece of the receiver as large as the sample's share of the link's light
  // (the whole receiver, for a link with one clear sample): the light entering at the slot's
  // ends was spread over its middle, where it escapes less often, and the slot trapped it. The
  // middle strip of the cabinet's back was 1.86x light tracing (rays, `high`, this test).
  // Landing each sample's light at the leaf it ends on: 1.29x (measured 2026-12-07). The bound
  // 1.6 lies between the two; the rest of the excess is the crevice bias that remains (a
  // ratchet, not a bound on what is right: light tracing is the answer).
  const Scene scene = cabinetSlotInStrips();
  size_t middle = scene.patches.size();
  for (size_t p = 0; p < scene.patches.size(); ++p) {
    const ConvexPolygon& poly = scene.patches[p].polygon;
    const Vec3 c = poly.centroid();
    if (poly.plane.normal.x > 0.99 && std::abs(c.x - 4.911) < 1e-6 && std::abs(c.y - 2.48) < 1e-6)
      middle = p;
  }
  ASSERT_LT(middle, scene.patches.size());
  const EmbreeScene bvh(scene);
  RayVisibility visibility(scene, bvh, 16);
  RadiosityOptions options;
  applyRadiosityQuality(RadiosityQuality::High, options);
  const RadiosityResult r = solveRadiosity(scene, visibility, options);
  EXPECT_TRUE(r.stats.converged);
  PhotonOptions po;
  po.photons = 4'000'000;
  const PhotonResult ref = photonReference(scene, bvh, po);
  const double solver = r.patchRadiosity[middle].r, photons = ref.radiosity[middle].r;
  const double error = ref.standardError[middle].r;
  std::printf("middle of the slot: solver %.4g, photons %.4g +- %.2g: x%.2f\n", solver, photons,
              error, solver / photons);
  RecordProperty("slot_middle_over_photons", std::to_string(solver / photons));
  ASSERT_GT(photons, 0.0);
  EXPECT_LT(error, 0.03 * photons);  // the reference can tell
  EXPECT_LT(solver / photons, 1.6);
  EXPECT_GT(solver / photons, 0.8);
}

TEST(RadiosityPhotonTest, CeilingOverALampSeesTheDarkTopsOfPillarsNotTheirMeans) {
  // A room of the shared level lit-doom-fd2-map03, cut out with one lamp: a 0.25-unit panel
  // under a ceiling beam, beside a wall, 19 units above the floor. The ceiling 12 units higher
  // is lit only by what the room sends up: walls and two floor-to-ceiling pillars that are bright
  // at the bottom and dark at the top, next to it. Gathering those sources' means puts it 76 %
  // over light tracing; the source-consistency check (RadiosityOptions::sourceEpsilon) brings it
  // to ~16 % at `high`. The 25 % bound is a ratchet over today's error, not a derived bound:
  // it fails without the check (76 %) and at sourceEpsilon 0.1 (36 %).
  const std::string path = test::sharedLevelPath("lit-doom-fd2-map03");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  Scene room = cutLevel(path, {{-43, 5, -16}, {-27, 13, 17}}, "light_s84_0");
  ASSERT_EQ(room.emitterCount(), 1u);
  ASSERT_GT(room.patches.size(), 150u);
  const EmbreeScene bvh(room);
  RayVisibility visibility(room, bvh, 16);
  RadiosityOptions options;
  applyRadiosityQuality(RadiosityQuality::High, options);
  const RadiosityResult r = solveRadiosity(room, visibility, options);
  PhotonOptions po;
  po.photons = 2'000'000;
  const PhotonResult ref = photonReference(room, bvh, po);
  double solver = 0, photons = 0, variance = 0, area = 0;
  for (size_t p = 0; p < room.patches.size(); ++p) {
    const ConvexPolygon& poly = room.patches[p].polygon;
    const Vec3 c = poly.centroid();
    if (room.materials[room.patches[p].material].name != "ceiling" || c.z < 16 || c.x < -42 ||
        c.x > -28 || c.y < 6 || c.y > 12)
      continue;
    const double a = poly.area();
    solver += a * r.patchRadiosity[p].r;
    photons += a * ref.radiosity[p].r;
    variance += a * a * ref.standardError[p].r * ref.standardError[p].r;
    area += a;
  }
  ASSERT_GT(area, 50.0);
  const double relative = solver / photons - 1;
  std::printf(
      "ceiling over the lamp: solver %.4g, photons %.4g (standard error %.2f %%): %+.1f %%\n",
      solver / area, photons / area, 100 * std::sqrt(variance) / photons, 100 * relative);
  RecordProperty("ceiling_relative_error", std::to_string(relative));
  EXPECT_LT(std::sqrt(variance) / photons, 0.02);  // the reference can tell
  EXPECT_LT(std::abs(relative), 0.25);
}

TEST(RadiosityPhotonTest, TapsReadTheLeavesThatRefinementCutLaterNotTheirMean) {
  // A strip of wall on lit-q3-dm4ish facing the void outside the level, 0.5 units wide and 5
  // high, sees the far, dark end of a 205-unit ceiling whose other end is lit. Its partial link
  // to that ceiling was made while the ceiling was one element, and its clear samples (taps)
  // read the element at their end; refinement then cut the ceiling into 240 leaves. A tap that
  // went on reading the whole ceiling's mean lit the strip ~14x over what its view of the
  // leaves gives (light tracing saw it dark: a leak). The check: the strip's radiosity against
  // a gather of the solution's own leaves by cosine-weighted rays (independent visibility, no
  // links), B − E = ρ · mean B(hit leaf). The factor-2 bound is loose on purpose: the gather
  // has ~5 % noise and the solver's links their own sampling error, while the defect is 14x.
  const std::string path = test::sharedLevelPath("lit-q3-dm4ish");
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const Scene cut = cutLevel(path, {{-2, -30, -14}, {30, 5, 8}});
  const EmbreeScene bvh(cut);
  RayVisibility visibility(cut, bvh, 16);
  RadiosityOptions options;
  applyRadiosityQuality(RadiosityQuality::High, options);
  const RadiosityResult r = solveRadiosity(cut, visibility, options);
  double solver = 0, gathered = 0, area = 0;
  SplitMix64 rng(17);
  for (size_t p = 0; p < cut.patches.size(); ++p) {
    const ConvexPolygon& poly = cut.patches[p].polygon;
    const Vec3 c = poly.centroid();
    if (!(poly.plane.normal.x > 0.99 && std::abs(c.x - 3) < 1e-3 && c.y > -28.5 && c.y < -28 &&
          c.z > 0.5 && c.z < 5.5))
      continue;
    const double a = poly.area();
    constexpr int kRays = 20000;
    double sum = 0;
    for (int i = 0; i < kRays; ++i) {
      const Vec3 x = uniformPoint(poly.vertices, rng);
      const Vec3 d = cosineDirection(poly.plane.normal, rng);
      const std::optional<RayHit> hit = bvh.firstHit(x, d, INFINITY, static_cast<uint32_t>(p));
      if (!hit) continue;  // the void: nothing to gather
      if (dot(d, cut.patches[hit->patch].polygon.plane.normal) >= 0) continue;  // a back
      sum += r.elementRadiosity[r.elements.deepestContaining(hit->patch, x + d * hit->t)].r;
    }
    solver += a * r.patchRadiosity[p].r;
    gathered += a * cut.materials[cut.patches[p].material].reflectance.r * sum / kRays;
    area += a;
  }
  ASSERT_GT(area, 2.0);  // the strip is there (two patches after the contact split)
  ASSERT_GT(gathered, 0.0);
  std::printf("wall strip facing the void: solver %.4g, gathered from the leaves %.4g: x%.2f\n",
              solver / area, gathered / area, solver / gathered);
  RecordProperty("strip_over_gather", std::to_string(solver / gathered));
  EXPECT_LT(solver / gathered, 2.0);
  EXPECT_GT(solver / gathered, 0.5);
}

}  // namespace
}  // namespace gv
