// Patches whose front looks into a sealed slab thinner than the tolerance (patch_search.cpp,
// placeAcrossThinSlabs): the planes of a brush's two faces on either side of a tiny bevel meet a
// hair in front of it, the BSP cuts a wedge of a cell there whose faces are all too thin to be
// portals, and the search from the bevel saw nothing. Its pairs with the room must be listed.
#include <gtest/gtest.h>

#include <algorithm>

#include "generators/scene_builder.h"
#include "visibility/listed_pairs.h"
#include "visibility/propagation.h"
#include "visibility/ray_oracle.h"

namespace gv {
namespace {

using test::listed;

TEST(ThinSlabs, BevelFacingIntoASealedWedgeIsListedWithTheRoom) {
  // A room [0, 128] x [0, 128] x [0, 64] holding a sloped beam from q3-oa_rpg3dm2 (patches
  // 3681-3686 there): between its lower face (slope -0.5) and its upper one (slope 2) a bevel B
  // at y = 31.875 only 5.6e-4 tall faces -y; the two faces' planes meet 2.2e-4 in front of B.
  // The room is that large so that the wedge's faces are slivers at its model tolerance (in a
  // room half as wide the upper one was kept as a portal, and B was searched through it).
  Scene scene;
  const Aabb room{{0, 0, 0}, {128, 128, 64}};
  SceneBuilder b(scene, Tolerance::forBounds(room));
  const uint32_t m = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  b.addAxisRect(2, true, {0, 0, 0}, {128, 128, 0}, m);     // floor
  b.addAxisRect(2, false, {0, 0, 64}, {128, 128, 64}, m);  // ceiling
  const auto wall = static_cast<uint32_t>(scene.patches.size());
  b.addAxisRect(1, true, {0, 0, 0}, {128, 0, 64}, m);  // the wall B looks at
  b.addAxisRect(1, false, {0, 128, 0}, {128, 128, 64}, m);
  b.addAxisRect(0, true, {0, 0, 0}, {0, 128, 64}, m);
  b.addAxisRect(0, false, {128, 0, 0}, {128, 128, 64}, m);
  ASSERT_EQ(scene.patches.size(), wall + 4);
  const auto first = static_cast<uint32_t>(scene.patches.size());
  ASSERT_TRUE(b.addPolygon({{31.5, 31.875, 12.25},
                            {31.5, 31.875, 12.250559},
                            {31.5, 31.999721, 12.5},
                            {31.5, 32.0, 12.5},
                            {31.5, 36.0, 10.5},
                            {31.5, 35.875, 10.25}},
                           m));
  ASSERT_TRUE(b.addPolygon({{32.5, 32.0, 12.5},
                            {32.5, 31.999721, 12.5},
                            {32.5, 31.875, 12.250559},
                            {32.5, 31.875, 12.25},
                            {32.5, 35.875, 10.25},
                            {32.5, 36.0, 10.5}},
                           m));
  const auto bevel = static_cast<uint32_t>(scene.patches.size());
  ASSERT_TRUE(b.addPolygon({{32.5, 31.875, 12.25},
                            {32.5, 31.875, 12.250559},
                            {31.5, 31.875, 12.250559},
                            {31.5, 31.875, 12.25}},
                           m));
  ASSERT_TRUE(b.addPolygon({{31.5, 35.874999, 10.25},
                            {31.5, 35.999999, 10.500001},
                            {32.5, 35.999999, 10.500001},
                            {32.5, 35.874999, 10.25}},
                           m));
  ASSERT_TRUE(b.addPolygon({{32.5, 31.875, 12.25056},
                            {32.5, 31.99972, 12.5},
                            {31.5, 31.99972, 12.5},
                            {31.5, 31.875, 12.25056}},
                           m));
  ASSERT_TRUE(b.addPolygon({{32.5, 35.874999, 10.25},
                            {32.5, 31.875, 12.249999},
                            {31.5, 31.875, 12.249999},
                            {31.5, 35.874999, 10.25}},
                           m));
  ASSERT_EQ(scene.patches.size(), first + 6);
  ASSERT_LT(scene.patches[bevel].polygon.normal().y, 0);

  // The witness, by the brute-force ray caster: from B's middle, down and along -y, the first
  // hit is the wall's front.
  const Vec3 origin{32, 31.875, 12.25028};
  const auto hit = test::firstHit(scene, origin, normalize(Vec3{0.05, -1, -0.2}), 0, 1e9, bevel);
  ASSERT_TRUE(hit);
  EXPECT_EQ(hit->patch, wall);
  EXPECT_TRUE(hit->front);

  BspOptions bsp;
  bsp.minCoverage = 0;  // every plane: the beam's faces' planes cut the wedge in front of B
  const Subdivision sub = buildSubdivision(scene, bsp);
  // The cell in front of B: the wedge, with no portal.
  bool sealedWedge = false;
  for (const Cell& cell : sub.cells)
    if (std::binary_search(cell.facingPatches.begin(), cell.facingPatches.end(), bevel) &&
        cell.portals.empty())
      sealedWedge = true;
  ASSERT_TRUE(sealedWedge);
  const VisibilityGraph g = computeVisibility(scene, sub, PropagationOptions{});
  EXPECT_GT(g.stats.acrossThinSlabPieces, 0u);
  // Without the pieces across the wedge (tried), B is listed with nothing.
  EXPECT_TRUE(listed(g, bevel, wall));
}

}  // namespace
}  // namespace gv
