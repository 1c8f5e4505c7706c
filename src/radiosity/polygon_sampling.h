// Stratified random points on convex polygons and a small deterministic generator: the sample
// end points of visibility rays between two elements (HSA91 §3: "jittered" ray casting).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/vec3.h"

namespace gv {

/// SplitMix64 (Steele, Lea & Flood 2014): tiny, fast, and good enough for jittering samples.
/// Deterministic: the same seed gives the same stream on every platform.
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t state_;
};

/// Mixes values into one 64-bit seed (order matters).
uint64_t mixSeed(uint64_t a, uint64_t b, uint64_t c = 0);

/// `count` points on the convex polygon `vertices`, stratified as a Latin hypercube: the first
/// coordinate (which picks the fan triangle by area, then the position across it) falls in
/// stratum i of `count` for point i, the second in a random permutation of the strata, each
/// jittered. Uniform in area for triangles and n-gons; for quads as well (the fan is used for
/// every polygon). The points are strictly inside the polygon with probability 1.
std::vector<Vec3> stratifiedPoints(std::span<const Vec3> vertices, int count, SplitMix64& rng);

/// One uniform point of the convex polygon `vertices`: a fan triangle by area, then a uniform
/// point in it. No allocation (the photon tracer and the cluster links call it per sample).
Vec3 uniformPoint(std::span<const Vec3> vertices, SplitMix64& rng);

/// A direction about unit normal `n` with density cos θ / π (Malley's method): the photon
/// tracer's diffuse bounces, and a gather whose mean over hits is Σ F·B.
Vec3 cosineDirection(const Vec3& n, SplitMix64& rng);

/// The weight of a visibility sample between `x` on a surface with unit normal `nx` and `y` with
/// unit normal `ny`: the form-factor kernel cos θx cos θy / r² (0 when either faces away). The
/// visibility of a link is the kernel-weighted mean of the samples, Σ K V / Σ K, not the plain
/// fraction: near parts of two elements, which carry most of the light, are usually less occluded
/// than far ones, and the plain fraction then makes a solution too dark (measured 2-3 % on the
/// office's walls).
double kernelWeight(const Vec3& x, const Vec3& nx, const Vec3& y, const Vec3& ny);

}  // namespace gv
