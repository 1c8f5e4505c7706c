// atan2 in a table lookup, two divisions and a short odd polynomial. Lambert's point-to-polygon
// form factor (radiosity/form_factor.h) takes one angle per polygon edge, millions of times per
// run, and libm's atan2 was a third of a radiosity run on the default office (perf: 29 % in
// __ieee754_atan2_fma, 4 % in its wrapper), and about a quarter on the real levels.
#pragma once

#include <array>
#include <cmath>
#include <numbers>

namespace gv {
namespace detail {

/// atan(j / 16) for j = 0..16, from libm once (correctly rounded or within an ulp).
inline const std::array<double, 17> kAtanOfSixteenths = [] {
  std::array<double, 17> table{};
  for (int j = 0; j <= 16; ++j) table[size_t(j)] = std::atan(j / 16.0);
  return table;
}();

}  // namespace detail

/// std::atan2(y, x), within a few units in the last place of it (the tests bound the difference
/// by 1e-15 relative over the whole circle, tiny angles included). Method: reduce to
/// t = min(|x|, |y|) / max(|x|, |y|) in [0, 1], write t's angle as atan(c) + atan(u) with c the
/// nearest sixteenth (the table) and u = (t − c) / (1 + t c), |u| <= 1/32, where the Taylor series
/// to u^11 is exact to ~1e-20; then undo the reduction by octant. Zeros, infinities and NaN go to
/// std::atan2, so its conventions (signed zeros, ±π) are kept.
inline double fastAtan2(double y, double x) {
  const double ay = std::abs(y), ax = std::abs(x);
  const bool steep = ay > ax;
  const double num = steep ? ax : ay, den = steep ? ay : ax;
  if (!(den > 0) || !(den < INFINITY) || !(num == num)) return std::atan2(y, x);
  const double t = num / den;
  const int j = static_cast<int>(t * 16.0 + 0.5);
  const double c = j * (1.0 / 16.0);
  const double u = (t - c) / (1.0 + t * c);
  const double u2 = u * u;
  const double series =
      u * (1.0 +
           u2 * (-1.0 / 3 + u2 * (1.0 / 5 + u2 * (-1.0 / 7 + u2 * (1.0 / 9 + u2 * (-1.0 / 11))))));
  double r = detail::kAtanOfSixteenths[size_t(j)] + series;
  if (steep) r = std::numbers::pi / 2 - r;
  if (x < 0) r = std::numbers::pi - r;
  return std::signbit(y) ? -r : r;
}

}  // namespace gv
