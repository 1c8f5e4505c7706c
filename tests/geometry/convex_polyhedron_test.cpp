// Tests of ConvexPolyhedron: boxes, halfspace intersections, and seeded random splits. Paper §3.
#include "geometry/convex_polyhedron.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace gv {
namespace {

const Tolerance kUnitTol{1.0};

Aabb box(const Vec3& lo, const Vec3& hi) {
  Aabb b;
  b.add(lo);
  b.add(hi);
  return b;
}

/// Every face's polygon faces outward: its plane equals its halfspace and the centroid of the
/// solid is behind it.
void expectWellFormed(const ConvexPolyhedron& p) {
  ASSERT_GE(p.faces.size(), 4u);
  EXPECT_EQ(p.faces.size(), p.halfspaces.size());
  const Vec3 c = p.centroid();
  for (const PolyhedronFace& f : p.faces) {
    ASSERT_GE(f.halfspace, 0);
    ASSERT_LT(f.halfspace, static_cast<int>(p.halfspaces.size()));
    const Plane& h = p.halfspaces[static_cast<std::size_t>(f.halfspace)];
    EXPECT_NEAR(dot(h.normal, f.polygon.plane.normal), 1.0, 1e-12);
    EXPECT_NEAR(h.offset, f.polygon.plane.offset, 1e-9);
    EXPECT_LT(h.distance(c), 0);
    EXPECT_GT(f.polygon.area(), 0);
  }
}

TEST(PolyhedronBasics, FromAabb) {
  const auto p = ConvexPolyhedron::fromAabb(box({0, 0, 0}, {1, 2, 3}));
  ASSERT_TRUE(p);
  expectWellFormed(*p);
  EXPECT_EQ(p->faces.size(), 6u);
  EXPECT_DOUBLE_EQ(p->volume(), 6.0);
  EXPECT_NEAR(distance(p->centroid(), Vec3(0.5, 1, 1.5)), 0, 1e-15);
  for (const PolyhedronFace& f : p->faces) {
    // Corners are exact and the stored plane agrees with Newell's.
    const auto refit = ConvexPolygon::fromVertices(f.polygon.vertices, kUnitTol);
    ASSERT_TRUE(refit);
    EXPECT_EQ(refit->normal(), f.polygon.normal());
  }
  EXPECT_TRUE(p->contains({0.5, 0.5, 0.5}, kUnitTol));
  EXPECT_TRUE(p->contains({1, 2, 3}, kUnitTol));
  EXPECT_FALSE(p->contains({1.1, 0.5, 0.5}, kUnitTol));
  EXPECT_FALSE(ConvexPolyhedron::fromAabb(Aabb{}));
  EXPECT_FALSE(ConvexPolyhedron::fromAabb(box({0, 0, 0}, {1, 0, 1})));
}

TEST(PolyhedronFromHalfspaces, Cube) {
  const std::vector<Plane> cube{{{1, 0, 0}, 1},  {{-1, 0, 0}, 1}, {{0, 1, 0}, 1},
                                {{0, -1, 0}, 1}, {{0, 0, 1}, 1},  {{0, 0, -1}, 1}};
  const auto p = ConvexPolyhedron::fromHalfspaces(cube, Tolerance{4});
  ASSERT_TRUE(p);
  expectWellFormed(*p);
  EXPECT_EQ(p->faces.size(), 6u);
  EXPECT_NEAR(p->volume(), 8.0, 1e-9);
  EXPECT_NEAR(length(p->centroid()), 0, 1e-9);
  for (const PolyhedronFace& f : p->faces) {
    EXPECT_EQ(f.polygon.vertices.size(), 4u);
    EXPECT_NEAR(f.polygon.area(), 4.0, 1e-9);
  }
}

TEST(PolyhedronFromHalfspaces, RedundantDuplicateAndDegenerate) {
  std::vector<Plane> planes{{{1, 0, 0}, 1},  {{-1, 0, 0}, 1}, {{0, 1, 0}, 1},
                            {{0, -1, 0}, 1}, {{0, 0, 1}, 1},  {{0, 0, -1}, 1}};
  planes.push_back({{1, 0, 0}, 5});                 // redundant: dropped
  planes.push_back({{0, 0, 1}, 1});                 // duplicate: merged
  planes.push_back(Plane::through({1, 1, 1}, {1, 1, 1}));  // touches a corner only: dropped
  const auto p = ConvexPolyhedron::fromHalfspaces(planes, Tolerance{4});
  ASSERT_TRUE(p);
  EXPECT_EQ(p->faces.size(), 6u);
  EXPECT_EQ(p->halfspaces.size(), 6u);
  EXPECT_NEAR(p->volume(), 8.0, 1e-9);
  // Unbounded (no -z side), empty, and flat inputs.
  std::vector<Plane> open(planes.begin(), planes.begin() + 5);
  EXPECT_FALSE(ConvexPolyhedron::fromHalfspaces(open, Tolerance{4}));
  std::vector<Plane> empty = planes;
  empty.push_back({{-1, 0, 0}, -2});  // x >= 2
  EXPECT_FALSE(ConvexPolyhedron::fromHalfspaces(empty, Tolerance{4}));
  std::vector<Plane> flat(planes.begin(), planes.begin() + 6);
  flat[4] = {{0, 0, 1}, 0};
  flat[5] = {{0, 0, -1}, 0};  // 0 <= z <= 0
  EXPECT_FALSE(ConvexPolyhedron::fromHalfspaces(flat, Tolerance{4}));
}

TEST(PolyhedronFromHalfspaces, Tetrahedron) {
  // x >= 0, y >= 0, z >= 0, x + y + z <= 1: volume 1/6, centroid (1/4, 1/4, 1/4).
  const std::vector<Plane> planes{{{-1, 0, 0}, 0},
                                  {{0, -1, 0}, 0},
                                  {{0, 0, -1}, 0},
                                  Plane::through({1, 0, 0}, {1, 1, 1})};
  const auto p = ConvexPolyhedron::fromHalfspaces(planes, kUnitTol);
  ASSERT_TRUE(p);
  expectWellFormed(*p);
  EXPECT_EQ(p->faces.size(), 4u);
  for (const PolyhedronFace& f : p->faces) EXPECT_EQ(f.polygon.vertices.size(), 3u);
  EXPECT_NEAR(p->volume(), 1.0 / 6.0, 1e-12);
  EXPECT_NEAR(distance(p->centroid(), Vec3(0.25, 0.25, 0.25)), 0, 1e-12);
  EXPECT_EQ(p->classify(Plane{{1, 0, 0}, 0.5}, kUnitTol), PlaneSide::Spanning);
  EXPECT_EQ(p->classify(Plane{{1, 0, 0}, 1}, kUnitTol), PlaneSide::Back);
  EXPECT_EQ(p->classify(Plane{{1, 0, 0}, 0}, kUnitTol), PlaneSide::Front);
}

TEST(PolyhedronFromHalfspaces, RandomTetrahedraFarFromOrigin) {
  // Tetrahedra from random points, shifted far away: volume |det|/6 and 4 triangular faces.
  std::mt19937 rng(31337);
  std::uniform_real_distribution<double> u(-1, 1);
  const Vec3 shift{3e4, -2e4, 1e4};
  const Tolerance tol{1e5};
  int built = 0;
  for (int trial = 0; trial < 300; ++trial) {
    Vec3 v[4];
    for (Vec3& p : v) p = shift + Vec3{u(rng), u(rng), u(rng)} * 10.0;
    const double sixV = dot(cross(v[1] - v[0], v[2] - v[0]), v[3] - v[0]);
    if (std::abs(sixV) < 10) continue;  // skip near-flat ones
    if (sixV < 0) std::swap(v[1], v[2]);
    // Face (i, j, k) opposite vertex l, oriented away from l.
    const int faces[4][4] = {{1, 2, 3, 0}, {0, 3, 2, 1}, {0, 1, 3, 2}, {0, 2, 1, 3}};
    std::vector<Plane> planes;
    for (const auto& f : faces) {
      Plane h = Plane::through(v[f[0]], cross(v[f[1]] - v[f[0]], v[f[2]] - v[f[0]]));
      if (h.distance(v[f[3]]) > 0) h = h.flipped();
      planes.push_back(h);
    }
    const auto p = ConvexPolyhedron::fromHalfspaces(planes, tol);
    ASSERT_TRUE(p);
    ++built;
    expectWellFormed(*p);
    EXPECT_EQ(p->faces.size(), 4u);
    EXPECT_NEAR(p->volume(), std::abs(sixV) / 6.0, 1e-8 * std::abs(sixV));
    const Vec3 c = (v[0] + v[1] + v[2] + v[3]) * 0.25;
    EXPECT_LT(distance(p->centroid(), c), 1e-8);
    EXPECT_TRUE(p->contains(c, tol));
    EXPECT_FALSE(p->contains(v[0] + (v[0] - c) * 0.01, tol));
  }
  EXPECT_GT(built, 150);
}

TEST(PolyhedronSplit, CubeInHalves) {
  auto p = ConvexPolyhedron::fromAabb(box({0, 0, 0}, {2, 2, 2}));
  ASSERT_TRUE(p);
  for (PolyhedronFace& f : p->faces) f.planeId = 100 + f.halfspace;
  const Plane cut{{0, 0, 1}, 0.5};
  const PolyhedronSplit s = split(*p, cut, Tolerance{4}, 7);
  ASSERT_TRUE(s.front && s.back);
  expectWellFormed(*s.front);
  expectWellFormed(*s.back);
  EXPECT_NEAR(s.front->volume(), 6.0, 1e-12);
  EXPECT_NEAR(s.back->volume(), 2.0, 1e-12);
  EXPECT_EQ(s.front->faces.size(), 6u);
  EXPECT_EQ(s.back->faces.size(), 6u);
  int caps = 0;
  for (const PolyhedronFace& f : s.back->faces) {
    if (f.planeId == 7) {
      ++caps;
      EXPECT_NEAR(dot(f.polygon.normal(), cut.normal), 1, 1e-15);  // out of the back piece
      EXPECT_NEAR(f.polygon.area(), 4, 1e-12);
    } else {
      EXPECT_GE(f.planeId, 100);  // plane ids survive the split
    }
  }
  EXPECT_EQ(caps, 1);
  for (const PolyhedronFace& f : s.front->faces) {
    if (f.planeId == 7) {
      EXPECT_NEAR(dot(f.polygon.normal(), cut.normal), -1, 1e-15);
    }
  }
  // Non-cuts: touching a face, or missing the cell.
  EXPECT_TRUE(split(*p, Plane{{0, 0, 1}, 2}, Tolerance{4}).back);
  EXPECT_FALSE(split(*p, Plane{{0, 0, 1}, 2}, Tolerance{4}).front);
  EXPECT_TRUE(split(*p, Plane{{0, 0, 1}, -1}, Tolerance{4}).front);
  // A cut a fraction of the tolerance inside the cell leaves it whole.
  const PolyhedronSplit graze = split(*p, Plane{{0, 0, 1}, 2 - 1e-9}, Tolerance{4});
  EXPECT_TRUE(graze.back);
  EXPECT_FALSE(graze.front);
  // Through an edge: two triangular prisms.
  const PolyhedronSplit diag = split(*p, Plane::through({0, 0, 0}, {1, -1, 0}), Tolerance{4});
  ASSERT_TRUE(diag.front && diag.back);
  EXPECT_EQ(diag.front->faces.size(), 5u);
  EXPECT_NEAR(diag.front->volume(), 4, 1e-12);
}

Plane randomPlaneThrough(std::mt19937& rng, const Vec3& center, double spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  for (;;) {
    const Vec3 n{u(rng), u(rng), u(rng)};
    if (length(n) > 0.1) {
      return Plane::through(center + Vec3{u(rng), u(rng), u(rng)} * spread, n);
    }
  }
}

TEST(PolyhedronSplit, RandomRecursiveSplitsConserveVolumeAndPartitionPoints) {
  std::mt19937 rng(4242);
  std::uniform_real_distribution<double> u(0, 1);
  const Aabb world = box({-1, -2, -3}, {4, 3, 2});
  const Tolerance tol = Tolerance::forBounds(world);
  int spanning = 0, attempts = 0;
  for (int scene = 0; scene < 20; ++scene) {
    // Cut the box recursively with random planes, like a BSP: cells must tile the box.
    std::vector<ConvexPolyhedron> cells{*ConvexPolyhedron::fromAabb(world)};
    for (int step = 0; step < 40; ++step) {
      const std::size_t k = rng() % cells.size();
      const ConvexPolyhedron cell = cells[k];
      const Plane plane = randomPlaneThrough(rng, cell.centroid(), 0.5 * cell.bounds().diagonal());
      const PolyhedronSplit s = split(cell, plane, tol, step);
      ++attempts;
      ASSERT_TRUE(s.front || s.back);
      const double vf = s.front ? s.front->volume() : 0, vb = s.back ? s.back->volume() : 0;
      EXPECT_NEAR(vf + vb, cell.volume(), 1e-9 * world.diagonal() * world.diagonal());
      const double eps = tol.length();
      if (s.front) {
        expectWellFormed(*s.front);
        for (const auto& f : s.front->faces) {
          for (const Vec3& v : f.polygon.vertices) EXPECT_GE(plane.distance(v), -eps);
        }
      }
      if (s.back) {
        expectWellFormed(*s.back);
        for (const auto& f : s.back->faces) {
          for (const Vec3& v : f.polygon.vertices) EXPECT_LE(plane.distance(v), eps);
        }
      }
      if (s.front && s.back) {
        ++spanning;
        cells[k] = *s.front;
        cells.push_back(*s.back);
      }
    }
    double total = 0;
    for (const ConvexPolyhedron& c : cells) total += c.volume();
    EXPECT_NEAR(total, 125.0, 1e-9);
    // Random points of the box lie in exactly one cell (skip points within 1e-7 of a boundary,
    // where two cells legitimately share them).
    for (int i = 0; i < 200; ++i) {
      const Vec3 p{world.lo.x + 5 * u(rng), world.lo.y + 5 * u(rng), world.lo.z + 5 * u(rng)};
      int inside = 0;
      bool nearBoundary = false;
      for (const ConvexPolyhedron& c : cells) {
        double worst = -INFINITY;
        for (const Plane& h : c.halfspaces) worst = std::max(worst, h.distance(p));
        if (std::abs(worst) < 1e-7) nearBoundary = true;
        inside += c.contains(p, tol);
      }
      if (!nearBoundary) {
        EXPECT_EQ(inside, 1) << p;
      }
    }
  }
  // The generator really cuts cells most of the time.
  EXPECT_GT(spanning, attempts / 2);
}

TEST(PolyhedronSplit, NearlyCoplanarVerticesSnapToOn) {
  // Cutting exactly along (rounded) existing vertices must not create sliver cells.
  const Aabb world = box({0, 0, 0}, {1, 1, 1});
  const Tolerance tol = Tolerance::forBounds(world);
  auto cube = *ConvexPolyhedron::fromAabb(world);
  const PolyhedronSplit first = split(cube, Plane::through({0.3, 0, 0}, {1, 0.2, 0.1}), tol);
  ASSERT_TRUE(first.front && first.back);
  // The same plane again, nudged by far less than the tolerance: no further cut.
  const Plane again = Plane::through({0.3 + 1e-13, 0, 0}, {1, 0.2, 0.1});
  const PolyhedronSplit s = split(*first.front, again, tol);
  EXPECT_TRUE(s.front);
  EXPECT_FALSE(s.back);
}

}  // namespace
}  // namespace gv
