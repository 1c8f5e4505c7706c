// Brute-force references for the linespace tests, written without Plücker coordinates: a segment
// meets a convex polygon iff it crosses the polygon's plane at a point inside every edge; and
// seeded random configurations of two elements and blockers.
#pragma once

#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

#include "geometry/convex_polygon.h"
#include "visibility/ray_oracle.h"

namespace gv::test {

/// Does the open segment p–q meet the closed convex polygon? (plane crossing + 2D inside test)
inline bool segmentHitsPolygon(const Vec3& p, const Vec3& q, const ConvexPolygon& poly) {
  const Vec3 n = poly.plane.normal;
  const double dp = poly.plane.distance(p), dq = poly.plane.distance(q);
  if (!((dp > 0 && dq < 0) || (dp < 0 && dq > 0))) return false;
  const Vec3 x = p + (q - p) * (dp / (dp - dq));
  const auto& v = poly.vertices;
  for (size_t k = 0; k < v.size(); ++k)
    if (dot(cross(v[(k + 1) % v.size()] - v[k], x - v[k]), n) < 0) return false;
  return true;
}

/// A random point of S and one of R such that the segment runs from S's front to R's front
/// (the segments that carry light); nullopt after many misses.
inline std::optional<std::pair<Vec3, Vec3>> frontSegment(const ConvexPolygon& s,
                                                         const ConvexPolygon& r,
                                                         std::mt19937& rng) {
  for (int attempt = 0; attempt < 64; ++attempt) {
    const Vec3 p = randomPointOn(s, rng), q = randomPointOn(r, rng);
    if (s.plane.distance(q) > 0 && r.plane.distance(p) > 0) return std::make_pair(p, q);
  }
  return std::nullopt;
}

/// Orthonormal u, v with u x v = n (n unit).
inline void frameOf(const Vec3& n, Vec3& u, Vec3& v) {
  u = normalize(std::abs(n.x) < 0.9 ? cross(n, {1, 0, 0}) : cross(n, {0, 1, 0}));
  v = cross(n, u);
}

inline Vec3 randomUnit(std::mt19937& rng) {
  std::normal_distribution<double> g(0, 1);
  for (;;) {
    const Vec3 d{g(rng), g(rng), g(rng)};
    if (length(d) > 1e-3) return normalize(d);
  }
}

/// A random convex polygon with 3 to 5 vertices (mostly quads) centred at c, facing n, of
/// radius about `size`: a regular-ish polygon with jittered angles and radii, counter-clockwise
/// seen from n.
inline ConvexPolygon randomPolygon(const Vec3& c, const Vec3& n, double size, std::mt19937& rng,
                                   int vertices = 0) {
  std::uniform_real_distribution<double> u(0, 1);
  Vec3 e1, e2;
  frameOf(n, e1, e2);
  if (vertices == 0) vertices = u(rng) < 0.7 ? 4 : (u(rng) < 0.5 ? 3 : 5);
  const double stretch = 0.4 + 1.2 * u(rng);
  for (;;) {
    std::vector<Vec3> pts;
    const double phase = u(rng) * 2 * std::numbers::pi;
    for (int k = 0; k < vertices; ++k) {
      const double a = phase + (k + 0.3 * (u(rng) - 0.5)) * 2 * std::numbers::pi / vertices;
      const double rad = size * (0.8 + 0.4 * u(rng));
      pts.push_back(c + e1 * (rad * std::cos(a) * stretch) + e2 * (rad * std::sin(a)));
    }
    // Points on a star around c at increasing angles are convex if every turn is left.
    bool convex = true;
    for (int k = 0; k < vertices && convex; ++k) {
      const Vec3& a = pts[k];
      const Vec3& b = pts[(k + 1) % vertices];
      const Vec3& d = pts[(k + 2) % vertices];
      convex = dot(cross(b - a, d - b), n) > 0;
    }
    if (!convex) continue;
    if (auto p = ConvexPolygon::fromVertices(pts, Tolerance{100})) return *p;
  }
}

}  // namespace gv::test
