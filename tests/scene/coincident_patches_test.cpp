// coincidentPatchGroups: same vertices facing the same way make a group, whatever the vertex
// order or a difference far below the tolerance; back-to-back faces, overlapping but different
// faces and faces sharing all but one vertex do not.
#include "scene/coincident_patches.h"

#include <gtest/gtest.h>

#include <vector>

namespace gv {
namespace {

void add(Scene& scene, std::vector<Vec3> v) {
  scene.patches.push_back({*ConvexPolygon::fromVertices(std::move(v), Tolerance{10}), 0});
}

TEST(CoincidentPatchesTest, GroupsSameVerticesSameFacing) {
  Scene scene;
  scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  const Vec3 a{0, 0, 0}, b{2, 0, 0}, c{2, 1, 0}, d{0, 1, 0};
  add(scene, {a, b, c, d});                          // 0
  add(scene, {c, d, a, b});                          // 1: the same, started elsewhere
  add(scene, {d, c, b, a});                          // 2: back to back with 0
  add(scene, {a, b, c, {0, 1.5, 0}});                // 3: all but one vertex shared
  add(scene, {a, {1, 0, 0}, {1, 1, 0}, d});          // 4: inside 0, not the same
  add(scene, {{1e-12, 0, 0}, b, c, {0, 1, 1e-12}});  // 5: 0 again, within the tolerance
  add(scene, {b, a, d, c});                          // 6: 2 again
  add(scene, {a, b, c, d});                          // 7: 0 again
  // Scene diagonal ~2.4: the plane-offset tolerance is ~2.4e-5.
  const std::vector<uint32_t> g = coincidentPatchGroups(scene);
  EXPECT_EQ(g, (std::vector<uint32_t>{0, 0, 2, 3, 4, 0, 2, 0}));
}

}  // namespace
}  // namespace gv
