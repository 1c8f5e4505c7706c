// Tests of the exact orientation predicates against exact rational evaluation. Paper §4.1.
#include "geometry/predicates.h"

#include <CGAL/Exact_rational.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace gv {
namespace {

using Rational = CGAL::Exact_rational;

/// Slow oracle: det[b-a, c-a, d-a] evaluated in exact rationals (doubles convert exactly).
int orient3dRational(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  auto r = [](double x) { return Rational(x); };
  const Rational ux = r(b.x) - r(a.x), uy = r(b.y) - r(a.y), uz = r(b.z) - r(a.z);
  const Rational vx = r(c.x) - r(a.x), vy = r(c.y) - r(a.y), vz = r(c.z) - r(a.z);
  const Rational wx = r(d.x) - r(a.x), wy = r(d.y) - r(a.y), wz = r(d.z) - r(a.z);
  const Rational det =
      ux * (vy * wz - vz * wy) - uy * (vx * wz - vz * wx) + uz * (vx * wy - vy * wx);
  return CGAL::sign(det);
}

/// What a careless implementation computes: the same determinant in doubles.
int orient3dNaive(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double det = dot(cross(b - a, c - a), d - a);
  return (det > 0) - (det < 0);
}

TEST(PredicatesOrient3d, SignConvention) {
  const Vec3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  EXPECT_EQ(orient3d(o, x, y, z), 1);   // z is where cross(x, y) points
  EXPECT_EQ(orient3d(o, y, x, z), -1);  // swapping two points flips the sign
  EXPECT_EQ(orient3d(o, x, y, -z), -1);
  EXPECT_EQ(orient3d(o, x, y, Vec3{3, -7, 0}), 0);
  EXPECT_EQ(orient3d(x, y, z, o), -1);  // odd permutation of (o, x, y, z)
  EXPECT_EQ(orient3d(x, y, o, z), 1);   // even permutation
}

TEST(PredicatesOrient2d, SignConvention) {
  EXPECT_EQ(orient2d(0, 0, 1, 0, 0, 1), 1);
  EXPECT_EQ(orient2d(0, 0, 0, 1, 1, 0), -1);
  EXPECT_EQ(orient2d(0, 0, 1, 1, 3, 3), 0);
  // Projected: the sign is that of the dropped-axis component of the normal.
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  EXPECT_EQ(orient2dProjected(a, b, c, 2), 1);
  const Vec3 p{0, 0, 0}, q{0, 1, 0}, r{0, 0, 1};  // normal +x
  EXPECT_EQ(orient2dProjected(p, q, r, 0), 1);
  const Vec3 s{0, 0, 0}, t{0, 0, 1}, w{1, 0, 0};  // normal +y
  EXPECT_EQ(orient2dProjected(s, t, w, 1), 1);
  EXPECT_EQ(orient2dProjected(s, w, t, 1), -1);
}

TEST(PredicatesOrient3d, ExactOnNearlyCoplanarPoints) {
  // d is computed (with rounding) on the plane of a, b, c and then nudged by a few ulps, so the
  // true sign is decided by bits far below the rounding error of the naive determinant.
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> u(-1, 1);
  int naiveWrong = 0, nonZero = 0;
  const int kTrials = 20000;
  for (int trial = 0; trial < kTrials; ++trial) {
    // Coordinates of mixed sign and size, so that the differences b - a etc. round.
    const Vec3 a{u(rng), u(rng), u(rng)};
    const Vec3 b{u(rng), u(rng), u(rng)};
    const Vec3 c{u(rng), u(rng), u(rng)};
    Vec3 d = a + (b - a) * u(rng) + (c - a) * u(rng);
    const int nudges = static_cast<int>(rng() % 4);
    for (int k = 0; k < nudges; ++k) d.z = std::nextafter(d.z, (trial & 1) ? INFINITY : -INFINITY);
    const int exact = orient3dRational(a, b, c, d);
    ASSERT_EQ(orient3d(a, b, c, d), exact) << "trial " << trial;
    nonZero += exact != 0;
    naiveWrong += orient3dNaive(a, b, c, d) != exact;
  }
  // The test is meaningful only if doubles really fail here (they do, often).
  EXPECT_GT(naiveWrong, kTrials / 20);
  EXPECT_GT(nonZero, kTrials / 2);
}

TEST(PredicatesOrient3d, ExactlyCoplanarGridAndTinyRelativePerturbation) {
  // Points exactly on the plane x + y + z = 1, then a zero coordinate moved by 2^-60 (~1e-18,
  // i.e. ~1e-18 relative to the triangle's size).
  const Vec3 a{1, 0, 0}, b{0, 1, 0}, c{0, 0, 1};
  const Vec3 onPlane{0.75, 0.25, 0};
  EXPECT_EQ(orient3d(a, b, c, onPlane), 0);
  const Vec3 above{0.75, 0.25, 0x1p-60};
  const Vec3 below{0.75, 0.25, -0x1p-60};
  // (b-a)x(c-a) = (1, 1, 1): "above" is on the positive side.
  EXPECT_EQ(orient3d(a, b, c, above), 1);
  EXPECT_EQ(orient3d(a, b, c, below), -1);
  EXPECT_EQ(orient3dRational(a, b, c, above), 1);
  // With huge coordinates the naive determinant loses the perturbation entirely.
  const Vec3 big{1e15, 1e15, 1e15};
  const Vec3 a2 = big, b2 = big + Vec3{1, 0, 0}, c2 = big + Vec3{0, 1, 0};
  const Vec3 d2 = big + Vec3{0.5, 0.5, 0};
  EXPECT_EQ(orient3d(a2, b2, c2, d2), 0);
  const Vec3 d3{d2.x, d2.y, std::nextafter(d2.z, INFINITY)};
  EXPECT_EQ(orient3d(a2, b2, c2, d3), 1);
  EXPECT_EQ(orient3dRational(a2, b2, c2, d3), 1);
}

TEST(PredicatesOrient2d, ExactOnNearlyCollinearPoints) {
  // Classic failure: points along y = x near (0.5, 0.5) on a tiny grid of ulps.
  int naiveWrong = 0;
  for (int i = 0; i < 64; ++i) {
    for (int j = 0; j < 64; ++j) {
      const double px = 0.5 + i * 0x1p-53, py = 0.5 + j * 0x1p-53;
      const double qx = 12, qy = 12, rx = 24, ry = 24;
      auto ra = [](double x) { return Rational(x); };
      const Rational det =
          (ra(qx) - ra(px)) * (ra(ry) - ra(py)) - (ra(qy) - ra(py)) * (ra(rx) - ra(px));
      const int exact = CGAL::sign(det);
      EXPECT_EQ(orient2d(px, py, qx, qy, rx, ry), exact);
      const double naive = (qx - px) * (ry - py) - (qy - py) * (rx - px);
      naiveWrong += ((naive > 0) - (naive < 0)) != exact;
    }
  }
  EXPECT_GT(naiveWrong, 0);
}

// The coordinate-comparison shortcut (axis planes, axis-parallel line pairs) must agree with the
// exact rational sign: quadruples built with shared coordinates, many exactly coplanar, many not.
TEST(PredicatesOrient3d, AxisDegenerateQuadruplesMatchExactRationals) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  int zeros = 0, nonZeros = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Vec3 p[4];
    for (Vec3& q : p) q = {u(rng), u(rng), u(rng)};
    // Copy coordinates between random points so that axis-parallel pairs and planes appear.
    for (int k = 0; k < 7; ++k) {
      const int from = static_cast<int>(rng() % 4), to = static_cast<int>(rng() % 4);
      const int axis = static_cast<int>(rng() % 3);
      p[to][axis] = p[from][axis];
    }
    const int exact = orient3dRational(p[0], p[1], p[2], p[3]);
    ASSERT_EQ(orient3d(p[0], p[1], p[2], p[3]), exact) << "trial " << trial;
    (exact == 0 ? zeros : nonZeros)++;
  }
  EXPECT_GT(zeros, 1000);
  EXPECT_GT(nonZeros, 1000);
}

// The small-integer shortcut (coordinates below 2^15 in magnitude, evaluated in doubles) must
// agree with exact rationals, at the extremes of the range, on coplanar/collinear constructions
// (the zeros it exists for) and next to them; just outside the range the exact path still runs.
TEST(PredicatesSmallIntegers, Orient3dAndOrient2dMatchExactRationals) {
  std::mt19937_64 rng(5);
  const int64_t lim = 32767;
  std::uniform_int_distribution<int64_t> any(-lim, lim), small(-3, 3), pick(0, 2);
  auto coord = [&]() -> double {
    const int64_t k = pick(rng);
    return static_cast<double>(k == 0 ? lim * (any(rng) > 0 ? 1 : -1) - small(rng) * (any(rng) > 0)
                                      : any(rng));
  };
  int zeros = 0, nonZeros = 0, zeros2 = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Vec3 a{coord(), coord(), coord()}, b{coord(), coord(), coord()}, c{coord(), coord(), coord()};
    // d = a + i (b - a) + j (c - a) + a small offset, clamped into the range: coplanar when the
    // offset is zero and nothing was clamped.
    const double i = static_cast<double>(small(rng)), j = static_cast<double>(small(rng));
    Vec3 d = a + (b - a) * i + (c - a) * j;
    if (rng() % 2) d = d + Vec3{double(small(rng)), double(small(rng)), double(small(rng))};
    for (int k = 0; k < 3; ++k) d[k] = std::clamp(d[k], double(-lim), double(lim));
    if (trial % 7 == 0) d = a * 0.5 + b * 0.5;  // a collinear triple, maybe off the integers
    const int exact = orient3dRational(a, b, c, d);
    ASSERT_EQ(orient3d(a, b, c, d), exact) << trial;
    (exact == 0 ? zeros : nonZeros)++;
    // 2D: c2 on the line ab (or next to it) in the xy plane.
    const double cx = std::clamp(a.x + i * (b.x - a.x), double(-lim), double(lim)) +
                      (trial % 2 ? 0.0 : double(small(rng)));
    const double cy = std::clamp(a.y + i * (b.y - a.y), double(-lim), double(lim));
    auto ra = [](double x) { return Rational(x); };
    const Rational det2 =
        (ra(b.x) - ra(a.x)) * (ra(cy) - ra(a.y)) - (ra(b.y) - ra(a.y)) * (ra(cx) - ra(a.x));
    ASSERT_EQ(orient2d(a.x, a.y, b.x, b.y, cx, cy), CGAL::sign(det2)) << trial;
    zeros2 += CGAL::sign(det2) == 0;
  }
  EXPECT_GT(zeros, 2000);
  EXPECT_GT(nonZeros, 2000);
  EXPECT_GT(zeros2, 2000);
}

// The axis-parallel-line shortcut of orient2d: shared x (or y) coordinates, non-integer values,
// some triples collinear, some not, against exact rationals.
TEST(PredicatesOrient2d, AxisParallelTriplesMatchExactRationals) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-100, 100);
  int zeros = 0, nonZeros = 0;
  auto ra = [](double x) { return Rational(x); };
  for (int trial = 0; trial < 20000; ++trial) {
    double p[6];
    for (double& x : p) x = u(rng);
    // Copy coordinates of the same axis between the points.
    for (int k = 0; k < 3; ++k) {
      const int axis = static_cast<int>(rng() % 2);
      p[2 * (rng() % 3) + axis] = p[2 * (rng() % 3) + axis];
    }
    const Rational det = (ra(p[2]) - ra(p[0])) * (ra(p[5]) - ra(p[1])) -
                         (ra(p[3]) - ra(p[1])) * (ra(p[4]) - ra(p[0]));
    const int exact = CGAL::sign(det);
    ASSERT_EQ(orient2d(p[0], p[1], p[2], p[3], p[4], p[5]), exact) << trial;
    (exact == 0 ? zeros : nonZeros)++;
  }
  EXPECT_GT(zeros, 1000);
  EXPECT_GT(nonZeros, 1000);
}

}  // namespace
}  // namespace gv
