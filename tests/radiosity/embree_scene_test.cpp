// EmbreeScene against a brute-force double-precision segment/polygon test on seeded random
// scenes and segments (cases within a float-rounding margin of an edge are skipped as ambiguous).
#include "raycast/embree_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "generators/scene_builder.h"

namespace gv {
namespace {

/// Where the open segment p + t (q - p), t in (0,1), crosses polygon `poly`: t, and the distance of
/// the crossing from the polygon's boundary (negative outside). nullopt if parallel or t outside.
struct Crossing {
  double t;
  double edgeDistance;
};
std::optional<Crossing> crossing(const ConvexPolygon& poly, const Vec3& p, const Vec3& q) {
  const double dp = poly.plane.distance(p), dq = poly.plane.distance(q);
  if ((dp > 0) == (dq > 0) || dp == dq) return std::nullopt;
  const double t = dp / (dp - dq);
  const Vec3 x = p + (q - p) * t;
  double inside = INFINITY;
  const auto& v = poly.vertices;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 e = v[(i + 1) % v.size()] - v[i];
    // Signed distance of x from edge i's line, positive inside (counter-clockwise polygon).
    const double d = dot(cross(e, x - v[i]), poly.plane.normal) / length(e);
    inside = std::min(inside, d);
  }
  return Crossing{t, inside};
}

Scene randomScene(std::mt19937_64& rng, int count) {
  Scene scene;
  const uint32_t m = scene.addMaterial({});
  SceneBuilder builder(scene, Tolerance{2.0});
  std::uniform_real_distribution<double> u(0.0, 1.0), s(0.05, 0.3);
  while (static_cast<int>(scene.patches.size()) < count) {
    const Vec3 c{u(rng), u(rng), u(rng)};
    // A random planar quad: two random orthogonal in-plane axes around c.
    Vec3 n = normalize(Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5});
    Vec3 e1 = normalize(cross(n, std::abs(n.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    Vec3 e2 = cross(n, e1);
    const double a = s(rng), b = s(rng);
    builder.addQuad(c - e1 * a - e2 * b, c + e1 * a - e2 * b, c + e1 * a + e2 * b,
                    c - e1 * a + e2 * b, m);
  }
  return scene;
}

TEST(EmbreeSceneTest, OccludedAgreesWithBruteForceOnRandomSegments) {
  std::mt19937_64 rng(12345);
  const Scene scene = randomScene(rng, 60);
  const EmbreeScene bvh(scene);
  EXPECT_EQ(bvh.patchCount(), scene.patches.size());
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  const double margin = 1e-4;  // float rounding at unit scale is ~1e-7; stay far from it
  int blocked = 0, clear = 0, ambiguous = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Vec3 p{u(rng), u(rng), u(rng)}, q{u(rng), u(rng), u(rng)};
    bool hit = false, unsure = false;
    for (const Patch& patch : scene.patches) {
      const std::optional<Crossing> c = crossing(patch.polygon, p, q);
      if (!c) continue;
      if (std::abs(c->edgeDistance) < margin)
        unsure = true;
      else if (c->edgeDistance > 0)
        hit = true;
    }
    if (unsure) {
      ++ambiguous;
      continue;
    }
    EXPECT_EQ(bvh.occluded(p, q), hit) << "trial " << trial;
    hit ? ++blocked : ++clear;
  }
  // The generator is not trivial: both outcomes occur often.
  EXPECT_GT(blocked, 300);
  EXPECT_GT(clear, 300);
  EXPECT_LT(ambiguous, 100);
}

TEST(EmbreeSceneTest, FirstHitIsTheNearestCrossing) {
  std::mt19937_64 rng(777);
  const Scene scene = randomScene(rng, 40);
  const EmbreeScene bvh(scene);
  std::uniform_real_distribution<double> u(-0.2, 1.2);
  int hits = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Vec3 p{u(rng), u(rng), u(rng)}, q{u(rng), u(rng), u(rng)};
    std::optional<std::pair<double, uint32_t>> best;
    bool unsure = false;
    for (uint32_t id = 0; id < scene.patches.size(); ++id) {
      const std::optional<Crossing> c = crossing(scene.patches[id].polygon, p, q);
      if (!c) continue;
      if (std::abs(c->edgeDistance) < 1e-4)
        unsure = true;
      else if (c->edgeDistance > 0 && (!best || c->t < best->first))
        best = {{c->t, id}};
    }
    if (unsure) continue;
    const std::optional<RayHit> h = bvh.firstHit(p, q - p, 1.0);
    ASSERT_EQ(h.has_value(), best.has_value()) << "trial " << trial;
    if (!h) continue;
    ++hits;
    // Two crossings closer than float resolution could swap; the random scene makes that rare.
    EXPECT_EQ(h->patch, best->second) << "trial " << trial;
    EXPECT_NEAR(h->t, best->first, 1e-5);
  }
  EXPECT_GT(hits, 200);
}

TEST(EmbreeSceneTest, IgnoredPatchesDoNotBlock) {
  // Two parallel squares at z = 1 and z = 2 over [0,1]^2; a segment through both.
  Scene scene;
  const uint32_t m = scene.addMaterial({});
  SceneBuilder builder(scene, Tolerance{4.0});
  builder.addQuad({0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}, m);
  builder.addQuad({0, 0, 2}, {1, 0, 2}, {1, 1, 2}, {0, 1, 2}, m);
  const EmbreeScene bvh(scene);
  const Vec3 p{0.5, 0.5, 0}, q{0.5, 0.5, 3};
  EXPECT_TRUE(bvh.occluded(p, q));
  EXPECT_TRUE(bvh.occluded(p, q, 0));
  EXPECT_TRUE(bvh.occluded(p, q, kNoPatch, 1));
  EXPECT_FALSE(bvh.occluded(p, q, 0, 1));
  EXPECT_FALSE(bvh.occluded(p, q, 1, 0));
  // End points on the patches themselves: ignored, the segment between them is clear.
  EXPECT_FALSE(bvh.occluded({0.3, 0.3, 1}, {0.6, 0.7, 2}, 0, 1));
  const std::optional<RayHit> h = bvh.firstHit(p, {0, 0, 1}, INFINITY, 0);
  ASSERT_TRUE(h.has_value());
  EXPECT_EQ(h->patch, 1u);
  EXPECT_NEAR(h->t, 2.0, 1e-6);
  EXPECT_FALSE(bvh.firstHit(p, {0, 0, -1}).has_value());
}

TEST(EmbreeSceneTest, FarFromOriginKeepsPrecision) {
  // A 1 m square 10 km from the origin: translation to the scene centre keeps float precision.
  Scene scene;
  const uint32_t m = scene.addMaterial({});
  const double o = 1e4;
  SceneBuilder builder(scene, Tolerance{2.0});
  builder.addQuad({o, o, o}, {o + 1, o, o}, {o + 1, o + 1, o}, {o, o + 1, o}, m);
  const EmbreeScene bvh(scene);
  EXPECT_TRUE(bvh.occluded({o + 0.999, o + 0.5, o - 1}, {o + 0.999, o + 0.5, o + 1}));
  EXPECT_FALSE(bvh.occluded({o + 1.001, o + 0.5, o - 1}, {o + 1.001, o + 0.5, o + 1}));
}

}  // namespace
}  // namespace gv
