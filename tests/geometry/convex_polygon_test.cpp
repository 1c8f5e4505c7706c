// Tests of ConvexPolygon: hand cases and seeded random split/clip properties. Paper §3.
#include "geometry/convex_polygon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace gv {
namespace {

const Tolerance kUnitTol{1.0};

//  (0,1) 3---2 (1,1)      the unit square in z = 0, counter-clockwise seen from +z
//        |   |
//  (0,0) 0---1 (1,0)
ConvexPolygon unitSquare() {
  return *ConvexPolygon::fromVertices({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, kUnitTol);
}

TEST(PolygonBasics, SquareHasNewellNormalAreaCentroid) {
  const ConvexPolygon sq = unitSquare();
  EXPECT_EQ(sq.vertices.size(), 4u);
  EXPECT_NEAR(sq.normal().z, 1.0, 1e-15);
  EXPECT_NEAR(sq.plane.offset, 0.0, 1e-15);
  EXPECT_NEAR(sq.area(), 1.0, 1e-15);
  EXPECT_NEAR(sq.centroid().x, 0.5, 1e-15);
  EXPECT_NEAR(sq.centroid().y, 0.5, 1e-15);
  const Aabb box = sq.bounds();
  EXPECT_EQ(box.lo, Vec3(0, 0, 0));
  EXPECT_EQ(box.hi, Vec3(1, 1, 0));
}

TEST(PolygonBasics, ClockwiseInputFacesDown) {
  const auto p = ConvexPolygon::fromVertices({{0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}}, kUnitTol);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->normal().z, -1.0, 1e-15);
  EXPECT_NEAR(p->plane.offset, -2.0, 1e-15);
  EXPECT_NEAR(p->area(), 1.0, 1e-15);
}

TEST(PolygonBasics, CentroidOfTriangleAndOfUnevenQuad) {
  const auto tri = ConvexPolygon::fromVertices({{0, 0, 0}, {3, 0, 0}, {0, 3, 0}}, kUnitTol);
  ASSERT_TRUE(tri);
  EXPECT_NEAR(tri->centroid().x, 1.0, 1e-15);
  EXPECT_NEAR(tri->centroid().y, 1.0, 1e-15);
  // A trapezoid whose vertex mean differs from its area centroid.
  const auto quad =
      ConvexPolygon::fromVertices({{0, 0, 0}, {4, 0, 0}, {2, 1, 0}, {0, 1, 0}}, kUnitTol);
  ASSERT_TRUE(quad);
  // Rectangle [0,2]x[0,1] (area 2, cx 1) + triangle (2,0),(4,0),(2,1) (area 1, cx 8/3).
  EXPECT_NEAR(quad->area(), 3.0, 1e-14);
  EXPECT_NEAR(quad->centroid().x, (2 * 1.0 + 1 * 8.0 / 3.0) / 3.0, 1e-14);
}

TEST(PolygonBasics, RemovesDuplicatesAndCollinearVertices) {
  const auto p = ConvexPolygon::fromVertices(
      {{0, 0, 0}, {0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.5, 1, 0}, {0, 1, 0},
       {0, 1e-12, 0}, {0, 0, 0}},
      kUnitTol);
  ASSERT_TRUE(p);
  EXPECT_EQ(p->vertices.size(), 4u);
  EXPECT_NEAR(p->area(), 1.0, 1e-12);
}

TEST(PolygonBasics, RejectsDegenerates) {
  EXPECT_FALSE(ConvexPolygon::fromVertices({{0, 0, 0}, {1, 0, 0}}, kUnitTol));
  EXPECT_FALSE(ConvexPolygon::fromVertices({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, kUnitTol));
  EXPECT_FALSE(ConvexPolygon::fromVertices({{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, kUnitTol));
  // A sliver 1e-10 wide: below the 1e-9 length tolerance of a unit scene.
  EXPECT_FALSE(ConvexPolygon::fromVertices({{0, 0, 0}, {1, 0, 0}, {1, 1e-10, 0}, {0, 1e-10, 0}},
                                           kUnitTol));
  // The same sliver is fine in a scene a thousand times smaller.
  EXPECT_TRUE(ConvexPolygon::fromVertices({{0, 0, 0}, {1, 0, 0}, {1, 1e-10, 0}, {0, 1e-10, 0}},
                                          Tolerance{1e-3}));
}

TEST(PolygonBasics, FlippedReversesOrderAndPlane) {
  const ConvexPolygon sq = unitSquare();
  const ConvexPolygon f = sq.flipped();
  EXPECT_NEAR(f.normal().z, -1.0, 0);
  EXPECT_NEAR(f.area(), 1.0, 1e-15);
  EXPECT_EQ(f.vertices.front(), sq.vertices.back());
  const auto refit = ConvexPolygon::fromVertices(f.vertices, kUnitTol);
  ASSERT_TRUE(refit);
  EXPECT_NEAR(dot(refit->normal(), f.normal()), 1.0, 1e-15);
}

TEST(PolygonBasics, ClassifyAndContains) {
  const ConvexPolygon sq = unitSquare();
  EXPECT_EQ(sq.classify(Plane{{1, 0, 0}, -1}, kUnitTol), PlaneSide::Front);
  EXPECT_EQ(sq.classify(Plane{{1, 0, 0}, 0}, kUnitTol), PlaneSide::Front);  // touches: still Front
  EXPECT_EQ(sq.classify(Plane{{1, 0, 0}, 1}, kUnitTol), PlaneSide::Back);
  EXPECT_EQ(sq.classify(Plane{{1, 0, 0}, 0.5}, kUnitTol), PlaneSide::Spanning);
  EXPECT_EQ(sq.classify(Plane{{0, 0, 1}, 1e-12}, kUnitTol), PlaneSide::On);
  EXPECT_TRUE(sq.contains({0.5, 0.5, 0}, kUnitTol));
  EXPECT_TRUE(sq.contains({1, 1, 0}, kUnitTol));
  EXPECT_TRUE(sq.contains({1 + 1e-12, 0.5, 1e-12}, kUnitTol));
  EXPECT_FALSE(sq.contains({1 + 1e-6, 0.5, 0}, kUnitTol));
  EXPECT_FALSE(sq.contains({0.5, 0.5, 1e-6}, kUnitTol));
}

TEST(PolygonSplit, SquareThroughMiddle) {
  const PolygonSplit s = split(unitSquare(), Plane{{1, 0, 0}, 0.25}, kUnitTol);
  ASSERT_TRUE(s.front && s.back);
  EXPECT_FALSE(s.on);
  EXPECT_NEAR(s.front->area(), 0.75, 1e-15);
  EXPECT_NEAR(s.back->area(), 0.25, 1e-15);
  EXPECT_EQ(s.front->vertices.size(), 4u);
  EXPECT_EQ(s.front->plane.normal, unitSquare().plane.normal);  // plane kept, not refitted
}

TEST(PolygonSplit, ThroughVerticesAndTouching) {
  // Diagonal through two vertices: two triangles.
  const PolygonSplit d = split(unitSquare(), Plane::through({0, 0, 0}, {1, -1, 0}), kUnitTol);
  ASSERT_TRUE(d.front && d.back);
  EXPECT_EQ(d.front->vertices.size(), 3u);
  EXPECT_EQ(d.back->vertices.size(), 3u);
  EXPECT_NEAR(d.front->area() + d.back->area(), 1.0, 1e-15);
  // Plane touching one edge: whole polygon on one side.
  const PolygonSplit t = split(unitSquare(), Plane{{1, 0, 0}, 1}, kUnitTol);
  EXPECT_TRUE(t.back && !t.front && !t.on);
  // Coplanar, either orientation.
  EXPECT_TRUE(split(unitSquare(), Plane{{0, 0, -1}, 0}, kUnitTol).on);
  // Cutting off a sliver thinner than the tolerance keeps only the big piece.
  const PolygonSplit sliver = split(unitSquare(), Plane{{1, 0, 0}, 1 - 5e-10}, kUnitTol);
  EXPECT_TRUE(sliver.back);
  EXPECT_FALSE(sliver.front);
}

TEST(PolygonClip, ClipToFront) {
  const auto c = clipToFront(unitSquare(), Plane::through({0.5, 0, 0}, {1, 1, 0}), kUnitTol);
  ASSERT_TRUE(c);
  EXPECT_NEAR(c->area(), 1.0 - 0.125, 1e-15);
  EXPECT_FALSE(clipToFront(unitSquare(), Plane{{1, 0, 0}, 2}, kUnitTol));
  EXPECT_TRUE(clipToFront(unitSquare(), Plane{{0, 0, 1}, 0}, kUnitTol));  // on the plane: kept
}

/// A random convex polygon: points on a random ellipse-ish circle in a random plane.
ConvexPolygon randomPolygon(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::uniform_real_distribution<double> angle(0, 2 * std::numbers::pi);
  std::uniform_int_distribution<int> count(3, 12);
  for (;;) {
    const Vec3 center{u(rng), u(rng), u(rng)};
    const Vec3 n{u(rng), u(rng), u(rng)};
    if (length(n) < 0.1) continue;
    const Vec3 axisU = normalize(cross(n, std::abs(n.x) < 0.5 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
    const Vec3 axisV = normalize(cross(n, axisU));
    std::vector<double> angles(static_cast<std::size_t>(count(rng)));
    for (double& a : angles) a = angle(rng);
    std::sort(angles.begin(), angles.end());
    std::vector<Vec3> vs;
    for (double a : angles) vs.push_back(center + axisU * std::cos(a) + axisV * std::sin(a));
    if (auto p = ConvexPolygon::fromVertices(vs, kUnitTol)) return *p;
  }
}

Plane randomPlane(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  for (;;) {
    const Vec3 n{u(rng), u(rng), u(rng)};
    if (length(n) > 0.1) return Plane::through({u(rng), u(rng), u(rng)}, n);
  }
}

TEST(PolygonSplit, RandomSplitsConserveAreaAndSides) {
  std::mt19937 rng(12345);
  int spanning = 0;
  const int kTrials = 2000;
  for (int trial = 0; trial < kTrials; ++trial) {
    const ConvexPolygon poly = randomPolygon(rng);
    const Plane plane = randomPlane(rng);
    const PolygonSplit s = split(poly, plane, kUnitTol);
    EXPECT_FALSE(s.on);
    const double fa = s.front ? s.front->area() : 0;
    const double ba = s.back ? s.back->area() : 0;
    EXPECT_NEAR(fa + ba, poly.area(), 1e-12);
    if (s.front && s.back) ++spanning;
    const double eps = kUnitTol.length();
    if (s.front) {
      for (const Vec3& p : s.front->vertices) EXPECT_GE(plane.distance(p), -eps);
      EXPECT_EQ(s.front->classify(plane, kUnitTol) == PlaneSide::Back, false);
      const auto clipped = clipToFront(poly, plane, kUnitTol);
      ASSERT_TRUE(clipped);
      EXPECT_NEAR(clipped->area(), fa, 1e-15);
      EXPECT_TRUE(poly.contains(s.front->centroid(), kUnitTol));
    }
    if (s.back) {
      for (const Vec3& p : s.back->vertices) EXPECT_LE(plane.distance(p), eps);
    }
    // Convexity is kept: every vertex of each piece is inside the original polygon.
    for (const auto* piece : {&s.front, &s.back}) {
      if (!*piece) continue;
      for (const Vec3& p : (*piece)->vertices) EXPECT_TRUE(poly.contains(p, kUnitTol));
    }
  }
  // The generator is not trivial: a good share of the planes really cut the polygons.
  EXPECT_GT(spanning, kTrials / 5);
  EXPECT_LT(spanning, kTrials);
}

TEST(PolygonSplit, RandomPointsLandInExactlyOnePiece) {
  std::mt19937 rng(777);
  std::uniform_real_distribution<double> w(0, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const ConvexPolygon poly = randomPolygon(rng);
    const Plane plane = randomPlane(rng);
    const PolygonSplit s = split(poly, plane, kUnitTol);
    for (int k = 0; k < 20; ++k) {
      // A random convex combination of three vertices lies in the polygon.
      const std::size_t n = poly.vertices.size();
      const Vec3 a = poly.vertices[rng() % n], b = poly.vertices[rng() % n],
                 c = poly.vertices[rng() % n];
      double x = w(rng), y = w(rng);
      if (x + y > 1) x = 1 - x, y = 1 - y;
      const Vec3 p = a + (b - a) * x + (c - a) * y;
      if (std::abs(plane.distance(p)) < 1e-6) continue;  // skip points on the cut itself
      const bool inFront = s.front && s.front->contains(p, kUnitTol);
      const bool inBack = s.back && s.back->contains(p, kUnitTol);
      EXPECT_NE(inFront, inBack);
      EXPECT_EQ(inFront, plane.distance(p) > 0);
    }
  }
}

TEST(PolygonBasics, FarFromOriginKeepsPrecision) {
  // A 1 m square 1e6 m from the origin, in a scene of that size.
  const Tolerance tol{2e6};
  const Vec3 o{1e6, -1e6, 5e5};
  const auto p = ConvexPolygon::fromVertices(
      {o, o + Vec3{1, 0, 0}, o + Vec3{1, 1, 0}, o + Vec3{0, 1, 0}}, tol);
  ASSERT_TRUE(p);
  EXPECT_NEAR(p->area(), 1.0, 1e-9);
  EXPECT_NEAR(p->normal().z, 1.0, 1e-12);
  const PolygonSplit s = split(*p, Plane{{1, 0, 0}, o.x + 0.5}, tol);
  ASSERT_TRUE(s.front && s.back);
  EXPECT_NEAR(s.front->area(), 0.5, 1e-9);
}

}  // namespace
}  // namespace gv
