// The BSP tree of paper §3: plane merging, cells that partition the root volume, the stop rule.
#include "bsp/bsp_tree.h"

#include <gtest/gtest.h>

#include "bsp/bsp_oracle.h"
#include "bsp/bsp_scenes.h"
#include "bsp/plane_set.h"
#include "bsp/subdivision.h"
#include "generators/office.h"

namespace gv {
namespace {

using namespace bsptest;

double boxVolume(const Aabb& b) {
  const Vec3 e = b.extent();
  return e.x * e.y * e.z;
}

TEST(BspPlaneSet, MergesCoplanarPatchesEitherFacing) {
  const Scene s = messy();
  const PlaneSet planes = PlaneSet::fromScene(s, s.tolerance());
  // Patches 0-3 lie in z = 0 (patch 2 facing down), 4-6 in x = 4, 7-8 in z ~ 1.
  for (uint32_t i : {1u, 2u, 3u}) EXPECT_EQ(planes.of(i).plane, planes.of(0).plane);
  EXPECT_TRUE(planes.of(0).facesAlong);
  EXPECT_FALSE(planes.of(2).facesAlong);
  EXPECT_EQ(planes.of(5).plane, planes.of(4).plane);
  EXPECT_EQ(planes.of(6).plane, planes.of(4).plane);
  EXPECT_EQ(planes.of(8).plane, planes.of(7).plane);
  EXPECT_NE(planes.of(7).plane, planes.of(0).plane);
  EXPECT_NE(planes.of(4).plane, planes.of(0).plane);
}

TEST(BspPlaneSet, JitteredPiecesOfOneWallShareItsPlaneButTiltedOrOffsetFacesDoNot) {
  // A 20 m box (plane offset tolerance 1e-5 x its diagonal, 3.5e-4) with a wall at x = 10 in
  // three 1 m pieces, the second and third tilted by moving their edges 2e-5 each way (as
  // rounding leaves them): their normals are 4e-5 rad off (beyond the 1e-5 of the angle
  // tolerance alone), yet every vertex is within the offset tolerance of the first piece's
  // plane: one plane. A piece tilted
  // by 2e-3 rad, and one 1e-3 off the wall, are other planes.
  SceneMaker m(boxOf({0, 0, 0}, {20, 10, 3}));
  const double j = 2e-5;
  m.builder.addQuad({10, 0, 0}, {10, 1, 0}, {10, 1, 1}, {10, 0, 1}, m.grey);
  m.builder.addQuad({10 + j, 1, 0}, {10 + j, 2, 0}, {10 - j, 2, 1}, {10 - j, 1, 1}, m.grey);
  m.builder.addQuad({10 - j, 2, 0}, {10 + j, 3, 0}, {10 + j, 3, 1}, {10 - j, 2, 1}, m.grey);
  m.builder.addQuad({10, 3, 0}, {10, 4, 0}, {10 + 2e-3, 4, 1}, {10 + 2e-3, 3, 1}, m.grey);
  m.builder.addQuad({10.001, 4, 0}, {10.001, 5, 0}, {10.001, 5, 1}, {10.001, 4, 1}, m.grey);
  ASSERT_EQ(m.scene.patches.size(), 5u);  // each quad one patch (none triangulated)
  const size_t first = 0;
  const PlaneSet planes = PlaneSet::fromScene(m.scene, m.scene.tolerance());
  const uint32_t wall = planes.of(static_cast<uint32_t>(first)).plane;
  EXPECT_EQ(planes.of(static_cast<uint32_t>(first + 1)).plane, wall);
  EXPECT_EQ(planes.of(static_cast<uint32_t>(first + 2)).plane, wall);
  EXPECT_NE(planes.of(static_cast<uint32_t>(first + 3)).plane, wall);
  EXPECT_NE(planes.of(static_cast<uint32_t>(first + 4)).plane, wall);
}

TEST(BspPlaneSet, BoxFacesMakeSixPlanesAndOpposedFacesOfTouchingBoxesShareOne) {
  SceneMaker m(boxOf({0, 0, 0}, {2, 1, 1}));
  m.builder.addBox({0, 0, 0}, {1, 1, 1}, m.grey);
  m.builder.addBox({1, 0, 0}, {2, 1, 1}, m.grey);  // its -x face is the first box's +x face
  const PlaneSet planes = PlaneSet::fromScene(m.scene, m.scene.tolerance());
  EXPECT_EQ(planes.planes().size(), 7u);  // x = 0, 1, 2; y = 0, 1; z = 0, 1
}

TEST(BspTree, OnePatchSplitsTheRootInTwo) {
  const Scene s = onePatch();
  const BspTree tree = buildBspTree(s);
  ASSERT_EQ(tree.nodes.size(), 1u);
  EXPECT_EQ(tree.leaves.size(), 2u);
  EXPECT_EQ(tree.nodes[0].coplanar.size(), 1u);
  // The root box is the scene's box enlarged on every side, so even a flat scene has volume.
  const Aabb root = tree.root.bounds();
  EXPECT_LT(root.lo.z, 0);
  EXPECT_GT(root.hi.z, 0);
  EXPECT_LT(root.lo.x, 0);
  EXPECT_GT(root.hi.x, 2);
}

TEST(BspTree, LeafVolumesSumToTheRootVolume) {
  for (const Scene& s : {closedRoom(), twoRoomsWithDoor(), messy(), randomClutter(7, 8, 6)}) {
    const BspTree tree = buildBspTree(s);
    double sum = 0;
    for (const BspLeaf& leaf : tree.leaves) sum += leaf.shape.volume();
    const double root = boxVolume(tree.root.bounds());
    EXPECT_NEAR(sum, root, 1e-9 * root);
    EXPECT_GT(tree.leaves.size(), 4u);
  }
}

TEST(BspTree, LeafAtAgreesWithBruteForceContainment) {
  const Scene s = randomClutter(3, 10, 8);
  const BspTree tree = buildBspTree(s);
  const Aabb root = tree.root.bounds();
  const double margin = 1e-7 * s.bounds().diagonal();
  std::mt19937 rng(11);
  int checked = 0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 p{uniform(rng, root.lo.x, root.hi.x), uniform(rng, root.lo.y, root.hi.y),
                 uniform(rng, root.lo.z, root.hi.z)};
    int strict = -1;
    for (size_t c = 0; c < tree.leaves.size(); ++c) {
      const auto& hs = tree.leaves[c].shape.halfspaces;
      if (std::all_of(hs.begin(), hs.end(),
                      [&](const Plane& h) { return h.distance(p) < -margin; }))
        strict = static_cast<int>(c);
    }
    if (strict < 0) continue;  // on a boundary
    EXPECT_EQ(static_cast<int>(tree.leafAt(p)), strict);
    ++checked;
  }
  EXPECT_GT(checked, 450);
}

TEST(BspTree, DefaultStopRuleLeavesEveryPatchOnCellBoundaries) {
  const Scene s = randomClutter(5, 12, 10);
  const BspTree tree = buildBspTree(s);
  size_t interior = 0;
  for (const BspLeaf& leaf : tree.leaves) interior += leaf.interior.size();
  EXPECT_EQ(interior, 0u);
  // No leaf is crossed by a patch: every patch point sampled is on a leaf's boundary, i.e. not
  // strictly inside any leaf.
  std::mt19937 rng(2);
  const double margin = 1e-7 * s.bounds().diagonal();
  for (const Patch& p : s.patches) {
    const Vec3 q = samplePolygon(p.polygon.vertices, rng);
    for (const BspLeaf& leaf : tree.leaves) {
      const auto& hs = leaf.shape.halfspaces;
      EXPECT_FALSE(std::all_of(hs.begin(), hs.end(),
                               [&](const Plane& h) { return h.distance(q) < -margin; }));
    }
  }
}

TEST(BspTree, CoarserStopRuleKeepsSmallPatchesInsideCells) {
  OfficeOptions o;
  const Scene s = generateOffice(o);
  const BspTree fine = buildBspTree(s);
  BspOptions coarse;
  coarse.minCoverage = 0.5;
  const BspTree big = buildBspTree(s, coarse);
  EXPECT_LT(big.leaves.size(), fine.leaves.size());
  size_t interior = 0;
  double sum = 0;
  for (const BspLeaf& leaf : big.leaves)
    interior += leaf.interior.size(), sum += leaf.shape.volume();
  EXPECT_GT(interior, 0u);
  EXPECT_NEAR(sum, boxVolume(big.root.bounds()), 1e-9 * boxVolume(big.root.bounds()));
}

TEST(BspTree, EmptySceneIsAnError) {
  EXPECT_THROW(buildBspTree(Scene{}), std::invalid_argument);
}

}  // namespace
}  // namespace gv
