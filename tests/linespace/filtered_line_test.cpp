// The filtered Plücker side sign against the exact predicate (orient3d): random lines, lines
// through shared points, nearly coplanar lines, parallel axis lines, coordinates far from the
// origin. The filter may only be faster, never different.
#include "linespace/filtered_line.h"

#include <gtest/gtest.h>

#include <random>

namespace gv {
namespace {

TEST(FilteredLineTest, SignAlwaysEqualsTheExactPredicate) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> u(-1, 1);
  int disagreements = 0, zeros = 0, checked = 0;
  for (const double offset : {0.0, 1e3, 1e6}) {
    for (const double size : {1.0, 1e-3}) {
      for (int i = 0; i < 20000; ++i) {
        const Vec3 base{offset, -offset, 0.5 * offset};
        auto point = [&] { return base + Vec3{u(rng), u(rng), u(rng)} * size; };
        Vec3 a = point(), b = point(), c = point(), d = point();
        switch (i % 5) {
          case 1:
            c = a;
            break;  // shared point
          case 2:
            d = a + (b - a) * 0.37 + (c - a) * 0.61;
            break;  // nearly coplanar
          case 3:
            b = {a.x, a.y, a.z + size};
            d = {c.x, c.y, c.z - size};
            break;  // both along z
          case 4:
            d = c + (b - a) * 3.0;
            break;  // nearly parallel
          default:
            break;
        }
        const FilteredLine l = FilteredLine::through(a, b), e = FilteredLine::through(c, d);
        const int s = sideSign(l, e);
        disagreements += s != sideExact({a, b}, {c, d});
        zeros += s == 0;
        ++checked;
      }
    }
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(zeros, checked / 10);  // the degenerate cases really occur
}

}  // namespace
}  // namespace gv
