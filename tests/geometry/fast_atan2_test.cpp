// fastAtan2 against atan2l in extended precision (an independent evaluation: libm's long double
// code, 64-bit mantissa), over the whole circle, tiny and near-right angles, the table's seams
// and the special values whose conventions must not change.
#include "geometry/fast_atan2.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

namespace gv {
namespace {

/// The bound: 1e-15 relative to the angle (about 4.5 ulp), which is what Lambert's formula
/// needs to keep far, small sources' form factors (sums of angles that cancel to 1e-8) accurate.
/// Not a ratchet: the method's error is ~2 ulp (rounding of two divisions, one table entry and
/// the sum), and the series' truncation is ~1e-20.
constexpr double kRelative = 1e-15;

void expectClose(double y, double x) {
  const long double ref = atan2l(static_cast<long double>(y), static_cast<long double>(x));
  const double got = fastAtan2(y, x);
  const long double err = std::abs(static_cast<long double>(got) - ref);
  EXPECT_LE(err, kRelative * std::abs(ref))
      << "y " << y << " x " << x << " got " << got << " ref " << static_cast<double>(ref);
}

TEST(FastAtan2, WholeCircleAnyScale) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(-std::numbers::pi, std::numbers::pi);
  std::uniform_real_distribution<double> exponent(-30, 30);
  for (int i = 0; i < 200000; ++i) {
    const double a = angle(rng), r = std::pow(10.0, exponent(rng));
    expectClose(r * std::sin(a), r * std::cos(a));
  }
}

TEST(FastAtan2, TinyAndNearRightAngles) {
  for (int k = 1; k <= 300; ++k) {
    const double tiny = std::pow(10.0, -k);
    for (const double sx : {1.0, -1.0})
      for (const double sy : {1.0, -1.0}) {
        expectClose(sy * tiny, sx);  // near 0 or ±π
        expectClose(sy, sx * tiny);  // near ±π/2
        expectClose(sy * 3.7 * tiny, sx * 2.9);
      }
  }
}

TEST(FastAtan2, TableSeamsAndOctantEdges) {
  for (int j = 0; j <= 32; ++j) {
    const double t = j / 32.0;
    for (const double d : {-1e-12, -1e-16, 0.0, 1e-16, 1e-12}) {
      const double tt = t + d;
      if (tt < 0) continue;
      expectClose(tt, 1.0);
      expectClose(1.0, tt);
      expectClose(-tt, -1.0);
      expectClose(1.0, -tt);
    }
  }
  expectClose(1.0, 1.0);
  expectClose(-1.0, -1.0);
  expectClose(1.0, std::nextafter(1.0, 2.0));
}

TEST(FastAtan2, SpecialValuesKeepLibmConventions) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const double y : {0.0, -0.0, 1.0, -1.0, inf, -inf})
    for (const double x : {0.0, -0.0, 1.0, -1.0, inf, -inf}) {
      const double want = std::atan2(y, x), got = fastAtan2(y, x);
      EXPECT_EQ(got, want) << y << " " << x;
      EXPECT_EQ(std::signbit(got), std::signbit(want)) << y << " " << x;
    }
  EXPECT_TRUE(std::isnan(fastAtan2(nan, 1.0)));
  EXPECT_TRUE(std::isnan(fastAtan2(1.0, nan)));
  EXPECT_TRUE(std::isnan(fastAtan2(nan, nan)));
}

}  // namespace
}  // namespace gv
