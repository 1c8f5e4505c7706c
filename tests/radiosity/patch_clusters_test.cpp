// The cluster tree over patches (patch_clusters.h): its invariants on a real scene, the box
// distance by hand, and the area-proportional pick of a cluster's patches.
#include "radiosity/patch_clusters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "generators/furnished_room.h"
#include "generators/scene_builder.h"

namespace gv {
namespace {

TEST(ClusterTreeTest, NodesPartitionThePatchesAndBoundThem) {
  const Scene scene = generateFurnishedRoom();
  const ClusterTree tree(scene);
  const size_t n = scene.patches.size();
  ASSERT_EQ(tree.size(), 2 * n - 1);
  // Every patch once in the order; every leaf one patch, found by leafOf.
  std::vector<uint32_t> sorted(tree.order().begin(), tree.order().end());
  std::sort(sorted.begin(), sorted.end());
  for (uint32_t p = 0; p < n; ++p) ASSERT_EQ(sorted[p], p);
  size_t leaves = 0;
  for (uint32_t id = 0; id < tree.size(); ++id) {
    const Cluster& c = tree[id];
    double area = 0;
    for (const uint32_t p : tree.patchesOf(id)) {
      const Aabb b = scene.patches[p].polygon.bounds();
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(c.box.lo[k], b.lo[k]);
        EXPECT_GE(c.box.hi[k], b.hi[k]);
      }
      area += scene.patches[p].polygon.area();
    }
    EXPECT_NEAR(c.area, area, 1e-9 * area);
    if (c.isLeaf()) {
      ++leaves;
      ASSERT_EQ(c.size(), 1u);
      EXPECT_EQ(tree.leafOf(tree.patchesOf(id)[0]), id);
      continue;
    }
    // Children split the range in two halves (median split: depth ⌈log2 n⌉), ids after the parent.
    const Cluster& l = tree[c.left];
    const Cluster& r = tree[c.right];
    EXPECT_GT(c.left, id);
    EXPECT_GT(c.right, id);
    EXPECT_EQ(l.begin, c.begin);
    EXPECT_EQ(l.end, r.begin);
    EXPECT_EQ(r.end, c.end);
    EXPECT_LE(l.size() > r.size() ? l.size() - r.size() : r.size() - l.size(), 1u);
    EXPECT_EQ(c.reflectance, std::max(l.reflectance, r.reflectance));
  }
  EXPECT_EQ(leaves, n);
}

TEST(ClusterTreeTest, PicksPatchesInProportionToTheirArea) {
  // Three squares of areas 1, 4 and 9: u splits [0, 1) at 1/14 and 5/14.
  Scene scene;
  const uint32_t m = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  SceneBuilder b(scene, Tolerance{20.0});
  ASSERT_TRUE(b.addAxisRect(2, true, {0, 0, 0}, {1, 1, 0}, m));
  ASSERT_TRUE(b.addAxisRect(2, true, {5, 0, 0}, {7, 2, 0}, m));
  ASSERT_TRUE(b.addAxisRect(2, true, {10, 0, 0}, {13, 3, 0}, m));
  const ClusterTree tree(scene);
  auto pick = [&](double u) { return tree.patchByArea(0, u); };
  EXPECT_EQ(pick(0.0), 0u);
  EXPECT_EQ(pick(1.0 / 14 - 1e-9), 0u);
  EXPECT_EQ(pick(1.0 / 14 + 1e-9), 1u);
  EXPECT_EQ(pick(5.0 / 14 - 1e-9), 1u);
  EXPECT_EQ(pick(5.0 / 14 + 1e-9), 2u);
  EXPECT_EQ(pick(1.0 - 1e-12), 2u);
  // Within a sub-cluster, only its own patches.
  for (uint32_t id = 1; id < tree.size(); ++id)
    for (const double u : {0.0, 0.3, 0.7, 0.999}) {
      const auto own = tree.patchesOf(id);
      EXPECT_NE(std::find(own.begin(), own.end(), tree.patchByArea(id, u)), own.end());
    }
}

TEST(ClusterTreeTest, BoxDistanceByHand) {
  Aabb a, b;
  a.add(Vec3{0, 0, 0});
  a.add(Vec3{1, 1, 1});
  b.add(Vec3{4, 5, 0.5});
  b.add(Vec3{6, 7, 2});
  EXPECT_DOUBLE_EQ(boxDistance(a, b), 5.0);  // gaps 3 and 4 along x and y, overlap along z
  EXPECT_DOUBLE_EQ(boxDistance(b, a), 5.0);
  Aabb c;
  c.add(Vec3{1, 0.5, 0.5});
  c.add(Vec3{2, 2, 2});
  EXPECT_EQ(boxDistance(a, c), 0.0);  // touching
}

}  // namespace
}  // namespace gv
