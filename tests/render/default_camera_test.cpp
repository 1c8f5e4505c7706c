// The default camera: closed levels are looked at from inside their lit air (issue #18 item 4),
// while the Cornell box and the office keep the views they had before (values recorded from the
// code before the interior camera existed).
#include "render/default_camera.h"

#include <gtest/gtest.h>

#include <vector>

#include "generators/cornell_box.h"
#include "generators/office.h"
#include "generators/scene_builder.h"
#include "raycast/embree_scene.h"

namespace gv {
namespace {

/// The fraction of a coarse grid of the camera's pixel rays whose first hit (two-sided rays, so
/// a back counts) is the front of a patch; misses count against it.
double frontFraction(const Scene& scene, const Camera& c) {
  const EmbreeScene rays(scene);
  int fronts = 0, total = 0;
  for (int row = 0; row < 12; ++row)
    for (int col = 0; col < 16; ++col) {
      const CameraRay r = c.ray((col + 0.5) * c.width / 16, (row + 0.5) * c.height / 12);
      ++total;
      const auto hit = rays.firstHit(r.origin, r.direction);
      fronts += hit && dot(scene.patches[hit->patch].polygon.normal(), r.direction) < 0;
    }
  return static_cast<double>(fronts) / total;
}

bool inside(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  return p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y && p.z > lo.z && p.z < hi.z;
}

/// Two rooms, y up (the OBJ convention), walls facing into the air: room A is x in [0, 4], room
/// B x in [4, 8] (a partition of no thickness, both sides facing their room, with a doorway),
/// z in [0, 8], floor y = 0, ceiling y = 7. A light panel under B's ceiling. Not flat (7 > 0.75
/// x 8), so the box camera stands outside, where the near wall's back is culled.
Scene twoRooms() {
  Scene scene;
  const uint32_t wall = scene.addMaterial({"wall", {0.6, 0.6, 0.6}, {}});
  const uint32_t lamp = scene.addMaterial({"lamp", {0, 0, 0}, {5, 5, 5}});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{0, 0, 0}, {8, 7, 8}}));
  b.addAxisRect(0, true, {0, 0, 0}, {0, 7, 8}, wall);   // x = 0 facing +x
  b.addAxisRect(0, false, {8, 0, 0}, {8, 7, 8}, wall);  // x = 8 facing -x
  for (const double x0 : {0.0, 4.0}) {  // floor, ceiling, end walls: one patch per room
    b.addAxisRect(1, true, {x0, 0, 0}, {x0 + 4, 0, 8}, wall);
    b.addAxisRect(1, false, {x0, 7, 0}, {x0 + 4, 7, 8}, wall);
    b.addAxisRect(2, true, {x0, 0, 0}, {x0 + 4, 7, 0}, wall);
    b.addAxisRect(2, false, {x0, 0, 8}, {x0 + 4, 7, 8}, wall);
  }
  // The partition x = 4 with a doorway z in [3, 5], y in [0, 5].
  for (const bool positive : {true, false}) {
    b.addAxisRect(0, positive, {4, 0, 0}, {4, 7, 3}, wall);
    b.addAxisRect(0, positive, {4, 0, 5}, {4, 7, 8}, wall);
    b.addAxisRect(0, positive, {4, 5, 3}, {4, 7, 5}, wall);
  }
  b.addAxisRect(1, false, {5.5, 6.9, 3}, {6.5, 6.9, 5}, lamp);
  return scene;
}

TEST(DefaultCameraTest, ClosedRoomsAreSeenFromInsideTheirAir) {
  const Scene scene = twoRooms();
  const Camera c = defaultCamera(scene, 400, 300);
  EXPECT_TRUE(inside(c.eye, {0, 0, 0}, {8, 7, 8})) << c.eye.x << " " << c.eye.y << " " << c.eye.z;
  EXPECT_NE(c.eye.x, 4);
  EXPECT_FALSE(c.cutaway);
  EXPECT_NEAR(c.up.y, 1, 1e-12);
  EXPECT_GT(c.fovYDegrees, 60);
  EXPECT_GE(frontFraction(scene, c), 0.95);
  // Without a solution, light is estimated from the lamp: the camera stands in the lamp's room.
  EXPECT_GT(c.eye.x, 4);
}

TEST(DefaultCameraTest, TheBestLitRoomOfTheSolutionWins) {
  const Scene scene = twoRooms();
  for (const bool leftLit : {true, false}) {
    SCOPED_TRACE(leftLit);
    std::vector<Rgb> b(scene.patches.size());
    for (size_t k = 0; k < b.size(); ++k) {
      const bool left =
          scene.patches[k].polygon.centroid().x < 4 ||
          (scene.patches[k].polygon.centroid().x == 4 && scene.patches[k].polygon.normal().x < 0);
      const double v = left == leftLit ? 1.0 : 0.05;
      b[k] = {v, v, v};
    }
    const Camera c = defaultCamera(scene, b, 400, 300);
    EXPECT_TRUE(inside(c.eye, {0, 0, 0}, {8, 7, 8}));
    EXPECT_GE(frontFraction(scene, c), 0.95);
    // The picture is mostly the lit room.
    const EmbreeScene rays(scene);
    int lit = 0, total = 0;
    for (int row = 0; row < 12; ++row)
      for (int col = 0; col < 16; ++col) {
        const CameraRay r = c.ray((col + 0.5) * c.width / 16, (row + 0.5) * c.height / 12);
        const auto hit = rays.firstHit(r.origin, r.direction);
        ++total;
        lit += hit && b[hit->patch].r == 1.0;
      }
    EXPECT_GE(lit, 0.75 * total) << c.eye.x << " " << c.eye.y << " " << c.eye.z;
  }
}

/// A flat level of outward-facing solids (as Quake brushes are), z up: a hall 10 x 10 with its
/// roof at z = 8 in one corner of a 30 x 30 floor whose other rooms are 3 high under a roof
/// slab. From above with the roof sawn off at the hall's ceiling, the picture is mostly the low
/// roof's top and the outer walls' outsides: the shell.
struct Level {
  Scene scene;
  std::vector<Aabb> solids;
};

Level flatLevel() {
  Level level;
  Scene& scene = level.scene;
  const uint32_t wall = scene.addMaterial({"wall", {0.6, 0.6, 0.6}, {}});
  const uint32_t lamp = scene.addMaterial({"lamp", {0, 0, 0}, {5, 5, 5}});
  SceneBuilder b(scene, Tolerance::forBounds(Aabb{{-0.5, -0.5, -1}, {30.5, 30.5, 9}}));
  level.solids = {
      {{-0.5, -0.5, -1}, {30.5, 30.5, 0}},  // floor slab
      {{-0.5, 0, 0}, {0, 10, 9}},           // outer walls by the hall, full height
      {{0, -0.5, 0}, {10, 0, 9}},
      {{-0.5, 10, 0}, {0, 30.5, 4}},  // outer walls of the low rooms
      {{10, -0.5, 0}, {30.5, 0, 4}},
      {{30, 0, 0}, {30.5, 30.5, 4}},
      {{0, 30, 0}, {30, 30.5, 4}},
      {{0, 10, 3}, {30, 30, 4}},  // the low roof
      {{10, 0, 3}, {30, 10, 4}},
      {{10, 0, 4}, {10.5, 10.5, 9}},  // the hall's walls above the low roof
      {{0, 10, 4}, {10, 10.5, 9}},
      {{-0.5, -0.5, 8}, {10.5, 10.5, 9}},  // the hall's roof
  };
  for (const Aabb& s : level.solids) b.addBox(s.lo, s.hi, wall);
  b.addAxisRect(2, false, {4, 4, 7.9}, {6, 6, 7.9}, lamp);
  b.addAxisRect(2, false, {19, 19, 2.9}, {21, 21, 2.9}, lamp);
  return level;
}

TEST(DefaultCameraTest, AFlatLevelShowingItsShellIsSeenFromInside) {
  const Level level = flatLevel();
  const Camera c = defaultCamera(level.scene, 400, 300);
  EXPECT_TRUE(inside(c.eye, {0, 0, 0}, {30, 30, 8})) << c.eye.x << " " << c.eye.y << " " << c.eye.z;
  for (const Aabb& s : level.solids) EXPECT_FALSE(inside(c.eye, s.lo, s.hi));
  EXPECT_NEAR(c.up.z, 1, 1e-12);
  EXPECT_FALSE(c.cutaway);
  EXPECT_GE(frontFraction(level.scene, c), 0.95);
}

void expectCamera(const Camera& c, const Vec3& eye, const Vec3& target, const Vec3& up) {
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(c.eye[a], eye[a], 1e-9);
    EXPECT_NEAR(c.target[a], target[a], 1e-9);
    EXPECT_NEAR(c.up[a], up[a], 1e-9);
  }
  EXPECT_EQ(c.fovYDegrees, kDefaultFovDegrees);
}

TEST(DefaultCameraTest, CornellBoxAndOfficeKeepTheirViews) {
  const Camera cornell = defaultCamera(generateCornellBox({}), 800, 600);
  expectCamera(cornell, {278, 274.4, -791.60319409326564}, {278, 274.4, 279.6}, {0, 1, 0});
  EXPECT_FALSE(cornell.cutaway);
  for (const int width : {800, 200}) {
    const Camera office = defaultCamera(generateOffice({}), width, width * 3 / 4);
    expectCamera(office, {-0.89012302399404497, -8.6726638159338876, 27.962933957875137},
                 {8.375, 7.375, 1.499}, {0, 0, 1});
    ASSERT_TRUE(office.cutaway);
    EXPECT_NEAR(office.cutaway->normal.z, 1, 1e-12);
    EXPECT_NEAR(office.cutaway->offset, 2.998, 1e-9);
  }
}

}  // namespace
}  // namespace gv
