// Hidden faces and coincident twins (bsp/hidden_faces.h): hand-built solids whose hidden faces are
// known, and on real brush-soup levels a ray oracle that shares nothing with the winding-number
// decision: a ray from air whose first hit in the original scene is the front of a dropped patch
// (with no kept patch there) would be a visible face lost.
#include "bsp/hidden_faces.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>

#include "generators/scene_builder.h"
#include "raycast/embree_scene.h"
#include "input/load_scene.h"

namespace gv {
namespace {

Scene boxes(const std::vector<std::pair<Vec3, Vec3>>& solids) {
  Scene scene;
  scene.addMaterial({});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{-10, -10, -10}, {10, 10, 10}}));
  for (const auto& [lo, hi] : solids) b.addBox(lo, hi, 0);
  return scene;
}

TEST(WindingNumber, OneInsideAnOutwardBoxZeroOutsideTwoWhereTwoOverlap) {
  const Scene one = boxes({{{0, 0, 0}, {1, 1, 1}}});
  EXPECT_NEAR(windingNumber(one, {0.5, 0.5, 0.5}), 1.0, 1e-9);
  EXPECT_NEAR(windingNumber(one, {2, 0.5, 0.5}), 0.0, 1e-9);
  const Scene two = boxes({{{0, 0, 0}, {2, 1, 1}}, {{1, 0, 0}, {3, 1, 1}}});
  EXPECT_NEAR(windingNumber(two, {1.5, 0.5, 0.5}), 2.0, 1e-9);
}

TEST(HiddenFaces, CleanSceneComesBackUnchanged) {
  const Scene scene = boxes({{{0, 0, 0}, {1, 1, 1}}, {{3, 0, 0}, {4, 2, 1}}});
  HiddenFaceReport r;
  const Scene out = removeHiddenFaces(scene, {}, &r);
  ASSERT_EQ(out.patches.size(), scene.patches.size());
  for (size_t i = 0; i < out.patches.size(); ++i)
    EXPECT_EQ(out.patches[i].polygon.vertices, scene.patches[i].polygon.vertices);
  EXPECT_FALSE(r.changed());
  EXPECT_EQ(r.partlyKept, 0u);
}

TEST(HiddenFaces, BoxOnSlabLosesItsBottomAndTheSlabTopPartlyHiddenIsKept) {
  // A 1x1x1 box standing on a 4x4 slab: the box's bottom faces into the slab (hidden); the
  // slab's top is partly under the box (kept whole by default, cut with cutPartly).
  const Scene scene = boxes({{{0, 0, -1}, {4, 4, 0}}, {{1, 1, 0}, {2, 2, 1}}});
  HiddenFaceReport r;
  const Scene out = removeHiddenFaces(scene, {}, &r);
  EXPECT_EQ(r.hidden, 1u);
  EXPECT_EQ(r.partlyKept, 1u);
  EXPECT_EQ(out.patches.size(), scene.patches.size() - 1);
  for (const Patch& p : out.patches) {  // no kept patch faces down at z = 0
    const bool bottomOfBox = p.polygon.plane.normal.z < -0.5 && std::abs(p.polygon.vertices[0].z) < 1e-9;
    EXPECT_FALSE(bottomOfBox);
  }
  HiddenFaceOptions cut;
  cut.cutPartly = true;
  HiddenFaceReport rc;
  const Scene pieces = removeHiddenFaces(scene, cut, &rc);
  EXPECT_EQ(rc.partlyHidden, 1u);
  double topArea = 0;
  for (const Patch& p : pieces.patches)
    if (p.polygon.plane.normal.z > 0.5 && std::abs(p.polygon.vertices[0].z) < 1e-9)
      topArea += p.polygon.area();
  EXPECT_NEAR(topArea, 16.0 - 1.0, 1e-6);  // the slab's top minus the box's footprint
}

TEST(HiddenFaces, FrontBeyondAirIsASolidsInsideAmongSolids) {
  // The box on the slab again: the slab's top, kept whole, looks partly into the box (a closed
  // solid); nothing else looks out of the air. Cut (cutPartly), its pieces in air do not.
  const Scene scene = boxes({{{0, 0, -1}, {4, 4, 0}}, {{1, 1, 0}, {2, 2, 1}}});
  HiddenFaceReport r;
  const Scene out = removeHiddenFaces(scene, {}, &r);
  EXPECT_FALSE(r.shells);
  ASSERT_EQ(out.beyondAirBounds.size(), out.patches.size());
  for (size_t i = 0; i < out.patches.size(); ++i) {
    const ConvexPolygon& p = out.patches[i].polygon;
    const bool slabTop = p.plane.normal.z > 0.5 && std::abs(p.vertices[0].z) < 1e-9;
    EXPECT_EQ(out.beyondAirBounds[i].empty(), !slabTop) << i;
    if (slabTop) {  // the part under the box
      EXPECT_NEAR(out.beyondAirBounds[i].lo.x, 1, 1e-6);
      EXPECT_NEAR(out.beyondAirBounds[i].hi.x, 2, 1e-6);
      EXPECT_NEAR(out.beyondAirBounds[i].lo.y, 1, 1e-6);
      EXPECT_NEAR(out.beyondAirBounds[i].hi.y, 2, 1e-6);
    }
  }
  EXPECT_EQ(r.frontBeyondAir, 1u);
  HiddenFaceOptions cut;
  cut.cutPartly = true;
  const Scene pieces = removeHiddenFaces(scene, cut);
  ASSERT_EQ(pieces.beyondAirBounds.size(), pieces.patches.size());
  for (const Aabb& box : pieces.beyondAirBounds) EXPECT_TRUE(box.empty());
}

TEST(HiddenFaces, FrontBeyondAirIsTheOutsideOnALevelOfShells) {
  // A room of six faces looking in (a 2.5D sector: air inside, winding number -1) and a small
  // closed box in the void beside it: the box's faces look into the void (0), which no air
  // reaches on such a level, though it is air on a level of solids.
  Scene scene;
  const uint32_t m = scene.addMaterial({});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{-10, -10, -10}, {10, 10, 10}}));
  b.addAxisRect(2, true, {0, 0, 0}, {10, 10, 0}, m);
  b.addAxisRect(2, false, {0, 0, 4}, {10, 10, 4}, m);
  b.addAxisRect(0, true, {0, 0, 0}, {0, 10, 4}, m);
  b.addAxisRect(0, false, {10, 0, 0}, {10, 10, 4}, m);
  b.addAxisRect(1, true, {0, 0, 0}, {10, 0, 4}, m);
  b.addAxisRect(1, false, {0, 10, 0}, {10, 10, 4}, m);
  const size_t roomFaces = scene.patches.size();
  b.addBox({2, -5, 1}, {4, -3, 3}, m);
  ASSERT_EQ(scene.patches.size(), roomFaces + 6);
  HiddenFaceReport r;
  const Scene out = removeHiddenFaces(scene, {}, &r);
  EXPECT_TRUE(r.shells);
  ASSERT_EQ(out.patches.size(), scene.patches.size());
  ASSERT_EQ(out.beyondAirBounds.size(), out.patches.size());
  for (size_t i = 0; i < out.patches.size(); ++i)
    EXPECT_EQ(out.beyondAirBounds[i].empty(), i < roomFaces) << i;
  EXPECT_EQ(r.frontBeyondAir, 6u);
}

TEST(HiddenFaces, OverlappingBrushesLoseTheFacesInsideEachOther) {
  // Two brushes overlapping in x in [1, 2]: the first's +x face lies inside the second, the
  // second's -x face inside the first; both are hidden. Their other faces are partly inside.
  const Scene scene = boxes({{{0, 0, 0}, {2, 1, 1}}, {{1, 0, 0}, {3, 1, 1}}});
  HiddenFaceReport r;
  const Scene out = removeHiddenFaces(scene, {}, &r);
  EXPECT_EQ(r.hidden, 2u);
  EXPECT_EQ(out.patches.size(), 10u);
}

TEST(HiddenFaces, CoincidentSameFacingTwinIsDroppedOppositeFacingPairBothHidden) {
  Scene scene;
  scene.addMaterial({});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{-10, -10, -10}, {10, 10, 10}}));
  b.addQuad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);  // a floor facing up
  b.addQuad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, 0);  // its twin
  b.addQuad({0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}, 0);  // a ceiling facing down
  HiddenFaceReport r;
  const Scene out = removeHiddenFaces(scene, {}, &r);
  EXPECT_EQ(r.coincident, 1u);
  EXPECT_EQ(r.hidden, 0u);
  EXPECT_EQ(out.patches.size(), 2u);
}

/// Rays from air (points just in front of kept patches, cosine directions) cast in the original
/// scene: a front hit on a dropped patch with no kept patch at the same place is a lost face.
struct RayCheck {
  size_t rays = 0, originsInSolid = 0, frontHitsOnDropped = 0, lost = 0;
};

RayCheck castFromAir(const Scene& original, const Scene& kept, size_t rays, uint32_t seed) {
  RayCheck out;
  const EmbreeScene all(original), keptBvh(kept);
  // Which original patches were kept: the output is a subsequence of the input (no cutting).
  std::vector<uint8_t> isKept(original.patches.size(), 0);
  for (size_t i = 0, j = 0; i < kept.patches.size(); ++i) {
    while (j < original.patches.size() &&
           original.patches[j].polygon.vertices != kept.patches[i].polygon.vertices)
      ++j;
    if (j < original.patches.size()) isKept[j++] = 1;
  }
  const double scale = original.tolerance().scale;
  const double offset = 1e-6 * scale, same = 1e-5 * scale;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::uniform_int_distribution<size_t> pick(0, kept.patches.size() - 1);
  for (size_t k = 0; k < rays; ++k) {
    const ConvexPolygon& poly = kept.patches[pick(rng)].polygon;
    const auto& v = poly.vertices;
    const size_t t = 1 + std::uniform_int_distribution<size_t>(0, v.size() - 3)(rng);
    double a = u(rng), b = u(rng);
    if (a + b > 1) a = 1 - a, b = 1 - b;
    const Vec3 n = poly.plane.normal;
    const Vec3 origin = v[0] + (v[t] - v[0]) * a + (v[t + 1] - v[0]) * b + n * offset;
    // A point on a partly hidden patch may lie under a solid: not air, not a start.
    if (windingNumber(original, origin) >= kSolidWindingNumber) {
      ++out.originsInSolid;
      continue;
    }
    const Vec3 tu = normalize(cross(n, std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    const Vec3 tv = cross(n, tu);
    const double r1 = u(rng), phi = 2 * 3.141592653589793 * u(rng);
    const Vec3 d = tu * (std::sqrt(r1) * std::cos(phi)) + tv * (std::sqrt(r1) * std::sin(phi)) +
                   n * std::sqrt(1 - r1);
    ++out.rays;
    const auto hit = all.firstHit(origin, d);
    if (!hit || isKept[hit->patch]) continue;
    if (dot(original.patches[hit->patch].polygon.plane.normal, d) >= 0) continue;  // its back
    ++out.frontHitsOnDropped;
    const auto keptHit = keptBvh.firstHit(origin, d);
    if (!keptHit || std::abs(keptHit->t - hit->t) > same) ++out.lost;
  }
  return out;
}

TEST(HiddenFaces, RaysFromAirNeverFirstMeetADroppedFaceOnHandBuiltSolids) {
  const Scene scene =
      boxes({{{0, 0, -1}, {4, 4, 0}}, {{1, 1, 0}, {2, 2, 1}}, {{2.5, 0.5, -0.5}, {3.5, 3, 2}}});
  const Scene out = removeHiddenFaces(scene);
  const RayCheck c = castFromAir(scene, out, 20000, 7);
  EXPECT_GT(c.rays, 15000u);
  EXPECT_EQ(c.lost, 0u);
}

// The shared brush-soup levels: thousands of hidden faces dropped, none that air can see.
TEST(HiddenFaces, RaysFromAirNeverFirstMeetADroppedFaceOnSharedArenaLevels) {
  const std::string dir = std::string(GV_SHARED_DATA_DIR) + "/levels/";
  for (const auto& [name, rays] : {std::pair{"q3-oa_ctf2.obj", 30000}, {"q3-dm4ish.obj", 15000}}) {
    if (!std::filesystem::exists(dir + name)) GTEST_SKIP() << dir + name << " not present";
    const Scene scene = loadScene(dir + name);
    HiddenFaceReport r;
    const Scene out = removeHiddenFaces(scene, {}, &r);
    EXPECT_GT(r.hidden, 100u) << name;  // the check below is not vacuous
    const RayCheck c = castFromAir(scene, out, rays, 11);
    EXPECT_EQ(c.lost, 0u) << name << ": " << c.frontHitsOnDropped << " front hits on dropped "
                          << "patches in " << c.rays << " rays, " << c.originsInSolid
                          << " origins under solids skipped";
    EXPECT_GT(c.rays, size_t(rays) / 2) << name;
  }
}

}  // namespace
}  // namespace gv
