// Independent checks for generated scenes: polygon validity, divergence-theorem volume, and
// brute-force segment casting. Written from scratch for the tests; shares no code with src/
// (the arithmetic helpers are tests/support/oracle_math.h).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <string>

#include "scene/scene.h"
#include "support/oracle_math.h"

namespace gv::testing {

using test::uniform;
using test::vectorArea2;

/// Checks one patch: >= 3 finite vertices, positive area, planar, strictly convex, normal unit
/// and on the counter-clockwise side. `scale` is the scene size for relative tolerances.
inline ::testing::AssertionResult isValidPatch(const Patch& patch, double scale) {
  const auto& v = patch.polygon.vertices;
  if (v.size() < 3) return ::testing::AssertionFailure() << "fewer than 3 vertices";
  for (const Vec3& p : v) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      return ::testing::AssertionFailure() << "non-finite vertex";
  }
  const Vec3 a2 = vectorArea2(v);
  const double area = 0.5 * length(a2);
  if (!(area > 1e-12 * scale * scale)) return ::testing::AssertionFailure() << "zero area";
  const Vec3 n = a2 / length(a2);
  const Vec3 pn = patch.polygon.plane.normal;
  if (std::abs(length(pn) - 1) > 1e-9) return ::testing::AssertionFailure() << "normal not unit";
  if (dot(n, pn) < 1 - 1e-9) return ::testing::AssertionFailure() << "normal not CCW side " << n << pn;
  for (size_t i = 0; i < v.size(); ++i) {
    if (std::abs(dot(v[i] - v[0], n)) > 1e-9 * scale)
      return ::testing::AssertionFailure() << "non-planar";
    const Vec3& p = v[i];
    const Vec3& q = v[(i + 1) % v.size()];
    const Vec3& r = v[(i + 2) % v.size()];
    if (dot(cross(q - p, r - q), n) <= 0) return ::testing::AssertionFailure() << "not convex";
  }
  return ::testing::AssertionSuccess();
}

/// Sum over patches of area * dot(centroid, normal) / 3: by the divergence theorem, the volume
/// enclosed by closed outward-oriented surfaces (signed: inward-facing surfaces subtract).
/// Emitters (open light panels) are skipped.
inline double divergenceVolume(const Scene& scene) {
  double sum = 0;
  for (const Patch& patch : scene.patches) {
    if (scene.materials[patch.material].isEmitter()) continue;
    // Over a planar polygon dot(x, n) is constant, so area * dot(any vertex, n) suffices; the
    // fan sum of vertex area vectors gives area * n directly.
    const auto& v = patch.polygon.vertices;
    sum += dot(v[0], vectorArea2(v)) / 6.0;
  }
  return sum;
}

/// Whether segment p-q meets the polygon at a point strictly between its ends (a relative margin
/// `endEps` of the segment excluded at each end). Segments parallel to the polygon's plane never
/// hit (random segments are almost never coplanar).
inline bool segmentHits(const Vec3& p, const Vec3& q, const std::vector<Vec3>& poly,
                        double endEps = 1e-9) {
  const Vec3 n = vectorArea2(poly);
  const Vec3 d = q - p;
  const double denom = dot(n, d);
  if (denom == 0) return false;
  const double t = dot(n, poly[0] - p) / denom;
  if (!(t > endEps && t < 1 - endEps)) return false;
  const Vec3 x = p + d * t;
  for (size_t i = 0; i < poly.size(); ++i) {
    const Vec3& a = poly[i];
    const Vec3& b = poly[(i + 1) % poly.size()];
    if (dot(cross(b - a, x - a), n) < 0) return false;
  }
  return true;
}

/// Whether any patch of the scene meets segment p-q.
inline bool segmentBlocked(const Scene& scene, const Vec3& p, const Vec3& q) {
  for (const Patch& patch : scene.patches) {
    if (segmentHits(p, q, patch.polygon.vertices)) return true;
  }
  return false;
}

/// Material index by name; fails the test when absent.
inline uint32_t materialNamed(const Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    if (scene.materials[i].name == name) return static_cast<uint32_t>(i);
  }
  ADD_FAILURE() << "no material " << name;
  return UINT32_MAX;
}

/// Point uniformly inside [lo, hi] shrunk by `margin` on every side.
inline Vec3 pointIn(std::mt19937& rng, const Vec3& lo, const Vec3& hi, double margin) {
  return {uniform(rng, lo.x + margin, hi.x - margin), uniform(rng, lo.y + margin, hi.y - margin),
          uniform(rng, lo.z + margin, hi.z - margin)};
}

}  // namespace gv::testing
