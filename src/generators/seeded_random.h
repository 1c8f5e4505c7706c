// Seeded random numbers whose values are the same on every platform, for reproducible generators.
#pragma once

#include <cstdint>
#include <random>

namespace gv {

/// std::mt19937 is specified bit-exactly by the standard, but std::uniform_*_distribution are not
/// (libstdc++ and libc++ give different numbers), so generators map its raw 32-bit output
/// themselves with these two functions.
class SeededRandom {
 public:
  explicit SeededRandom(uint32_t seed) : engine_(seed) {}

  /// Uniform in [0, 1): one 32-bit draw scaled by 2^-32 (resolution 2.3e-10, plenty for layout).
  double uniform01() { return static_cast<double>(engine_()) * 0x1p-32; }
  /// Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform01(); }
  /// Integer in [0, n) for n >= 1, by the multiply-shift mapping (bias below n / 2^32, irrelevant
  /// for layout choices and identical everywhere).
  uint32_t below(uint32_t n) {
    return static_cast<uint32_t>((static_cast<uint64_t>(engine_()) * n) >> 32);
  }

 private:
  std::mt19937 engine_;
};

}  // namespace gv
