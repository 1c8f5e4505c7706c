// Face → convex patches: hand cases and seeded random non-convex polygons checked against the
// shoelace area computed independently here.
#include "scene/face_to_patches.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace gv {
namespace {

const Tolerance kTol{10.0};

/// Shoelace area of a polygon in the z = 0 plane (counter-clockwise positive).
double shoelace(const std::vector<Vec3>& v) {
  double a = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3& p = v[i];
    const Vec3& q = v[(i + 1) % v.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

/// Convex (counter-clockwise about +z when flat) by the sign of every corner's turn.
bool isConvexAbout(const ConvexPolygon& p, const Vec3& n) {
  const auto& v = p.vertices;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 turn = cross(v[(i + 1) % v.size()] - v[i], v[(i + 2) % v.size()] - v[(i + 1) % v.size()]);
    if (dot(turn, n) < -1e-12) return false;
  }
  return true;
}

bool isInputVertex(const Vec3& p, const std::vector<Vec3>& face) {
  for (const Vec3& q : face)
    if (p == q) return true;
  return false;
}

TEST(FaceToPatches, ConvexQuadIsOnePatchWithItsVertices) {
  const std::vector<Vec3> quad{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  const FacePatches r = faceToPatches(quad, kTol);
  ASSERT_EQ(r.outcome, FaceOutcome::Convex);
  ASSERT_EQ(r.pieces.size(), 1u);
  EXPECT_EQ(r.pieces[0].vertices, quad);
  EXPECT_NEAR(r.pieces[0].normal().z, 1.0, 1e-12);
  EXPECT_NEAR(r.pieces[0].area(), 2.0, 1e-12);
}

TEST(FaceToPatches, ClockwiseOrderFacesTheOtherWay) {
  const std::vector<Vec3> quad{{0, 0, 0}, {0, 1, 0}, {2, 1, 0}, {2, 0, 0}};
  const FacePatches r = faceToPatches(quad, kTol);
  ASSERT_EQ(r.pieces.size(), 1u);
  EXPECT_NEAR(r.pieces[0].normal().z, -1.0, 1e-12);
}

TEST(FaceToPatches, LShapeIsSplitIntoConvexPiecesOfTheSameArea) {
  //  (0,2)+---+(1,2)
  //       |   |
  //       |   +-------+(2,1)
  //       |           |
  //  (0,0)+-----------+(2,0)
  const std::vector<Vec3> l{{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  const FacePatches r = faceToPatches(l, kTol);
  ASSERT_EQ(r.outcome, FaceOutcome::SplitConvex);
  EXPECT_EQ(r.pieces.size(), 2u);  // one diagonal suffices, and Hertel–Mehlhorn finds it
  double area = 0;
  for (const ConvexPolygon& p : r.pieces) {
    area += p.area();
    EXPECT_TRUE(isConvexAbout(p, {0, 0, 1}));
    EXPECT_GT(p.normal().z, 0.99);
    for (const Vec3& v : p.vertices) EXPECT_TRUE(isInputVertex(v, l));
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
}

TEST(FaceToPatches, RandomStarPolygonsKeepTheirArea) {
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> radius(0.3, 1.0);
  int nonConvex = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 4 + trial % 13;
    std::vector<Vec3> face;
    for (int i = 0; i < n; ++i) {
      const double a = 2 * std::numbers::pi * i / n;
      const double r = radius(rng);
      face.push_back({r * std::cos(a), r * std::sin(a), 0});
    }
    const FacePatches out = faceToPatches(face, kTol);
    nonConvex += out.outcome == FaceOutcome::SplitConvex;
    ASSERT_NE(out.outcome, FaceOutcome::Degenerate);
    double area = 0;
    for (const ConvexPolygon& p : out.pieces) {
      area += p.area();
      EXPECT_TRUE(isConvexAbout(p, {0, 0, 1})) << "trial " << trial;
    }
    EXPECT_NEAR(area, shoelace(face), 1e-9) << "trial " << trial;
  }
  EXPECT_GT(nonConvex, 150);  // the generator must mostly make non-convex faces
}

TEST(FaceToPatches, NonPlanarQuadIsTriangulatedWithoutMovingVertices) {
  const std::vector<Vec3> quad{{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2}, {0, 1, 0}};
  const FacePatches r = faceToPatches(quad, kTol);
  ASSERT_EQ(r.outcome, FaceOutcome::Triangulated);
  ASSERT_EQ(r.pieces.size(), 2u);
  for (const ConvexPolygon& p : r.pieces) {
    EXPECT_EQ(p.vertices.size(), 3u);
    for (const Vec3& v : p.vertices) EXPECT_TRUE(isInputVertex(v, quad));
  }
}

TEST(FaceToPatches, NonPlanarityBelowTheModelToleranceIsAccepted) {
  const std::vector<Vec3> quad{{0, 0, 0}, {1, 0, 0}, {1, 1, 1e-9}, {0, 1, 0}};
  EXPECT_EQ(faceToPatches(quad, kTol).outcome, FaceOutcome::Convex);
}

TEST(FaceToPatches, DegenerateFacesAreDropped) {
  EXPECT_EQ(faceToPatches({{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, kTol).outcome, FaceOutcome::Degenerate);
  EXPECT_EQ(faceToPatches({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}}, kTol).outcome, FaceOutcome::Degenerate);
  EXPECT_EQ(faceToPatches({{1, 1, 1}, {1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, kTol).outcome,
            FaceOutcome::Degenerate);
  EXPECT_EQ(faceToPatches({{0, 0, 0}, {1, 0, NAN}, {0, 1, 0}}, kTol).outcome, FaceOutcome::Degenerate);
}

TEST(FaceToPatches, SliversNarrowerThanTheModelToleranceAreDropped) {
  // Scene size 10: the model tolerance is 1e-4. A triangle 1.5e-5 wide along a 0.7-long edge
  // (a T-junction fix's sliver) is below it; one 1e-3 wide, and a long thin strip 2e-4 wide,
  // are kept.
  EXPECT_EQ(faceToPatches({{0, 0, 0}, {0, 1.5e-5, 0}, {0, 0, 0.7}}, kTol).outcome,
            FaceOutcome::Degenerate);
  EXPECT_EQ(faceToPatches({{0, 0, 0}, {0, 1e-3, 0}, {0, 0, 0.7}}, kTol).outcome,
            FaceOutcome::Convex);
  EXPECT_EQ(faceToPatches({{0, 0, 0}, {0, 2e-4, 0}, {0, 2e-4, 5}, {0, 0, 5}}, kTol).outcome,
            FaceOutcome::Convex);
}

TEST(FaceToPatches, RepeatedVertexInAQuadIsRemoved) {
  const FacePatches r = faceToPatches({{0, 0, 0}, {1, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, kTol);
  ASSERT_EQ(r.outcome, FaceOutcome::Convex);
  EXPECT_EQ(r.pieces[0].vertices.size(), 4u);
}

TEST(FaceToPatches, SelfIntersectingBowtieDoesNotCrashAndKeepsOrientation) {
  const std::vector<Vec3> bowtie{{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  const FacePatches r = faceToPatches(bowtie, kTol);
  for (const ConvexPolygon& p : r.pieces) EXPECT_GT(p.area(), 0);
}

}  // namespace
}  // namespace gv
