// Small hand-made scenes for the subdivision tests (paper §3): rooms of solid walls, a door,
// degenerate inputs, and a seeded random clutter. Coordinates in metres, z up.
#pragma once

#include <random>

#include "bsp/bsp_oracle.h"
#include "generators/scene_builder.h"
#include "scene/scene.h"

namespace gv::bsptest {

/// A scene with one grey material and a builder whose tolerance fits `box`.
struct SceneMaker {
  Scene scene;
  SceneBuilder builder;
  uint32_t grey;
  explicit SceneMaker(const Aabb& box)
      : builder(scene, Tolerance::forBounds(box)),
        grey(scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}})) {}
};

inline Aabb boxOf(Vec3 lo, Vec3 hi) {
  Aabb b;
  b.add(lo);
  b.add(hi);
  return b;
}

/// One quad 2 x 1 in z = 0, facing up.
inline Scene onePatch() {
  SceneMaker m(boxOf({0, 0, 0}, {2, 1, 0}));
  m.builder.addQuad({0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}, m.grey);
  return std::move(m.scene);
}

/// A closed room: the air [0,4] x [0,4] x [0,3] inside six solid slabs 0.2 thick (each a box with
/// all faces outward, overlapping at the edges as modellers do).
inline constexpr double kWall = 0.2;
inline Scene closedRoom() {
  const double t = kWall;
  SceneMaker m(boxOf({-t, -t, -t}, {4 + t, 4 + t, 3 + t}));
  auto& b = m.builder;
  b.addBox({-t, -t, -t}, {4 + t, 4 + t, 0}, m.grey);     // floor
  b.addBox({-t, -t, 3}, {4 + t, 4 + t, 3 + t}, m.grey);  // roof
  b.addBox({-t, -t, 0}, {0, 4 + t, 3}, m.grey);          // -x wall
  b.addBox({4, -t, 0}, {4 + t, 4 + t, 3}, m.grey);       // +x wall
  b.addBox({0, -t, 0}, {4, 0, 3}, m.grey);               // -y wall
  b.addBox({0, 4, 0}, {4, 4 + t, 3}, m.grey);            // +y wall
  return std::move(m.scene);
}

/// Two rooms side by side along x: A = [0,4] x [0,4] x [0,3], B = [4.2,8.2] x [0,4] x [0,3],
/// solid walls 0.2 thick, joined by one door through the shared wall (x in [4, 4.2]) at
/// y in [1.5, 2.5], z in [0, 2]. A desk-like box stands in room A.
inline constexpr double kDoorY0 = 1.5, kDoorY1 = 2.5, kDoorTop = 2.0;
inline Scene twoRoomsWithDoor() {
  const double t = kWall;
  SceneMaker m(boxOf({-t, -t, -t}, {8.2 + t, 4 + t, 3 + t}));
  auto& b = m.builder;
  b.addBox({-t, -t, -t}, {8.2 + t, 4 + t, 0}, m.grey);
  b.addBox({-t, -t, 3}, {8.2 + t, 4 + t, 3 + t}, m.grey);
  b.addBox({-t, -t, 0}, {0, 4 + t, 3}, m.grey);
  b.addBox({8.2, -t, 0}, {8.2 + t, 4 + t, 3}, m.grey);
  b.addBox({0, -t, 0}, {8.2, 0, 3}, m.grey);
  b.addBox({0, 4, 0}, {8.2, 4 + t, 3}, m.grey);
  // The shared wall, split around the door: left, right and lintel.
  b.addBox({4, 0, 0}, {4.2, kDoorY0, 3}, m.grey);
  b.addBox({4, kDoorY1, 0}, {4.2, 4, 3}, m.grey);
  b.addBox({4, kDoorY0, kDoorTop}, {4.2, kDoorY1, 3}, m.grey);
  b.addBox({1, 2.5, 0}, {2.5, 3.3, 0.8}, m.grey);  // a desk
  return std::move(m.scene);
}

/// Messy input in one scene: coplanar overlapping patches facing both ways, a T-junction (one big
/// quad beside two that split its edge), near-coplanar patches within the merge tolerance, a
/// sliver triangle, and a patch crossing others.
inline Scene messy() {
  SceneMaker m(boxOf({-1, -1, -1}, {5, 5, 3}));
  auto& b = m.builder;
  const uint32_t g = m.grey;
  // Overlapping coplanar quads in z = 0, two facing up, one down.
  b.addQuad({0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}, g);
  b.addQuad({1, 1, 0}, {3, 1, 0}, {3, 3, 0}, {1, 3, 0}, g);
  b.addQuad({0.5, 0.5, 0}, {0.5, 2.5, 0}, {2.5, 2.5, 0}, {2.5, 0.5, 0}, g);  // facing down
  b.addQuad({1.2, 1.2, 0}, {1.8, 1.2, 0}, {1.8, 1.8, 0}, {1.2, 1.8, 0}, g);  // inside the others
  // A T-junction in the plane x = 4: a tall quad beside two stacked ones whose shared edge ends
  // on the tall one's edge.
  b.addQuad({4, 0, 0}, {4, 1, 0}, {4, 1, 2}, {4, 0, 2}, g);
  b.addQuad({4, 1, 0}, {4, 2, 0}, {4, 2, 1}, {4, 1, 1}, g);
  b.addQuad({4, 1, 1}, {4, 2, 1}, {4, 2, 2}, {4, 1, 2}, g);
  // Near-coplanar: 1e-7 above z = 1 and a hair tilted, beside an exact one; merged as one plane.
  b.addQuad({0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, g);
  b.addQuad({1, 0, 1 + 1e-7}, {2, 0, 1 + 1e-7}, {2, 1, 1 + 2e-7}, {1, 1, 1 + 2e-7}, g);
  // A sliver triangle (1e-6 wide, 2 long) standing in y = 3.
  b.addPolygon({{0, 3, 1.5}, {2, 3, 1.5}, {1, 3, 1.5 + 1e-6}}, g);
  // A tilted quad crossing the stack.
  b.addQuad({-0.5, -0.5, -0.5}, {3, -0.5, 2}, {3, 3.5, 2}, {-0.5, 3.5, -0.5}, g);
  return std::move(m.scene);
}

/// Seeded clutter: `boxes` axis-aligned boxes and `quads` randomly tilted quads in a 10 m cube.
inline Scene randomClutter(uint32_t seed, int boxes, int quads) {
  std::mt19937 rng(seed);
  SceneMaker m(boxOf({0, 0, 0}, {10, 10, 10}));
  auto& b = m.builder;
  for (int i = 0; i < boxes; ++i) {
    const Vec3 lo{uniform(rng, 0, 8), uniform(rng, 0, 8), uniform(rng, 0, 8)};
    const Vec3 size{uniform(rng, 0.2, 2), uniform(rng, 0.2, 2), uniform(rng, 0.2, 2)};
    b.addBox(lo, lo + size, m.grey);
  }
  for (int i = 0; i < quads; ++i) {
    const Vec3 c{uniform(rng, 2, 8), uniform(rng, 2, 8), uniform(rng, 2, 8)};
    Vec3 n{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    if (length(n) < 0.1) n = {0, 0, 1};
    n = normalize(n);
    const Vec3 u = normalize(cross(n, std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    const Vec3 v = cross(n, u);
    const double su = uniform(rng, 0.3, 2), sv = uniform(rng, 0.3, 2);
    b.addQuad(c - u * su - v * sv, c + u * su - v * sv, c + u * su + v * sv, c - u * su + v * sv,
              m.grey);
  }
  return std::move(m.scene);
}

/// A closed room of solid walls 0.5 thick around the air [0,20] x [0,20] x [0,6], holding a
/// grid of n x n crates (closed boxes 0.4-1 m wide, `step` apart, a third of them raised off
/// the floor): a level of closed solids whose small detail no coarse stop rule splits on.
inline Scene cratesInAClosedRoom(int n, double step) {
  const double w = 20, h = 6, t = 0.5;
  SceneMaker m(boxOf({-t, -t, -t}, {w + t, w + t, h + t}));
  auto& b = m.builder;
  b.addBox({-t, -t, -t}, {w + t, w + t, 0}, m.grey);
  b.addBox({-t, -t, h}, {w + t, w + t, h + t}, m.grey);
  b.addBox({-t, -t, 0}, {0, w + t, h}, m.grey);
  b.addBox({w, -t, 0}, {w + t, w + t, h}, m.grey);
  b.addBox({0, -t, 0}, {w, 0, h}, m.grey);
  b.addBox({0, w, 0}, {w, w + t, h}, m.grey);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int k = (i * 7 + j * 3) % 5;
      const double size = 0.4 + 0.15 * k, height = 0.3 + 0.25 * ((i * 3 + j * 5) % 4);
      const double x = 1 + step * i + 0.3 * ((i + 2 * j) % 3);
      const double y = 1 + step * j + 0.3 * ((2 * i + j) % 3);
      const double z = (i + j) % 3 ? 0 : 1.5 + 0.5 * k;
      b.addBox({x, y, z}, {x + size, y + size, z + height}, m.grey);
    }
  return std::move(m.scene);
}

/// The scene with every vertex mapped to origin + scale * p (to test huge and tiny coordinates).
inline Scene transformed(const Scene& in, double scale, const Vec3& origin) {
  Aabb box;
  for (const Patch& p : in.patches)
    for (const Vec3& v : p.polygon.vertices) box.add(origin + v * scale);
  SceneMaker m(box);
  for (const Patch& p : in.patches) {
    std::vector<Vec3> v;
    for (const Vec3& q : p.polygon.vertices) v.push_back(origin + q * scale);
    m.builder.addPolygon(std::move(v), m.grey);
  }
  return std::move(m.scene);
}

}  // namespace gv::bsptest
