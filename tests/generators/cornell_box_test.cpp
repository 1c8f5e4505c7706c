// Tests for the Cornell box: face count, the emitter, orientation, block volumes, closedness.
#include "generators/cornell_box.h"

#include <gtest/gtest.h>

#include <random>

#include "generators/scene_oracle.h"

namespace gv {
namespace {

// Area of a polygon in the xz plane (shoelace), for the block footprints of the published data.
double footprintArea(const std::vector<std::pair<double, double>>& xz) {
  double twice = 0;
  for (size_t i = 0; i < xz.size(); ++i) {
    const auto& [x0, z0] = xz[i];
    const auto& [x1, z1] = xz[(i + 1) % xz.size()];
    twice += x0 * z1 - x1 * z0;
  }
  return 0.5 * std::abs(twice);
}

TEST(CornellBoxTest, FaceCountMaterialsAndLight) {
  const Scene open = generateCornellBox();
  // Floor, ceiling, back, green, red (2 triangles: the published quad is not planar), light,
  // 2 blocks x 6 faces.
  EXPECT_EQ(open.patches.size(), 19u);
  EXPECT_EQ(generateCornellBox({.closedFront = true}).patches.size(), 20u);
  ASSERT_EQ(open.emitterCount(), 1u);
  for (const Patch& p : open.patches) {
    EXPECT_TRUE(testing::isValidPatch(p, 1000.0));
    const Material& m = open.materials[p.material];
    if (!m.isEmitter()) continue;
    // The published light: 130 x 105 mm, just below the ceiling at 548.8, facing down.
    EXPECT_NEAR(p.polygon.plane.normal.y, -1.0, 1e-12);
    EXPECT_NEAR(0.5 * length(testing::vectorArea2(p.polygon.vertices)), 130.0 * 105.0, 1e-6);
    for (const Vec3& v : p.polygon.vertices) {
      EXPECT_LT(v.y, 548.8);
      EXPECT_GT(v.y, 547.8);
    }
  }
  const Material& red = open.materials[testing::materialNamed(open, "red")];
  EXPECT_NEAR(red.reflectance.r, 0.63, 1e-12);
}

TEST(CornellBoxTest, WallsFaceInwardBlocksAreClosedOutwardSolids) {
  const Scene scene = generateCornellBox();
  // Blocks: every patch with all vertices at y <= 330 except the floor. Their divergence volume
  // is footprint area x height, from the published top faces.
  const double shortVolume =
      footprintArea({{130, 65}, {82, 225}, {240, 272}, {290, 114}}) * 165.0;
  const double tallVolume =
      footprintArea({{423, 247}, {265, 296}, {314, 456}, {472, 406}}) * 330.0;
  Scene blocks;
  blocks.materials = scene.materials;
  const Vec3 center{278, 274.4, 279.6};
  for (const Patch& p : scene.patches) {
    double maxY = 0;
    for (const Vec3& v : p.polygon.vertices) maxY = std::max(maxY, v.y);
    const bool isFloor = maxY == 0 && p.polygon.plane.normal.y > 0.5;
    if (maxY <= 330.0 && !isFloor) {
      blocks.patches.push_back(p);
    } else if (!scene.materials[p.material].isEmitter()) {
      // Box walls face the inside.
      EXPECT_GT(dot(p.polygon.plane.normal, center - p.polygon.vertices[0]), 0);
    }
  }
  EXPECT_EQ(blocks.patches.size(), 12u);
  EXPECT_NEAR(testing::divergenceVolume(blocks), shortVolume + tallVolume, 1e-6 * tallVolume);
}

TEST(CornellBoxTest, ClosedBoxTrapsEveryRayOpenBoxLeaksOnlyThroughTheFront) {
  const Scene closed = generateCornellBox({.closedFront = true});
  const Scene open = generateCornellBox();
  std::mt19937 rng(7);
  int escapedOpen = 0;
  for (int k = 0; k < 2000; ++k) {
    // Start above both blocks (y > 330) and below the light, or beside them (x < 80).
    const Vec3 p = k % 2 == 0 ? Vec3{testing::uniform(rng, 10, 545), testing::uniform(rng, 335, 540),
                                     testing::uniform(rng, 10, 550)}
                              : Vec3{testing::uniform(rng, 10, 75), testing::uniform(rng, 5, 540),
                                     testing::uniform(rng, 10, 550)};
    Vec3 d{testing::uniform(rng, -1, 1), testing::uniform(rng, -1, 1), testing::uniform(rng, -1, 1)};
    if (lengthSquared(d) < 1e-6) continue;
    const Vec3 q = p + normalize(d) * 3000.0;
    EXPECT_TRUE(testing::segmentBlocked(closed, p, q)) << p << " -> " << q;
    if (!testing::segmentBlocked(open, p, q)) {
      ++escapedOpen;
      // It left through the open front: crossing z = 0 inside the front opening.
      ASSERT_LT(q.z, 0);
      const Vec3 x = p + (q - p) * (p.z / (p.z - q.z));
      EXPECT_GE(x.x, 0);
      EXPECT_LE(x.x, 556.0);
      EXPECT_GE(x.y, 0);
      EXPECT_LE(x.y, 548.8);
    }
  }
  EXPECT_GT(escapedOpen, 0);  // the check above is not vacuous
}

}  // namespace
}  // namespace gv
