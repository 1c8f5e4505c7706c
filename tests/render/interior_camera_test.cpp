// The pieces of the interior camera against hand-computed answers: saturated patch light, air
// points at eye height, the shell fraction of outside views.
#include "render/interior_camera.h"

#include <gtest/gtest.h>

#include "generators/cornell_box.h"
#include "generators/scene_builder.h"

namespace gv {
namespace {

/// A room [0, 4] x [0, 7] x [0, 4], y up, every face facing into it.
Scene inwardRoom() {
  Scene scene;
  const uint32_t wall = scene.addMaterial({"wall", {0.5, 0.5, 0.5}, {}});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{0, 0, 0}, {4, 7, 4}}));
  const Vec3 lo{0, 0, 0}, hi{4, 7, 4};
  for (int a = 0; a < 3; ++a) {
    Vec3 top = hi, bottom = lo;
    top[a] = lo[a];
    bottom[a] = hi[a];
    b.addAxisRect(a, true, lo, top, wall);
    b.addAxisRect(a, false, bottom, hi, wall);
  }
  return scene;
}

Scene solidCube() {
  Scene scene;
  const uint32_t wall = scene.addMaterial({"wall", {0.5, 0.5, 0.5}, {}});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{0, 0, 0}, {4, 4, 4}}));
  b.addBox({0, 0, 0}, {4, 4, 4}, wall);
  return scene;
}

Camera lookingAt(const Vec3& eye, const Vec3& target) {
  Camera c;
  c.eye = eye;
  c.target = target;
  c.width = 160;
  c.height = 120;
  return c;
}

TEST(InteriorCameraTest, SolutionLightIsReflectedRadiositySaturatedAtTheNinetiethPercentile) {
  Scene scene;
  const uint32_t grey = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  const uint32_t lamp = scene.addMaterial({"lamp", {0, 0, 0}, {100, 100, 100}});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{0, 0, 0}, {12, 1, 1}}));
  for (int k = 0; k <= 10; ++k) b.addAxisRect(1, true, {double(k), 0, 0}, {k + 1.0, 0, 1}, grey);
  b.addAxisRect(1, true, {11, 0, 0}, {12, 0, 1}, lamp);
  std::vector<Rgb> radiosity;
  for (int k = 0; k <= 10; ++k) radiosity.push_back({double(k), double(k), double(k)});
  radiosity.push_back({103, 103, 103});  // B - Ke = 3
  const EmbreeScene rays(scene);
  const std::vector<double> light = patchLight(scene, rays, radiosity);
  // Lit values 1..10 and 3: eleven, the 90th percentile is the 10th smallest (rank 9): 9.
  ASSERT_EQ(light.size(), 12u);
  for (int k = 0; k <= 10; ++k) EXPECT_NEAR(light[k], std::min(k / 9.0, 1.0), 1e-12) << k;
  EXPECT_NEAR(light[11], 3 / 9.0, 1e-12);
}

TEST(InteriorCameraTest, WithoutASolutionOnlyWhatTheLampShinesOnIsLit) {
  Scene scene;
  const uint32_t grey = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  const uint32_t lamp = scene.addMaterial({"lamp", {0, 0, 0}, {10, 10, 10}});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{0, 0, 0}, {10, 4, 2}}));
  b.addAxisRect(1, true, {0, 0, 0}, {2, 0, 2}, grey);   // under the lamp, facing it
  b.addAxisRect(1, false, {4, 0, 0}, {6, 0, 2}, grey);  // facing away from it
  b.addAxisRect(1, true, {8, 0, 0}, {10, 0, 2}, grey);  // facing up, behind the wall below
  b.addAxisRect(0, true, {7, 0, 0}, {7, 4, 2}, grey);   // the wall (its front away from 0..2)
  b.addAxisRect(1, false, {0.5, 3, 0.5}, {1.5, 3, 1.5}, lamp);
  const EmbreeScene rays(scene);
  const std::vector<double> light = patchLight(scene, rays, {});
  EXPECT_GT(light[0], 0);
  EXPECT_EQ(light[1], 0);
  EXPECT_EQ(light[2], 0);
  EXPECT_EQ(light[4], 0);  // the lamp reflects nothing (Kd = 0)
}

TEST(InteriorCameraTest, AirPointsOfARoomStandAtEyeHeightAndASolidHasNone) {
  const Scene room = inwardRoom();
  const EmbreeScene rays(room);
  const std::vector<double> light(room.patches.size(), 0.0);
  const std::vector<AirPoint> air = findAirPoints(room, rays, light, 1);
  ASSERT_FALSE(air.empty());
  for (const AirPoint& p : air) {
    EXPECT_NEAR(p.eye.y, kEyeHeightFraction * 7, 1e-6);
    EXPECT_TRUE(p.eye.x > 0 && p.eye.x < 4 && p.eye.z > 0 && p.eye.z < 4);
    EXPECT_TRUE(p.enclosed);
    EXPECT_GT(p.openness, 0);
  }
  const Scene cube = solidCube();
  const EmbreeScene cubeRays(cube);
  EXPECT_TRUE(findAirPoints(cube, cubeRays, std::vector<double>(6, 0.0), 1).empty());
}

TEST(InteriorCameraTest, ShellFractionOfOutsideViews) {
  // A solid seen from outside: its faces look into the void.
  const Scene cube = solidCube();
  EXPECT_EQ(shellFraction(cube, EmbreeScene(cube), lookingAt({2, 2, -10}, {2, 2, 2})), 1.0);
  // A closed room seen from outside: its far walls only through the culled near wall.
  const Scene room = inwardRoom();
  EXPECT_EQ(shellFraction(room, EmbreeScene(room), lookingAt({2, 3.5, -10}, {2, 3.5, 2})), 1.0);
  // Nothing in view.
  EXPECT_EQ(shellFraction(room, EmbreeScene(room), lookingAt({2, 3.5, -10}, {2, 3.5, -20})), 0);
  // The Cornell box through its open front: inside walls, not shell.
  const Scene cornell = generateCornellBox({});
  EXPECT_LT(
      shellFraction(cornell, EmbreeScene(cornell), lookingAt({278, 273, -800}, {278, 273, 0})),
      0.2);
}

}  // namespace
}  // namespace gv
