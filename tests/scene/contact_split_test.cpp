// Tests of the contact split: a floor under a box resting on it, a ceiling over a light panel
// hanging 2 cm below it, and the cases that must not be cut. The pieces are checked against the
// floor they came from by point sampling (every point of the floor in exactly one piece) and
// against the footprint by their vertices (each piece wholly inside or wholly outside it).
#include "scene/contact_split.h"

#include <gtest/gtest.h>

#include <random>

#include "generators/scene_builder.h"

namespace gv {
namespace {

constexpr uint32_t kFloor = 0, kBox = 1;

Scene floorScene() {
  Scene scene;
  scene.addMaterial({"floor", {0.5, 0.5, 0.5}, {}});
  scene.addMaterial({"box", {0.5, 0.5, 0.5}, {}});
  return scene;
}

SceneBuilder builder(Scene& scene) {
  return SceneBuilder(scene, Tolerance{20.0});
}

/// Patches of `scene` with material `m`.
std::vector<const Patch*> withMaterial(const Scene& scene, uint32_t m) {
  std::vector<const Patch*> out;
  for (const Patch& p : scene.patches)
    if (p.material == m) out.push_back(&p);
  return out;
}

/// Every point of the rectangle [x0,x1] x [y0,y1] at height z lies in exactly one piece.
void expectTiling(const std::vector<const Patch*>& pieces, double x0, double x1, double y0,
                  double y1, double z) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> ux(x0, x1), uy(y0, y1);
  const Tolerance tol{20.0};
  double area = 0;
  for (const Patch* p : pieces) area += p->polygon.area();
  EXPECT_NEAR(area, (x1 - x0) * (y1 - y0), 1e-9);
  for (int i = 0; i < 2000; ++i) {
    const Vec3 point{ux(rng), uy(rng), z};
    int inside = 0;
    for (const Patch* p : pieces) inside += p->polygon.contains(point, tol) ? 1 : 0;
    EXPECT_EQ(inside, 1) << "point " << point.x << ", " << point.y;
  }
}

/// True when every vertex of the piece is inside [x0,x1] x [y0,y1] (within 1e-12), or every
/// vertex outside-or-on it with the piece's centroid outside.
bool insideOrOutside(const ConvexPolygon& piece, double x0, double x1, double y0, double y1) {
  constexpr double e = 1e-12;
  bool allIn = true;
  for (const Vec3& v : piece.vertices)
    allIn = allIn && v.x >= x0 - e && v.x <= x1 + e && v.y >= y0 - e && v.y <= y1 + e;
  if (allIn) return true;
  // Outside: the convex piece lies beyond one side of the footprint.
  const auto beyond = [&](auto dist) {
    for (const Vec3& v : piece.vertices)
      if (dist(v) < -e) return false;
    return true;
  };
  return beyond([&](const Vec3& v) { return x0 - v.x; }) ||
         beyond([&](const Vec3& v) { return v.x - x1; }) ||
         beyond([&](const Vec3& v) { return y0 - v.y; }) ||
         beyond([&](const Vec3& v) { return v.y - y1; });
}

TEST(ContactSplit, FloorIsCutAlongTheFootprintOfABoxResting) {
  Scene scene = floorScene();
  SceneBuilder b = builder(scene);
  b.addAxisRect(2, true, {0, 0, 0}, {10, 10, 0}, kFloor);
  b.addBox({3, 4, 0}, {5, 7, 1}, kBox);  // its bottom face lies on the floor, facing down
  const ContactSplitReport r = splitPatchesAtContacts(scene);
  EXPECT_EQ(r.patchesSplit, 1u);
  const auto floor = withMaterial(scene, kFloor);
  EXPECT_EQ(floor.size(), r.piecesMade);
  EXPECT_EQ(floor.size(), 5u);  // four around the footprint and the covered one
  expectTiling(floor, 0, 10, 0, 10, 0);
  int covered = 0;
  for (const Patch* p : floor) {
    EXPECT_TRUE(insideOrOutside(p->polygon, 3, 5, 4, 7));
    EXPECT_GT(p->polygon.normal().z, 0.999);  // pieces keep the floor's orientation
    if (std::abs(p->polygon.area() - 6.0) < 1e-9) ++covered;
  }
  EXPECT_EQ(covered, 1);
  // The box's faces are not cut: its bottom lies inside the floor's outline, and its walls are
  // not parallel to anything.
  EXPECT_EQ(withMaterial(scene, kBox).size(), 6u);
  EXPECT_EQ(scene.report.splitAtContacts, 1u);
}

TEST(ContactSplit, CeilingIsCutOverAPanelHangingJustBelowButNotOverAFarOne) {
  for (const double gap : {0.02, 0.5}) {
    Scene scene = floorScene();
    SceneBuilder b = builder(scene);
    b.addAxisRect(2, false, {0, 0, 3}, {10, 10, 3}, kFloor);              // ceiling, facing down
    b.addAxisRect(2, false, {4, 4, 3 - gap}, {5.2, 4.6, 3 - gap}, kBox);  // panel, facing down
    splitPatchesAtContacts(scene);
    const auto ceiling = withMaterial(scene, kFloor);
    // 0.02 <= 0.05 sqrt(0.72) = 0.042: cut; 0.5 is beyond: whole.
    EXPECT_EQ(ceiling.size(), gap < 0.1 ? 5u : 1u) << "gap " << gap;
    expectTiling(ceiling, 0, 10, 0, 10, 3);
    if (ceiling.size() > 1)
      for (const Patch* p : ceiling) EXPECT_TRUE(insideOrOutside(p->polygon, 4, 5.2, 4, 4.6));
  }
}

TEST(ContactSplit, NothingBehindOrTiltedOrAlreadyFollowingTheOutlineIsCut) {
  Scene scene = floorScene();
  SceneBuilder b = builder(scene);
  b.addAxisRect(2, true, {0, 0, 0}, {10, 10, 0}, kFloor);
  b.addAxisRect(2, true, {2, 2, -0.2}, {3, 3, -0.2}, kBox);         // behind the floor
  b.addQuad({6, 6, 0}, {7, 6, 0.2}, {7, 7, 0.2}, {6, 7, 0}, kBox);  // tilted, touching
  EXPECT_EQ(splitPatchesAtContacts(scene).patchesSplit, 0u);
  EXPECT_EQ(scene.patches.size(), 3u);
  // A face back to back with the whole floor covers it exactly: nothing to cut either way.
  b.addAxisRect(2, false, {0, 0, 0}, {10, 10, 0}, kBox);
  EXPECT_EQ(splitPatchesAtContacts(scene).patchesSplit, 0u);
  EXPECT_EQ(scene.patches.size(), 4u);
}

TEST(ContactSplit, StripsUnderNoShadowAreMergedBack) {
  // Two boxes side by side on a floor (wall pieces beside a door): the first box's outline cuts
  // the open floor above both into a piece that ends where the second box's piece begins.
  // Afterwards no two pieces under the same shadows may share a whole edge with a convex union
  // (checked here by brute force), and the tiling is still exact.
  Scene scene = floorScene();
  SceneBuilder b = builder(scene);
  b.addAxisRect(2, true, {0, 0, 0}, {10, 10, 0}, kFloor);
  b.addBox({2, 4, 0}, {4, 5, 1}, kBox);
  b.addBox({4, 4, 0}, {6, 5, 1}, kBox);
  splitPatchesAtContacts(scene);
  const auto floor = withMaterial(scene, kFloor);
  expectTiling(floor, 0, 10, 0, 10, 0);
  const auto in = [](const Vec3& c, double x0, double x1) {
    return x0 < c.x && c.x < x1 && 4 < c.y && c.y < 5;
  };
  const auto coverage = [&](const ConvexPolygon& p) {
    return std::pair<bool, bool>{in(p.centroid(), 2, 4), in(p.centroid(), 4, 6)};
  };
  for (size_t i = 0; i < floor.size(); ++i) {
    EXPECT_TRUE(insideOrOutside(floor[i]->polygon, 2, 4, 4, 5));
    EXPECT_TRUE(insideOrOutside(floor[i]->polygon, 4, 6, 4, 5));
    for (size_t j = i + 1; j < floor.size(); ++j) {
      const ConvexPolygon& x = floor[i]->polygon;
      const ConvexPolygon& y = floor[j]->polygon;
      if (coverage(x) != coverage(y)) continue;
      // A shared whole edge with a convex union: the union's area equals the hull's.
      for (size_t k = 0; k < x.vertices.size(); ++k)
        for (size_t l = 0; l < y.vertices.size(); ++l) {
          const Vec3& a = x.vertices[k];
          const Vec3& bb = x.vertices[(k + 1) % x.vertices.size()];
          if (length(y.vertices[l] - bb) > 1e-9 ||
              length(y.vertices[(l + 1) % y.vertices.size()] - a) > 1e-9)
            continue;
          // The edge a-b is shared: the union is convex iff no vertex of either lies beyond
          // the lines through the other's edges that meet a or b; test it by turning at a, b.
          const auto turn = [](const Vec3& p, const Vec3& q, const Vec3& r) {
            return cross(q - p, r - q).z;
          };
          const Vec3& xPrev = x.vertices[(k + x.vertices.size() - 1) % x.vertices.size()];
          const Vec3& xNext = x.vertices[(k + 2) % x.vertices.size()];
          const Vec3& yNext = y.vertices[(l + 2) % y.vertices.size()];
          const Vec3& yPrev = y.vertices[(l + y.vertices.size() - 1) % y.vertices.size()];
          const bool convexAtA = turn(xPrev, a, yNext) >= -1e-12;
          const bool convexAtB = turn(yPrev, bb, xNext) >= -1e-12;
          EXPECT_FALSE(convexAtA && convexAtB) << "pieces " << i << " and " << j << " could merge";
        }
    }
  }
  // Below, above, left and right of the 4 x 1 footprint, and the two under it.
  EXPECT_EQ(floor.size(), 6u);
}

TEST(ContactSplit, NoSliverIsCutOff) {
  Scene scene = floorScene();
  SceneBuilder b = builder(scene);
  b.addAxisRect(2, true, {0, 0, 0}, {10, 10, 0}, kFloor);
  // A footprint flush with the floor's edge but for 1e-6 (far below kContactMinPieceWidth).
  b.addAxisRect(2, false, {1e-6, 2, 0}, {1, 3, 0}, kBox);
  splitPatchesAtContacts(scene);
  const auto floor = withMaterial(scene, kFloor);
  const double minWidth = kContactMinPieceWidth * scene.tolerance().scale;
  for (const Patch* p : floor) {
    double longest = 0;
    const auto& v = p->polygon.vertices;
    for (size_t i = 0; i < v.size(); ++i)
      longest = std::max(longest, length(v[(i + 1) % v.size()] - v[i]));
    EXPECT_GE(2 * p->polygon.area() / longest, minWidth);
  }
  expectTiling(floor, 0, 10, 0, 10, 0);
  EXPECT_EQ(floor.size(), 4u);  // three around the footprint and the one under it, no strip
}

TEST(ContactSplit, PiecesTakeThePatchsPlaceAndKeepItsMaterialAndFace) {
  Scene scene = floorScene();
  SceneBuilder b = builder(scene);
  b.addAxisRect(2, true, {0, 0, 5}, {1, 1, 5}, kBox);      // patch 0: elsewhere, untouched
  b.addAxisRect(2, true, {0, 0, 0}, {10, 10, 0}, kFloor);  // patch 1: cut
  b.addAxisRect(2, false, {4, 4, 0}, {6, 6, 0}, kBox);     // patch 2: resting on it
  for (uint32_t i = 0; i < scene.patches.size(); ++i) scene.patches[i].sourceFace = 10 + i;
  splitPatchesAtContacts(scene);
  ASSERT_EQ(scene.patches.size(), 7u);
  EXPECT_EQ(scene.patches[0].sourceFace, 10u);
  for (int i = 1; i <= 5; ++i) {
    EXPECT_EQ(scene.patches[i].sourceFace, 11u);
    EXPECT_EQ(scene.patches[i].material, kFloor);
  }
  EXPECT_EQ(scene.patches[6].sourceFace, 12u);
}

}  // namespace
}  // namespace gv
