// Stratified jittered points on convex polygons. HSA91 §3 (visibility by jittered rays).
#include "radiosity/polygon_sampling.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace gv {

uint64_t mixSeed(uint64_t a, uint64_t b, uint64_t c) {
  SplitMix64 g(a ^ 0x243F6A8885A308D3ull);
  uint64_t h = g.next() ^ b;
  SplitMix64 g2(h);
  h = g2.next() ^ c;
  SplitMix64 g3(h);
  return g3.next();
}

double kernelWeight(const Vec3& x, const Vec3& nx, const Vec3& y, const Vec3& ny) {
  const Vec3 d = y - x;
  const double r2 = dot(d, d);
  if (!(r2 > 0)) return 0.0;
  const double cx = dot(nx, d), cy = -dot(ny, d);
  if (!(cx > 0) || !(cy > 0)) return 0.0;
  return cx * cy / (r2 * r2);
}

Vec3 cosineDirection(const Vec3& n, SplitMix64& rng) {
  const auto [u, w] = perpendicularFrame(n);
  const double r2 = rng.uniform(), phi = 2 * std::numbers::pi * rng.uniform();
  const double r = std::sqrt(r2);
  return u * (r * std::cos(phi)) + w * (r * std::sin(phi)) + n * std::sqrt(std::max(0.0, 1 - r2));
}

Vec3 uniformPoint(std::span<const Vec3> v, SplitMix64& rng) {
  double total = 0;
  for (size_t k = 1; k + 1 < v.size(); ++k) total += length(cross(v[k] - v[0], v[k + 1] - v[0]));
  double pick = rng.uniform() * total;
  size_t k = 1;
  for (; k + 2 < v.size(); ++k) {
    const double a = length(cross(v[k] - v[0], v[k + 1] - v[0]));
    if (pick < a) break;
    pick -= a;
  }
  double s = rng.uniform(), t = rng.uniform();
  if (s + t > 1) {
    s = 1 - s;
    t = 1 - t;
  }
  return v[0] + (v[k] - v[0]) * s + (v[k + 1] - v[0]) * t;
}

std::vector<Vec3> stratifiedPoints(std::span<const Vec3> vertices, int count, SplitMix64& rng) {
  std::vector<Vec3> points;
  if (count <= 0 || vertices.size() < 3) return points;
  // Cumulative fan-triangle areas around vertex 0 (convex, so the fan covers the polygon).
  const size_t triangles = vertices.size() - 2;
  std::vector<double> cdf(triangles + 1, 0.0);
  for (size_t k = 0; k < triangles; ++k)
    cdf[k + 1] =
        cdf[k] + length(cross(vertices[k + 1] - vertices[0], vertices[k + 2] - vertices[0]));
  const double total = cdf.back();
  if (!(total > 0)) return std::vector<Vec3>(static_cast<size_t>(count), vertices[0]);

  std::vector<int> permutation(static_cast<size_t>(count));
  std::iota(permutation.begin(), permutation.end(), 0);
  for (size_t i = permutation.size(); i > 1; --i)  // Fisher–Yates
    std::swap(permutation[i - 1], permutation[static_cast<size_t>(rng.next() % i)]);

  points.reserve(static_cast<size_t>(count));
  const double n = static_cast<double>(count);
  for (int i = 0; i < count; ++i) {
    const double u1 = (i + rng.uniform()) / n * total;
    const double u2 = (permutation[static_cast<size_t>(i)] + rng.uniform()) / n;
    size_t k = static_cast<size_t>(std::upper_bound(cdf.begin(), cdf.end(), u1) - cdf.begin());
    k = std::clamp<size_t>(k, 1, triangles) - 1;
    const double s = std::clamp((u1 - cdf[k]) / (cdf[k + 1] - cdf[k]), 0.0, 1.0);
    // Uniform on the triangle (v0, vk+1, vk+2): sqrt warps the first coordinate so that equal
    // strata get equal area.
    const double a = std::sqrt(s);
    const Vec3& p0 = vertices[0];
    const Vec3& p1 = vertices[k + 1];
    const Vec3& p2 = vertices[k + 2];
    points.push_back(p0 * (1.0 - a) + (p1 * (1.0 - u2) + p2 * u2) * a);
  }
  return points;
}

}  // namespace gv
