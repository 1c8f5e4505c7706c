// Small numeric helpers shared by the tests' independent oracles (tests/bsp/bsp_oracle.h,
// tests/generators/scene_oracle.h, the random lines of the stabbing and leaf-PVS tests). Written
// for the tests; uses only Vec3 arithmetic, none of the library's algorithms.
#pragma once

#include <cmath>
#include <random>
#include <vector>

#include "geometry/vec3.h"

namespace gv::test {

/// Uniform double in [lo, hi) from one raw mt19937 draw (portable, unlike the std
/// distributions).
inline double uniform(std::mt19937& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng()) * 0x1p-32);
}

/// Twice the vector area of a polygon: the sum of its fan triangles' cross products from vertex 0
/// (Newell-style; its direction is the counter-clockwise normal).
inline Vec3 vectorArea2(const std::vector<Vec3>& v) {
  Vec3 sum;
  for (size_t i = 1; i + 1 < v.size(); ++i) sum += cross(v[i] - v[0], v[i + 1] - v[0]);
  return sum;
}

/// A random point of the convex hull of `w`: a convex combination with exponential weights.
inline Vec3 randomPointIn(std::mt19937_64& rng, const std::vector<Vec3>& w) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> wts(w.size());
  double sum = 0;
  for (double& x : wts) x = -std::log(u(rng) + 1e-300), sum += x;
  Vec3 p{};
  for (size_t i = 0; i < w.size(); ++i) p += w[i] * (wts[i] / sum);
  return p;
}

}  // namespace gv::test
