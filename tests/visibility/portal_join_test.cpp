// Coplanar portal pieces between the same two cells joined into one opening
// (visibility/portal_join.h): exactly where their union is convex, never across cells, planes or
// directions, and on a real level every piece stays covered by a portal between its cells.
#include "visibility/portal_join.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>

#include "bsp/hidden_faces.h"
#include "input/load_scene.h"
#include "support/shared_levels.h"
#include "visibility/convex_merge.h"

namespace gv {
namespace {

/// A square-ish portal in the plane x = `x` from (y0, z0) to (y1, z1), normal +x (back → front),
/// or -x when `flipped`.
Portal rectPortal(double x, double y0, double z0, double y1, double z1, uint32_t back,
                  uint32_t front, int32_t node, const Tolerance& tol, bool flipped = false) {
  std::vector<Vec3> v{{x, y0, z0}, {x, y1, z0}, {x, y1, z1}, {x, y0, z1}};
  if (flipped) std::reverse(v.begin(), v.end());
  Portal p;
  p.polygon = *ConvexPolygon::fromVertices(v, tol);
  p.back = back;
  p.front = front;
  p.node = node;
  return p;
}

TEST(PortalJoin, JoinsOnlyPiecesWhoseUnionIsConvex) {
  Subdivision sub;
  const Tolerance tol(10);
  sub.tree.tol = tol;
  // Nodes 0 and 1 share merged plane 0 (x = 0); node 2 is plane 1 (x = 5).
  for (uint32_t plane : {0u, 0u, 1u}) {
    BspNode node;
    node.plane = plane;
    sub.tree.nodes.push_back(node);
  }
  sub.cells.resize(3);
  sub.portals = {
      rectPortal(0, 0, 0, 1, 1, 0, 1, 0, tol),        // joins the next: [0, 2] x [0, 1]
      rectPortal(0, 1, 0, 2, 1, 0, 1, 1, tol),        // another node on the same plane
      rectPortal(0, 0, 1, 1, 2, 0, 1, 0, tol),        // on top of the first only: an L, not joined
      rectPortal(0, 3, 0, 4, 1, 0, 1, 0, tol),        // a gap between: the hull would cover it
      rectPortal(0, 2, 0, 3, 1, 1, 0, 0, tol, true),  // the other direction: another opening
      rectPortal(0, 2, 1, 3, 2, 0, 2, 0, tol),        // other cells
      rectPortal(5, 0, 0, 1, 1, 0, 1, 2, tol),        // another plane
  };
  for (uint32_t id = 0; id < sub.portals.size(); ++id) {
    sub.cells[sub.portals[id].back].portals.push_back(id);
    sub.cells[sub.portals[id].front].portals.push_back(id);
  }
  const PortalJoinStats stats = joinCoplanarPortals(sub);
  EXPECT_EQ(stats.portalsBefore, 7u);
  ASSERT_EQ(stats.portalsAfter, 6u);
  ASSERT_EQ(sub.portals.size(), 6u);
  // The joined one takes the first piece's place, normal and cells.
  const Portal& joined = sub.portals[0];
  EXPECT_NEAR(joined.polygon.area(), 2.0, 1e-12);
  EXPECT_NEAR(joined.polygon.normal().x, 1.0, 1e-12);
  EXPECT_TRUE(joined.polygon.contains({0, 1.9, 0.5}, tol));
  EXPECT_EQ(joined.back, 0u);
  EXPECT_EQ(joined.front, 1u);
  for (size_t k = 1; k < sub.portals.size(); ++k)
    EXPECT_NEAR(sub.portals[k].polygon.area(), 1.0, 1e-12) << k;
  // Cell lists rebuilt, sorted, each portal in both of its cells'.
  EXPECT_EQ(sub.cells[0].portals, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(sub.cells[1].portals, (std::vector<uint32_t>{0, 1, 2, 3, 5}));
  EXPECT_EQ(sub.cells[2].portals, (std::vector<uint32_t>{4}));
}

TEST(PortalJoin, ThousandsOfPiecesOfOnePlaneJoinWhereTheyCan) {
  // 2,000 unit squares between the same two cells, given in a shuffled order: a row of 1,000
  // that joins into one 1,000 x 1 strip (whatever order the pieces come in), and 1,000 squares
  // each a unit apart from the next, which must stay apart.
  Subdivision sub;
  const Tolerance tol(4000);
  sub.tree.tol = tol;
  sub.tree.nodes.push_back(BspNode{});
  sub.cells.resize(2);
  std::vector<int> order(2000);
  for (int k = 0; k < 2000; ++k) order[k] = k;
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  for (int k : order) {
    if (k < 1000) {
      sub.portals.push_back(rectPortal(0, k, 0, k + 1, 1, 0, 1, 0, tol));
    } else {
      const double y = 2.0 * (k - 1000);
      sub.portals.push_back(rectPortal(0, y, 5, y + 1, 6, 0, 1, 0, tol));
    }
  }
  for (uint32_t id = 0; id < sub.portals.size(); ++id) {
    sub.cells[0].portals.push_back(id);
    sub.cells[1].portals.push_back(id);
  }
  const PortalJoinStats stats = joinCoplanarPortals(sub);
  EXPECT_EQ(stats.portalsAfter, 1001u);
  double area = 0, largest = 0;
  for (const Portal& p : sub.portals) {
    area += p.polygon.area();
    largest = std::max(largest, p.polygon.area());
  }
  EXPECT_NEAR(area, 2000.0, 1e-6);
  EXPECT_NEAR(largest, 1000.0, 1e-6);
}

TEST(PortalJoin, EveryPieceOfARealLevelStaysInsideAPortalBetweenItsCells) {
  // An arena level's and a sector level's merged cells, before and after the join: every piece's
  // vertices lie in one joined portal with the same back and front (conservative: no opening
  // shrinks), and the join removes pieces (the reason it exists). The sector level's outside is one
  // cell merged from many leaves, whose lists of portals the join renumbers.
  size_t leafPieces = 0;
  for (const char* name : {"q3-oa_ctf2", "doom-fd2-map01"}) {
    const std::string level = test::sharedLevelPath(name);
    if (!std::filesystem::exists(level)) GTEST_SKIP() << level << " not present";
    const Scene scene = removeHiddenFaces(loadScene(level));
    Subdivision merged = mergeConvexCells(scene, buildVisibilitySubdivision(scene, {}));
    const std::vector<Portal> pieces = merged.portals;
    std::vector<std::vector<std::vector<uint32_t>>> partPieces;  // per cell, per leaf: its pieces
    for (const Cell& cell : merged.cells) {
      partPieces.emplace_back();
      for (const CellPart& part : cell.parts) partPieces.back().push_back(part.portals);
    }
    const PortalJoinStats stats = joinCoplanarPortals(merged);
    EXPECT_EQ(stats.portalsBefore, pieces.size());
    EXPECT_LT(stats.portalsAfter, pieces.size() * 9 / 10);
    const Tolerance tol = merged.tree.tol;
    for (const Portal& piece : pieces) {
      bool covered = false;
      for (uint32_t id : merged.cells[piece.back].portals) {
        const Portal& p = merged.portals[id];
        if (p.back != piece.back || p.front != piece.front) continue;
        if (dot(p.polygon.normal(), piece.polygon.normal()) < 1 - 1e-6) continue;
        bool all = true;
        for (const Vec3& v : piece.polygon.vertices) all = all && p.polygon.contains(v, tol);
        if (all) covered = true;
      }
      EXPECT_TRUE(covered) << "a piece between cells " << piece.back << " and " << piece.front;
    }
    // A leaf of a merged cell lists the joined portal its pieces went into.
    for (uint32_t c = 0; c < merged.cells.size(); ++c)
      for (size_t k = 0; k < partPieces[c].size(); ++k)
        for (uint32_t before : partPieces[c][k]) {
          ++leafPieces;
          const Portal& piece = pieces[before];
          const auto& now = merged.cells[c].parts[k].portals;
          EXPECT_TRUE(std::any_of(
              now.begin(), now.end(),
              [&](uint32_t id) {
                const Portal& p = merged.portals[id];
                return p.back == piece.back && p.front == piece.front &&
                       std::all_of(piece.polygon.vertices.begin(), piece.polygon.vertices.end(),
                                   [&](const Vec3& v) { return p.polygon.contains(v, tol); });
              }))
              << "cell " << c << " leaf " << k;
        }
  }
  EXPECT_GT(leafPieces, 0u);
}

}  // namespace
}  // namespace gv
