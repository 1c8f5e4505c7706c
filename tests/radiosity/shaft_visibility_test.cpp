// `shaft` link visibility (Haines & Wallace 1991): the segment-polygon test against brute force,
// candidate lists that never miss a blocker Embree finds, and the same solution as `rays` (which
// samples the same segments against the whole scene).
#include "radiosity/shaft_visibility.h"

#include <gtest/gtest.h>

#include <cmath>

#include "generators/cornell_box.h"
#include "generators/office.h"
#include "generators/scene_builder.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/polygon_sampling.h"
#include "radiosity/ray_visibility.h"
#include "raycast/embree_scene.h"

namespace gv {
namespace {

TEST(ShaftVisibilityTest, SegmentCrossingAgreesWithEmbreeOnRandomSegments) {
  const Scene scene = generateCornellBox();
  const EmbreeScene bvh(scene);
  const Aabb box = scene.bounds();
  const double eps = scene.tolerance().length();
  SplitMix64 rng(3);
  auto randomPoint = [&] {
    const Vec3 e = box.extent();
    return box.lo + Vec3{e.x * rng.uniform(), e.y * rng.uniform(), e.z * rng.uniform()};
  };
  int blocked = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 from = randomPoint(), to = randomPoint();
    bool ours = false;
    for (const Patch& p : scene.patches)
      ours = ours || segmentCrossesPolygon(from, to, p.polygon, eps);
    ASSERT_EQ(ours, bvh.occluded(from, to)) << i;
    blocked += ours;
  }
  EXPECT_GT(blocked, 2000);  // the sample exercises both answers
}

TEST(ShaftVisibilityTest, MatchesRaysModeOnTheCornellBox) {
  // Same seed, same segments where both sample; but a link whose shaft is empty is proven
  // visible (no sampling uncertainty to refine away), so the two refine differently and agree to
  // the solver's discretisation error (about 1 % at epsilon 1e-4), not bit for bit.
  const Scene scene = generateCornellBox();
  const EmbreeScene bvh(scene);
  RayVisibility rays(scene, bvh, 16);
  ShaftVisibility shaft(scene, 16);
  RadiosityOptions options;
  options.epsilon = 1e-4;
  const RadiosityResult r = solveRadiosity(scene, rays, options);
  const RadiosityResult s = solveRadiosity(scene, shaft, options);
  EXPECT_TRUE(s.stats.converged);
  ASSERT_EQ(r.patchRadiosity.size(), s.patchRadiosity.size());
  for (size_t p = 0; p < r.patchRadiosity.size(); ++p) {
    EXPECT_NEAR(s.patchRadiosity[p].r, r.patchRadiosity[p].r, 2e-2 * r.patchRadiosity[p].r) << p;
    EXPECT_NEAR(s.patchRadiosity[p].b, r.patchRadiosity[p].b, 2e-2 * r.patchRadiosity[p].b) << p;
  }
  // Culling pays: links with nothing in their shaft cast no rays.
  EXPECT_LT(s.stats.rays, r.stats.rays);
  EXPECT_EQ(s.stats.visibility, "shaft");
}

TEST(ShaftVisibilityTest, EmptyShaftIsVisibleWithoutRays) {
  // Two facing squares and a third patch off to the side: nothing meets their hull.
  Scene scene;
  const uint32_t m = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  SceneBuilder builder(scene, Tolerance{3.0});
  ASSERT_TRUE(builder.addAxisRect(2, true, {0, 0, 0}, {1, 1, 0}, m));
  ASSERT_TRUE(builder.addAxisRect(2, false, {0, 0, 1}, {1, 1, 1}, m));
  ASSERT_TRUE(builder.addAxisRect(0, true, {2, 0, 0}, {2, 1, 1}, m));
  ShaftVisibility shaft(scene, 8);
  ElementTree tree(scene);
  const VisibilityEstimate v = shaft.estimate(tree[0], tree[1], kNoTube, 1);
  EXPECT_EQ(v.status, VisibilityStatus::Visible);
  EXPECT_EQ(v.raysCast, 0u);
  EXPECT_EQ(v.fraction, 1.0);
}

}  // namespace
}  // namespace gv
