// Patches the BSP moved onto a plane tilted from their own (patch_search.cpp,
// placeAcrossCoplanarPortals): the patch sits in a wedge of a cell a hair thick between the tilted
// plane and its own, and its front looks out of the wedge through an opening that lies along it.
// Its pairs with the room above must be listed; on a scene without such wedges nothing is added.
#include <gtest/gtest.h>

#include "generators/cornell_box.h"
#include "generators/office.h"
#include "generators/scene_builder.h"
#include "visibility/listed_pairs.h"
#include "visibility/propagation.h"
#include "visibility/ray_oracle.h"

namespace gv {
namespace {

using test::listed;

TEST(AcrossOpenings, RampFaceMovedOntoATiltedFloorSeesTheRoom) {
  // A room x in [0, 100], y in [-50, 100], z up to 50. Its floor: B at z = 0 for y < 0, then A
  // and C on the plane z = 3e-5 y, tilted from B's by 3e-5 rad. All of A lies within the model
  // tolerance of B's plane, so the BSP splits on B's plane and puts A on it; C does not, and its
  // plane (A's own) then cuts a wedge between the two planes, 6e-4 thick at A's far edge, whose
  // top over A is an opening into the room (lq_e4m4.map has a ramp face in such a wedge). Without
  // the pieces across that opening the search from A saw neither the ceiling nor the walls, and
  // `verify` found rays from A meeting them.
  Scene scene;
  const Aabb room{{0, -50, 0}, {100, 100, 50}};
  SceneBuilder b(scene, Tolerance::forBounds(room));
  const uint32_t m = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  const double tilt = 3e-5, h = 50;
  auto floorZ = [&](double y) { return tilt * y; };
  const auto first = static_cast<uint32_t>(scene.patches.size());
  ASSERT_EQ(b.addQuad({0, -50, 0}, {100, -50, 0}, {100, 0, 0}, {0, 0, 0}, m), 1);  // B
  const auto a = static_cast<uint32_t>(scene.patches.size());
  ASSERT_EQ(b.addQuad({0, 0, 0}, {100, 0, 0}, {100, 20, floorZ(20)}, {0, 20, floorZ(20)}, m), 1);
  ASSERT_EQ(b.addQuad({0, 20, floorZ(20)}, {100, 20, floorZ(20)}, {100, 100, floorZ(100)},
                      {0, 100, floorZ(100)}, m),
            1);  // C
  const auto ceiling = static_cast<uint32_t>(scene.patches.size());
  ASSERT_EQ(b.addQuad({0, -50, h}, {0, 100, h}, {100, 100, h}, {100, -50, h}, m), 1);
  ASSERT_EQ(b.addQuad({0, -50, 0}, {0, -50, h}, {100, -50, h}, {100, -50, 0}, m), 1);
  ASSERT_EQ(
      b.addQuad({0, 100, floorZ(100)}, {100, 100, floorZ(100)}, {100, 100, h}, {0, 100, h}, m), 1);
  ASSERT_EQ(b.addQuad({0, -50, 0}, {0, 100, floorZ(100)}, {0, 100, h}, {0, -50, h}, m), 1);
  ASSERT_EQ(b.addQuad({100, -50, 0}, {100, -50, h}, {100, 100, h}, {100, 100, floorZ(100)}, m), 1);
  const auto end = static_cast<uint32_t>(scene.patches.size());
  ASSERT_EQ(end - first, 8u);

  // The witness, by the brute-force ray caster: straight up from A's middle, the first hit is
  // the ceiling's front.
  const auto up = test::firstHit(scene, {50, 10, floorZ(10)}, {0, 0, 1}, 0, 1e9, a);
  ASSERT_TRUE(up);
  EXPECT_EQ(up->patch, ceiling);
  EXPECT_TRUE(up->front);

  const Subdivision sub = buildSubdivision(scene);
  const VisibilityGraph g = computeVisibility(scene, sub, PropagationOptions{});
  EXPECT_GT(g.stats.acrossPortalPieces, 0u);
  // A sees the ceiling and all four walls (and B, grazing: the floor bends up by 3e-5 at A's
  // near edge); A and C lie in one plane and do not see each other.
  for (uint32_t t = ceiling; t < end; ++t) EXPECT_TRUE(listed(g, a, t)) << t;
  EXPECT_FALSE(listed(g, a, a + 1));
}

TEST(AcrossOpenings, NothingIsAddedOnTheGeneratedScenes) {
  // The office (axis-aligned) and the Cornell box (its boxes turned about z): no patch lies on a
  // plane tilted from its own, so every opening of a cell is off the patches, and no piece is
  // added (the pieces cost searches and pairs).
  for (const Scene& scene : {generateOffice(), generateCornellBox()}) {
    const Subdivision sub = buildSubdivision(scene);
    const VisibilityGraph g = computeVisibility(scene, sub, PropagationOptions{});
    EXPECT_EQ(g.stats.acrossPortalPieces, 0u);
    EXPECT_GT(g.interactions.size(), 0u);
  }
}

}  // namespace
}  // namespace gv
