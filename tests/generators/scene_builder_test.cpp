// Tests for SceneBuilder: outward box faces, face masks, degenerate and non-planar quads.
#include "generators/scene_builder.h"

#include <gtest/gtest.h>

#include "generators/scene_oracle.h"

namespace gv {
namespace {

Tolerance unitTolerance() { return Tolerance{10.0}; }

TEST(SceneBuilderTest, BoxIsClosedAndFacesOutward) {
  Scene scene;
  const uint32_t m = scene.addMaterial({"m", {0.5, 0.5, 0.5}, {}});
  SceneBuilder builder(scene, unitTolerance());
  const Vec3 lo{1, 2, 3}, hi{2, 4, 7};
  EXPECT_EQ(builder.addBox(lo, hi, m), 6);
  ASSERT_EQ(scene.patches.size(), 6u);
  const Vec3 center = (lo + hi) * 0.5;
  for (const Patch& p : scene.patches) {
    EXPECT_TRUE(testing::isValidPatch(p, 10.0));
    const Vec3 n = p.polygon.plane.normal;
    // Axis-aligned and pointing away from the centre (towards the air side).
    EXPECT_NEAR(std::abs(n.x) + std::abs(n.y) + std::abs(n.z), 1.0, 1e-12);
    EXPECT_GT(dot(n, p.polygon.vertices[0] - center), 0);
  }
  EXPECT_NEAR(testing::divergenceVolume(scene), 1.0 * 2.0 * 4.0, 1e-12);
}

TEST(SceneBuilderTest, FaceMaskAndPerFaceMaterials) {
  Scene scene;
  SceneBuilder builder(scene, unitTolerance());
  BoxMaterials materials;
  materials.face = {0, 1, 2, 3, 4, 5};
  EXPECT_EQ(builder.addBox({0, 0, 0}, {1, 1, 1}, materials, kBoxMinZ | kBoxMaxX), 2);
  ASSERT_EQ(scene.patches.size(), 2u);
  for (const Patch& p : scene.patches) {
    const Vec3 n = p.polygon.plane.normal;
    if (p.material == 1) EXPECT_NEAR(n.x, 1.0, 1e-12);
    else {
      EXPECT_EQ(p.material, 4u);
      EXPECT_NEAR(n.z, -1.0, 1e-12);
    }
  }
}

TEST(SceneBuilderTest, TwoBoxesSharingAFaceMaskedStayClosed) {
  // Two unit cubes side by side; the exactly coincident faces x = 1 are dropped from both, so the
  // remaining surface bounds their union: volume 2.
  Scene scene;
  SceneBuilder builder(scene, unitTolerance());
  builder.addBox({0, 0, 0}, {1, 1, 1}, 0u, kBoxAllFaces & ~kBoxMaxX);
  builder.addBox({1, 0, 0}, {2, 1, 1}, 0u, kBoxAllFaces & ~kBoxMinX);
  scene.addMaterial({});
  EXPECT_EQ(scene.patches.size(), 10u);
  EXPECT_NEAR(testing::divergenceVolume(scene), 2.0, 1e-12);
}

TEST(SceneBuilderTest, AxisRectFacesTheRequestedWay) {
  Scene scene;
  SceneBuilder builder(scene, unitTolerance());
  ASSERT_TRUE(builder.addAxisRect(1, true, {0, 5, 0}, {2, 5, 3}, 0));
  ASSERT_TRUE(builder.addAxisRect(1, false, {0, 5, 0}, {2, 5, 3}, 0));
  EXPECT_NEAR(scene.patches[0].polygon.plane.normal.y, 1.0, 1e-12);
  EXPECT_NEAR(scene.patches[1].polygon.plane.normal.y, -1.0, 1e-12);
  EXPECT_NEAR(testing::vectorArea2(scene.patches[0].polygon.vertices).y, 12.0, 1e-12);
}

TEST(SceneBuilderTest, DegenerateQuadIsRejected) {
  Scene scene;
  SceneBuilder builder(scene, unitTolerance());
  EXPECT_EQ(builder.addQuad({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}, 0), 0);
  EXPECT_FALSE(builder.addPolygon({{0, 0, 0}, {1, 1, 1}, {0, 0, 0}}, 0));
  EXPECT_TRUE(scene.patches.empty());
}

TEST(SceneBuilderTest, NonPlanarQuadBecomesTwoPlanarTriangles) {
  Scene scene;
  SceneBuilder builder(scene, unitTolerance());
  // The fourth corner is lifted by 1% of the quad's size: far beyond the model tolerance.
  EXPECT_EQ(builder.addQuad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0.01}, 0), 2);
  ASSERT_EQ(scene.patches.size(), 2u);
  for (const Patch& p : scene.patches) {
    EXPECT_TRUE(testing::isValidPatch(p, 10.0));
    EXPECT_GT(p.polygon.plane.normal.z, 0.99);
  }
  // A planar quad stays one patch.
  EXPECT_EQ(builder.addQuad({0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, 0), 1);
}

}  // namespace
}  // namespace gv
