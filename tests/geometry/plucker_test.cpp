// Tests of Plücker lines: the side relation, its symmetries and its agreement with orient3d.
#include "geometry/plucker.h"

#include <gtest/gtest.h>

#include <random>

#include "geometry/predicates.h"

namespace gv {
namespace {

int sign(double x) { return (x > 0) - (x < 0); }

TEST(PluckerLine, CoordinatesOfAxisLines) {
  const PluckerLine l = PluckerLine::through({0, 0, 1}, {1, 0, 1});
  EXPECT_EQ(l.direction, Vec3(1, 0, 0));
  EXPECT_EQ(l.moment, Vec3(0, 1, 0));  // (0,0,1) x (1,0,1)
  EXPECT_EQ(dot(l.direction, l.moment), 0);
}

TEST(PluckerSide, HandCasesAndGeometricMeaning) {
  // a is the x axis, oriented +x. b passes above it (z = 1).
  const Segment a{{0, 0, 0}, {1, 0, 0}};
  const Segment bLeft{{0, 0, 1}, {0, 1, 1}};    // going +y
  const Segment bRight{{0, 1, 1}, {0, 0, 1}};   // going -y
  // Looking along +x with +z up, +y is to the left: b going -y above a turns clockwise.
  EXPECT_GT(side(PluckerLine::of(a), PluckerLine::of(bRight)), 0);
  EXPECT_LT(side(PluckerLine::of(a), PluckerLine::of(bLeft)), 0);
  EXPECT_EQ(sideExact(a, bRight), 1);
  EXPECT_EQ(sideExact(a, bLeft), -1);
  // Side value equals det[q-p, r-p, s-p] (here -1 for bLeft).
  EXPECT_DOUBLE_EQ(side(PluckerLine::of(a), PluckerLine::of(bLeft)), -1.0);
  // Intersecting and parallel lines: zero.
  const Segment meets{{0.5, -1, 0}, {0.5, 1, 0}};
  const Segment parallel{{0, 3, 4}, {2, 3, 4}};
  EXPECT_EQ(side(PluckerLine::of(a), PluckerLine::of(meets)), 0);
  EXPECT_EQ(side(PluckerLine::of(a), PluckerLine::of(parallel)), 0);
  EXPECT_EQ(sideExact(a, meets), 0);
  EXPECT_EQ(sideExact(a, parallel), 0);
  EXPECT_EQ(sideExact(a, a), 0);
}

TEST(PluckerSide, RandomLinesAgreeWithOrient3dAndHaveTheRightSymmetries) {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-10, 10);
  auto point = [&] { return Vec3{u(rng), u(rng), u(rng)}; };
  int positive = 0, negative = 0;
  const int kTrials = 10000;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Segment l{point(), point()}, e{point(), point()};
    const PluckerLine pl = PluckerLine::of(l), pe = PluckerLine::of(e);
    const double s = side(pl, pe);
    const double det = dot(cross(l.b - l.a, e.a - l.a), e.b - l.a);
    // Same quantity up to rounding (magnitudes ~1e3, so 1e-9 relative is generous).
    EXPECT_NEAR(s, det, 1e-9 * (1 + std::abs(det)));
    const int exact = sideExact(l, e);
    EXPECT_EQ(exact, orient3d(l.a, l.b, e.a, e.b));
    if (std::abs(s) > 1e-6) {
      EXPECT_EQ(sign(s), exact);
    }
    // Symmetric: the permuted inner product does not depend on the order of the two lines.
    EXPECT_DOUBLE_EQ(side(pe, pl), s);
    EXPECT_EQ(sideExact(e, l), exact);
    // Reversing either line flips the sign; reversing both keeps it.
    EXPECT_DOUBLE_EQ(side(pl.reversed(), pe), -s);
    EXPECT_EQ(sideExact(Segment{l.b, l.a}, e), -exact);
    EXPECT_EQ(sideExact(l, Segment{e.b, e.a}), -exact);
    EXPECT_EQ(sideExact(Segment{l.b, l.a}, Segment{e.b, e.a}), exact);
    // A line has side 0 with itself (it meets itself), and any valid line has d·m = 0.
    EXPECT_NEAR(side(pl, pl), 0, 1e-9);
    // Sliding the defining points along the line (a positive rescaling of d) keeps the sign.
    const Segment slid{l.a + (l.b - l.a) * 0.25, l.a + (l.b - l.a) * 3.0};
    if (std::abs(s) > 1e-6) {
      EXPECT_EQ(sign(side(PluckerLine::of(slid), pe)), exact);
    }
    positive += exact > 0;
    negative += exact < 0;
  }
  // Non-trivial generator: both signs occur often.
  EXPECT_GT(positive, kTrials / 4);
  EXPECT_GT(negative, kTrials / 4);
}

TEST(PluckerSide, StabbingATriangleMeansOneSignedWithItsEdges) {
  // A triangle in z = 0, counter-clockwise seen from +z; lines going down through it have one
  // sign with all three oriented edges, lines missing it do not.
  const Vec3 t0{0, 0, 0}, t1{1, 0, 0}, t2{0, 1, 0};
  const Segment edges[3] = {{t0, t1}, {t1, t2}, {t2, t0}};
  auto signs = [&](const Segment& l) {
    int s[3];
    for (int i = 0; i < 3; ++i) s[i] = sideExact(l, edges[i]);
    return s[0] == s[1] && s[1] == s[2] ? s[0] : 0;
  };
  const int through = signs(Segment{{0.2, 0.2, 1}, {0.25, 0.2, -1}});
  EXPECT_NE(through, 0);
  EXPECT_EQ(signs(Segment{{0.2, 0.25, -1}, {0.2, 0.2, 1}}), -through);  // upward: other sign
  EXPECT_EQ(signs(Segment{{2, 2, 1}, {2, 2.1, -1}}), 0);                // misses
}

}  // namespace
}  // namespace gv
