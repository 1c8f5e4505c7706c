// Tests of `verify` (the ray-casting check of the DESIGN.md contract): clean on a real result, and
// each kind of violation caught when the result is broken on purpose, with the double-precision
// confirmation of Embree's hits in place.
#include "visibility/verify.h"

#include <gtest/gtest.h>

#include <map>

#include "bsp/subdivision.h"
#include "generators/office.h"
#include "visibility/propagation.h"

namespace gv {
namespace {

struct Fixture {
  Scene scene = generateOffice();
  VisibilityGraph graph;
  Fixture() {
    BspOptions bsp;
    bsp.minCoverage = kVisibilityMinCoverage;
    graph = computeVisibility(scene, buildSubdivision(scene, bsp));
  }
};

VerifyOptions options() {
  VerifyOptions o;
  o.rays = 100000;
  o.segments = 40000;
  return o;
}

TEST(VerifyChecks, CleanResultPassesAndEveryViolationKindIsCaught) {
  Fixture f;
  const VerifyReport clean = verifyVisibility(f.scene, f.graph, options());
  EXPECT_TRUE(clean.ok()) << (clean.examples.empty() ? "" : clean.examples[0]);
  ASSERT_GT(clean.blockedSegments, 1000u);

  // The pair most often met by rays, removed: missing pairs.
  {
    VisibilityGraph g = f.graph;
    size_t best = 0;  // the VISIBLE pair of the two largest patches is met often
    double bestArea = 0;
    for (size_t i = 0; i < g.interactions.size(); ++i) {
      const Interaction& in = g.interactions[i];
      const double a = f.scene.patches[in.s].polygon.area() * f.scene.patches[in.r].polygon.area();
      if (a > bestArea) bestArea = a, best = i;
    }
    g.interactions.erase(g.interactions.begin() + long(best));
    EXPECT_GT(verifyVisibility(f.scene, g, options()).missingPairs, 0u);
  }
  // Every PARTIAL pair declared VISIBLE: blocked VISIBLE pairs.
  {
    VisibilityGraph g = f.graph;
    for (Interaction& in : g.interactions) in.blockers.clear();
    EXPECT_GT(verifyVisibility(f.scene, g, options()).blockedVisible, 100u);
  }
  // The blocker that occurs in most lists removed from every list (lists stay non-empty):
  // first hits missing from blocker lists.
  {
    VisibilityGraph g = f.graph;
    std::map<uint32_t, size_t> count;
    for (const Interaction& in : g.interactions)
      for (uint32_t b : in.blockers) ++count[b];
    uint32_t top = 0;
    size_t most = 0;
    for (auto [b, c] : count)
      if (c > most) most = c, top = b;
    for (Interaction& in : g.interactions)
      if (in.blockers.size() > 1) std::erase(in.blockers, top);
    EXPECT_GT(verifyVisibility(f.scene, g, options()).missingBlockers, 0u);
  }
}

// A scene of grey polygons given by their vertices (fronts counter-clockwise); `size` sets the
// tolerance the polygons are built with.
struct GreyScene {
  Scene scene;
  uint32_t grey;
  double size;
  explicit GreyScene(double size_)
      : grey(scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}})), size(size_) {}
  void add(const std::vector<Vec3>& v) {
    Patch p;
    p.polygon = *ConvexPolygon::fromVertices(v, Tolerance{size});
    p.material = grey;
    scene.patches.push_back(p);
  }
};

TEST(VerifyChecks, UnlistedPairsWithAFreeSegmentAreMissingAndPairsBehindAWallAreNot) {
  // Two squares facing each other across an empty gap (A below, B above), two more (C, D) with a
  // wall W between them that also hides A from D and B from C. Visible pairs: (A, B), and W's
  // front with B and D.
  GreyScene g(8);
  g.add({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});            // 0 A, facing up
  g.add({{0, 0, 2}, {0, 1, 2}, {1, 1, 2}, {1, 0, 2}});            // 1 B, facing down
  g.add({{3, 0, 0}, {4, 0, 0}, {4, 1, 0}, {3, 1, 0}});            // 2 C, facing up
  g.add({{3, 0, 2}, {3, 1, 2}, {4, 1, 2}, {4, 0, 2}});            // 3 D, facing down
  g.add({{1.4, -1, 1}, {5.5, -1, 1}, {5.5, 2, 1}, {1.4, 2, 1}});  // 4 W, facing up
  VerifyOptions o;
  o.rays = 0;
  o.segments = 0;
  o.tightnessPairs = 0;
  o.unlistedPairs = 2000;
  VisibilityGraph graph;
  graph.interactions = {{0, 1, {}}, {1, 4, {}}, {3, 4, {}}};
  const VerifyReport clean = verifyVisibility(g.scene, graph, o);
  EXPECT_TRUE(clean.ok()) << (clean.examples.empty() ? "" : clean.examples[0]);
  EXPECT_GT(clean.unlistedDrawn, 500u);
  EXPECT_GT(clean.unlistedTried, 200u);  // (2, 3), (0, 3) and (1, 2): facing, all blocked
  EXPECT_EQ(clean.missingUnlisted, 0u);
  // (A, B) left out: found.
  graph.interactions.erase(graph.interactions.begin());
  const VerifyReport missing = verifyVisibility(g.scene, graph, o);
  EXPECT_GT(missing.missingUnlisted, 50u);
  EXPECT_FALSE(missing.ok());
}

TEST(VerifyChecks, HitsOfTheOffsetSegmentThatTheSegmentItselfMissesAreNotViolations) {
  // Two floor quads facing up, the far one tilted up by 1e-7 (so they face each other at a
  // grazing angle), and a fence standing between them whose bottom edge is 1e-6 above the floor:
  // every segment between the quads passes under the fence (at most ~1e-7 high), so the pair is
  // VISIBLE, but verify's segments start and end kVerifyContactDistance (3e-6 here) above the
  // quads and run into the fence. Those hits are not the contract's and must not be reported.
  GreyScene g(4);
  Scene& scene = g.scene;
  auto add = [&](const std::vector<Vec3>& v) { g.add(v); };
  add({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});                    // S, facing up
  add({{2, 0, 0}, {3, 0, 1e-7}, {3, 1, 1e-7}, {2, 1, 0}});              // R, facing up, tilted
  add({{1.5, 0, 1e-6}, {1.5, 1, 1e-6}, {1.5, 1, 0.5}, {1.5, 0, 0.5}});  // the fence, facing -x
  VisibilityGraph graph;
  graph.interactions = {{0, 1, {}}};
  VerifyOptions o;
  o.rays = 0;
  o.segments = 2000;
  const VerifyReport r = verifyVisibility(scene, graph, o);
  EXPECT_GT(r.segments, 1000u);
  EXPECT_GT(r.offsetOnlyHits, 1000u);  // the offset segments did run into the fence
  EXPECT_EQ(r.blockedVisible, 0u);
  EXPECT_TRUE(r.ok()) << (r.examples.empty() ? "" : r.examples[0]);
  // A fence reaching down to the floor blocks the segments themselves: a violation.
  scene.patches[2].polygon = *ConvexPolygon::fromVertices(
      {{1.5, 0, -0.1}, {1.5, 1, -0.1}, {1.5, 1, 0.5}, {1.5, 0, 0.5}}, Tolerance{4});
  const VerifyReport blocked = verifyVisibility(scene, graph, o);
  EXPECT_GT(blocked.blockedVisible, 1000u);
  EXPECT_FALSE(blocked.ok());
}

TEST(VerifyChecks, TheRaysContactDistanceDecidesWhetherAThinWallRightOverAPatchIsSeenThrough) {
  // S (z = 0, facing up), a one-sided sheet W 2e-5 above it facing away from S, and R (z = 1,
  // facing down) over both; nothing listed. The diagonal is about 7.1, so W lies between the
  // default contact distance (1e-6 of it, 7e-6) and the model tolerance (1e-5, 7e-5): by default
  // every ray from S meets W's back (no pair named); with --contact 1e-5 most rays' hits of W
  // are contact, and they name (S, R), which is not listed.
  GreyScene g(8);
  auto add = [&](const std::vector<Vec3>& v) { g.add(v); };
  add({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});                  // S, facing up
  add({{-2, -2, 2e-5}, {3, -2, 2e-5}, {3, 3, 2e-5}, {-2, 3, 2e-5}});  // W, facing up
  add({{-2, -2, 1}, {-2, 3, 1}, {3, 3, 1}, {3, -2, 1}});              // R, facing down
  VisibilityGraph graph;
  graph.interactions = {{1, 2, {}}};  // W's front sees R
  VerifyOptions o;
  o.rays = 20000;
  o.segments = 0;
  o.tightnessPairs = 0;
  const VerifyReport strict = verifyVisibility(g.scene, graph, o);
  EXPECT_EQ(strict.missingPairs, 0u) << (strict.examples.empty() ? "" : strict.examples[0]);
  o.rayContact = 1e-5;
  const VerifyReport loose = verifyVisibility(g.scene, graph, o);
  // S has 1/51 of the area: about 390 of the rays leave S, most of them within 63° of its normal.
  EXPECT_GT(loose.missingPairs, 100u);
}

TEST(VerifyChecks, AListedBlockerMetWithinTheContactDistanceIsTheFirstHit) {
  // S (z = 0, facing up) and R (z = 1, facing down) face each other. B1 lies 5e-7 above the
  // near half of S (a solid's face resting on S, a little out of line), under verify's contact
  // distance (1e-6 of the diagonal, 1.7e-6 here): the offset segments start past it. B2 lies
  // over B1 at 1e-5 (only segments through B1 reach it), and B3 just under R covers R whole.
  // Segments from the near half of S meet B1 first: with B1 and B3 listed that is not a
  // violation, though the offset segment's first hit (B2) is unlisted; without B1 it is one.
  GreyScene g(2);
  Scene& scene = g.scene;
  auto add = [&](const std::vector<Vec3>& v) { g.add(v); };
  add({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}});                  // 0: S, facing up
  add({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}});                  // 1: R, facing down
  add({{0, 0, 5e-7}, {0, 1, 5e-7}, {0.5, 1, 5e-7}, {0.5, 0, 5e-7}});  // 2: B1, facing down
  add({{0, 0, 1e-5}, {0, 1, 1e-5}, {0.5, 1, 1e-5}, {0.5, 0, 1e-5}});  // 3: B2, facing down
  add({{0, 0, 0.9}, {1, 0, 0.9}, {1, 1, 0.9}, {0, 1, 0.9}});          // 4: B3, facing up
  VerifyOptions o;
  o.rays = 0;
  o.segments = 2000;
  VisibilityGraph graph;
  graph.interactions = {{0, 1, {2, 4}}};
  const VerifyReport r = verifyVisibility(scene, graph, o);
  EXPECT_GT(r.blockedSegments, 1000u);
  EXPECT_GT(r.contactFirstHits, 500u);  // about half the segments start under B1
  EXPECT_TRUE(r.ok()) << (r.examples.empty() ? "" : r.examples[0]);
  graph.interactions = {{0, 1, {4}}};
  const VerifyReport without = verifyVisibility(scene, graph, o);
  EXPECT_GT(without.missingBlockers, 500u);
  EXPECT_EQ(without.contactFirstHits, 0u);
  ASSERT_FALSE(without.examples.empty());
  EXPECT_NE(without.examples[0].find("patch 2 is met first"), std::string::npos)
      << without.examples[0];
}

}  // namespace
}  // namespace gv

namespace gv {
namespace {

TEST(VerifyTightness, APairBehindAWholeWallIsExcessAndAnOpenPairIsNot) {
  // S and R face each other across x = 1.5; a wall there (facing S) hides all of R or, cut to a
  // half-height fence, only part of it. Listing the pair is conservative either way; only the
  // first listing is excess.
  GreyScene g(4);
  g.add({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}});              // S at x = 0, facing +x
  g.add({{3, 0, 0}, {3, 0, 1}, {3, 1, 1}, {3, 1, 0}});              // R at x = 3, facing -x
  g.add({{1.5, -1, -1}, {1.5, -1, 2}, {1.5, 2, 2}, {1.5, 2, -1}});  // the wall, facing -x
  VisibilityGraph graph;
  graph.interactions = {{0, 1, {2}}};
  VerifyOptions o;
  o.rays = 0;
  o.segments = 0;
  o.tightnessPairs = 50;
  const VerifyReport hidden = verifyVisibility(g.scene, graph, o);
  EXPECT_EQ(hidden.tightnessPairs, 50u);
  EXPECT_EQ(hidden.excess, 50u);
  g.scene.patches[2].polygon = *ConvexPolygon::fromVertices(
      {{1.5, -1, -1}, {1.5, -1, 0.5}, {1.5, 2, 0.5}, {1.5, 2, -1}}, Tolerance{4});
  const VerifyReport fence = verifyVisibility(g.scene, graph, o);
  EXPECT_EQ(fence.tightnessPairs, 50u);
  EXPECT_EQ(fence.excess, 0u);
}

}  // namespace
}  // namespace gv
