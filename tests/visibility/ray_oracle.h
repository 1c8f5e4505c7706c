// A brute-force ray caster over a scene's patches, written independently of the visibility code:
// the oracle that propagation tests are checked against.
#pragma once

#include <cmath>
#include <numbers>
#include <optional>
#include <random>

#include "scene/scene.h"

namespace gv::test {

struct RayHit {
  uint32_t patch = 0;
  double t = 0;
  bool front = false;  ///< the ray meets the patch's front (travels against its normal)
};

/// First patch met by origin + t·dir for t in (tMin, tMax), skipping `skip` (the source patch).
inline std::optional<RayHit> firstHit(const Scene& scene, const Vec3& origin, const Vec3& dir,
                                      double tMin, double tMax, uint32_t skip) {
  std::optional<RayHit> best;
  for (uint32_t i = 0; i < scene.patches.size(); ++i) {
    if (i == skip) continue;
    const ConvexPolygon& poly = scene.patches[i].polygon;
    const Vec3 n = poly.plane.normal;
    const double denom = dot(n, dir);
    if (denom == 0) continue;
    const double t = (poly.plane.offset - dot(n, origin)) / denom;
    if (!(t > tMin && t < tMax) || (best && t >= best->t)) continue;
    const Vec3 x = origin + dir * t;
    bool inside = true;
    const auto& v = poly.vertices;
    for (size_t k = 0; k < v.size() && inside; ++k)
      inside = dot(cross(v[(k + 1) % v.size()] - v[k], x - v[k]), n) >= 0;
    if (inside) best = RayHit{i, t, denom < 0};
  }
  return best;
}

/// A uniform random point of a convex polygon (triangle fan weighted by area).
inline Vec3 randomPointOn(const ConvexPolygon& poly, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const auto& v = poly.vertices;
  double total = 0;
  for (size_t k = 1; k + 1 < v.size(); ++k) total += length(cross(v[k] - v[0], v[k + 1] - v[0]));
  double pick = u(rng) * total;
  size_t k = 1;
  for (; k + 2 < v.size(); ++k) {
    const double a = length(cross(v[k] - v[0], v[k + 1] - v[0]));
    if (pick < a) break;
    pick -= a;
  }
  double a = u(rng), b = u(rng);
  if (a + b > 1) a = 1 - a, b = 1 - b;
  return v[0] + (v[k] - v[0]) * a + (v[k + 1] - v[0]) * b;
}

/// A cosine-distributed direction about unit normal n.
inline Vec3 cosineDirection(const Vec3& n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double r = std::sqrt(u(rng)), phi = 2 * std::numbers::pi * u(rng);
  const Vec3 t = normalize(std::abs(n.x) < 0.9 ? cross(n, {1, 0, 0}) : cross(n, {0, 1, 0}));
  const Vec3 b = cross(n, t);
  return t * (r * std::cos(phi)) + b * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - r * r));
}

}  // namespace gv::test
