// Linespace tubes (paper §6) against brute force: seeded random configurations of two convex
// elements and blockers, each verdict checked by sampling segments from S's front to R's front
// with an independent segment/polygon test; child tubes after subdivision; the paper's Fig. 12.
#include "linespace/tube.h"

#include <fmt/core.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>

#include "linespace/linespace_oracle.h"
#include "linespace/segment_blocking.h"
#include "linespace/tube_classification.h"
#include "radiosity/element_tree.h"

namespace gv {
namespace {

using test::frontSegment;
using test::randomPolygon;
using test::randomUnit;
using test::segmentHitsPolygon;

ConvexPolygon square(double x0, double y0, double x1, double y1, double z, bool up) {
  std::vector<Vec3> v{{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  if (!up) std::reverse(v.begin(), v.end());
  return *ConvexPolygon::fromVertices(v, Tolerance{10});
}

/// Sampled facts about the segments from S's front to R's front against a set of blockers.
struct Sampled {
  int segments = 0, blocked = 0;
  bool anyBlocked() const { return blocked > 0; }
  bool anyFree() const { return blocked < segments; }
};

Sampled sample(const ConvexPolygon& s, const ConvexPolygon& r,
               const std::vector<const ConvexPolygon*>& blockers, int count, std::mt19937& rng) {
  Sampled out;
  for (int i = 0; i < count; ++i) {
    const auto seg = frontSegment(s, r, rng);
    if (!seg) break;
    ++out.segments;
    for (const ConvexPolygon* b : blockers)
      if (segmentHitsPolygon(seg->first, seg->second, *b)) {
        ++out.blocked;
        break;
      }
  }
  return out;
}

/// One random configuration: S, R facing each other roughly, blockers scattered around and
/// between them with sizes from tiny to larger than S.
struct Config {
  ConvexPolygon s, r;
  std::vector<ConvexPolygon> blockers;
};

Config randomConfig(std::mt19937& rng, int blockerCount) {
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 cs = randomUnit(rng) * u(rng);
  const Vec3 axis = randomUnit(rng);
  const double dist = 2 + 3 * u(rng);
  const Vec3 cr = cs + axis * dist + randomUnit(rng) * (0.8 * u(rng));
  const Vec3 ns = normalize(normalize(cr - cs) + randomUnit(rng) * (0.6 * u(rng)));
  const Vec3 nr = normalize(normalize(cs - cr) + randomUnit(rng) * (0.6 * u(rng)));
  Config c{randomPolygon(cs, ns, 0.5 + u(rng), rng), randomPolygon(cr, nr, 0.3 + u(rng), rng), {}};
  for (int k = 0; k < blockerCount; ++k) {
    const double t = -0.2 + 1.4 * u(rng);
    const Vec3 a = test::randomPointOn(c.s, rng), b = test::randomPointOn(c.r, rng);
    const Vec3 centre = a + (b - a) * t + randomUnit(rng) * (0.4 * u(rng));
    const Vec3 along = normalize(b - a);
    const Vec3 n =
        u(rng) < 0.6 ? normalize(along + randomUnit(rng) * (0.5 * u(rng))) * (u(rng) < 0.5 ? 1 : -1)
                     : randomUnit(rng);
    const double size = 0.05 * std::pow(60.0, u(rng));  // 0.05 .. 3, log-uniform
    c.blockers.push_back(randomPolygon(centre, n, size, rng));
  }
  return c;
}

struct Tally {
  OutcomeCounts single, paper;
  int impingesExact = 0, puntsExact = 0;
  int tubes[3] = {0, 0, 0};  // by VisibilityStatus
  int partialExact = 0;
  int childTubes[3] = {0, 0, 0};
  int childPartialExact = 0;
};

/// Checks one tube's verdict against sampling; returns whether a PARTIAL verdict was exact.
bool checkVerdict(const TubeVerdict& v, const Sampled& sm, std::span<const uint32_t> parentList) {
  for (const uint32_t b : v.blockers)
    EXPECT_TRUE(std::find(parentList.begin(), parentList.end(), b) != parentList.end())
        << "a kept blocker must come from the list classified";
  switch (v.status) {
    case VisibilityStatus::Invisible:
      EXPECT_FALSE(sm.anyFree()) << sm.blocked << " of " << sm.segments << " blocked";
      EXPECT_NE(v.proof, kNoBlocker);
      return false;
    case VisibilityStatus::Visible:
      EXPECT_FALSE(sm.anyBlocked()) << sm.blocked << " of " << sm.segments << " blocked";
      return false;
    case VisibilityStatus::Partial:
      return sm.anyBlocked() && sm.anyFree();
  }
  return false;
}

TEST(LinespaceTubeTest, RandomConfigurationsAgreeWithSegmentSampling) {
  std::mt19937 rng(20261201);
  const Tolerance tol{20};
  Tally t;
  constexpr int kConfigs = 600, kSamples = 300, kBlockers = 4;
  TubeOptions paperOnly;
  paperOnly.resolvePunts = false;
  paperOnly.splitStraddling = false;
  for (int iter = 0; iter < kConfigs; ++iter) {
    const Config c = randomConfig(rng, 1 + iter % kBlockers);
    const BlockerTable table(c.blockers);
    std::vector<uint32_t> ids(c.blockers.size());
    for (uint32_t k = 0; k < ids.size(); ++k) ids[k] = k;
    const Tube tube(c.s, c.r);

    // Each blocker alone.
    for (uint32_t k = 0; k < ids.size(); ++k) {
      const BlockerVerdict v = classifyBlocker(tube, table[k], tol);
      t.single.add(v);
      const Sampled sm = sample(c.s, c.r, {&c.blockers[k]}, kSamples, rng);
      if (v.outcome == BlockerOutcome::Occludes) {
        EXPECT_FALSE(sm.anyFree()) << "iter " << iter;
      }
      if (v.outcome == BlockerOutcome::Disjoint) {
        EXPECT_FALSE(sm.anyBlocked()) << "iter " << iter;
      }
      // The paper's tests alone (no straddling split, no PUNT resolution) must be sound too.
      const BlockerVerdict paper = classifyBlocker(tube, table[k], tol, paperOnly);
      t.paper.add(paper);
      if (paper.outcome == BlockerOutcome::Occludes) {
        EXPECT_FALSE(sm.anyFree()) << "iter " << iter;
      }
      if (paper.outcome == BlockerOutcome::Disjoint) {
        EXPECT_FALSE(sm.anyBlocked()) << "iter " << iter;
      }
      if (v.outcome == BlockerOutcome::Impinges) t.impingesExact += sm.anyBlocked() && sm.anyFree();
      if (v.outcome == BlockerOutcome::Punt) t.puntsExact += sm.anyBlocked() && sm.anyFree();
    }

    // The whole list (§6.2's multi-blocker logic).
    std::vector<const ConvexPolygon*> all;
    for (const ConvexPolygon& b : c.blockers) all.push_back(&b);
    const TubeVerdict whole = classifyTube(tube, ids, table, tol);
    ++t.tubes[static_cast<int>(whole.status)];
    t.partialExact += checkVerdict(whole, sample(c.s, c.r, all, kSamples, rng), ids);

    // Children: S subdivided, each child against the parent's kept blockers; then one child's
    // children of R (level 2). VISIBLE parents give VISIBLE children without work.
    if (whole.status != VisibilityStatus::Partial) continue;
    for (const ConvexPolygon& cs : splitElementPolygon(c.s)) {
      const TubeVerdict child = classifyTube(Tube(cs, c.r), whole.blockers, table, tol);
      ++t.childTubes[static_cast<int>(child.status)];
      t.childPartialExact +=
          checkVerdict(child, sample(cs, c.r, all, kSamples / 2, rng), whole.blockers);
      if (child.status != VisibilityStatus::Partial) continue;
      for (const ConvexPolygon& cr : splitElementPolygon(c.r)) {
        const TubeVerdict grand = classifyTube(Tube(cs, cr), child.blockers, table, tol);
        ++t.childTubes[static_cast<int>(grand.status)];
        t.childPartialExact +=
            checkVerdict(grand, sample(cs, cr, all, kSamples / 4, rng), child.blockers);
      }
    }
  }
  const OutcomeCounts& o = t.single;
  // The generator must produce every outcome, and PUNTs of both kinds.
  EXPECT_GT(o.occludes, 0u);
  EXPECT_GT(o.impinges, 0u);
  EXPECT_GT(o.disjoint, 0u);
  EXPECT_GT(o.punt, 0u);
  EXPECT_GT(o.puntsRemoved, 0u);
  EXPECT_GT(o.straddling, 0u);
  EXPECT_GT(o.byPlanes, 0u);
  for (int s = 0; s < 3; ++s) EXPECT_GT(t.tubes[s], 0) << s;
  for (int s = 0; s < 3; ++s) EXPECT_GT(t.childTubes[s], 0) << s;
  const auto report = fmt::format(
      "single blockers: occludes {} impinges {} (exact {}) disjoint {} (by planes {}) punt {} "
      "(exact {}); straddling {}; punts tested {} removed by stabbing {}; tubes I/P/V {}/{}/{} "
      "(partial exact {}); children I/P/V {}/{}/{} (partial exact {})",
      o.occludes, o.impinges, t.impingesExact, o.disjoint, o.byPlanes, o.punt, t.puntsExact,
      o.straddling, o.puntsTested, o.puntsRemoved, t.tubes[0], t.tubes[1], t.tubes[2],
      t.partialExact, t.childTubes[0], t.childTubes[1], t.childTubes[2], t.childPartialExact);
  const OutcomeCounts& p = t.paper;
  EXPECT_LE(o.punt, p.punt);
  EXPECT_GE(o.disjoint, p.disjoint);
  const auto paperReport =
      fmt::format("paper's tests alone: occludes {} impinges {} disjoint {} punt {}", p.occludes,
                  p.impinges, p.disjoint, p.punt);
  std::printf("%s\n", paperReport.c_str());
  RecordProperty("counts", report);
  std::printf("%s\n", report.c_str());
}

TEST(LinespaceTubeTest, StabbingRemovesOnlyDisjointPunts) {
  // The same random stream with and without PUNT resolution: every PUNT the stabbing test drops
  // must be disjoint by sampling, and resolution never changes another outcome.
  std::mt19937 rng(7);
  const Tolerance tol{20};
  TubeOptions off;
  off.resolvePunts = false;
  int removed = 0, checked = 0;
  for (int iter = 0; iter < 1500; ++iter) {
    const Config c = randomConfig(rng, 3);
    const BlockerTable table(c.blockers);
    const Tube tube(c.s, c.r);
    for (uint32_t k = 0; k < c.blockers.size(); ++k) {
      const BlockerVerdict a = classifyBlocker(tube, table[k], tol, off);
      const BlockerVerdict b = classifyBlocker(tube, table[k], tol);
      if (a.outcome != BlockerOutcome::Punt) {
        EXPECT_EQ(a.outcome, b.outcome);
        continue;
      }
      ++checked;
      if (b.outcome != BlockerOutcome::Disjoint) continue;
      ++removed;
      EXPECT_FALSE(sample(c.s, c.r, {&c.blockers[k]}, 2000, rng).anyBlocked()) << iter;
    }
  }
  EXPECT_GT(removed, 0);
  std::printf("punts %d, removed by stabbing %d\n", checked, removed);
}

TEST(LinespaceTubeTest, PaperFigure12Evolution) {
  // Fig. 12: a large polygon S (z = 0, facing up) and a small one R (z = 4, facing down) with one
  // blocker B between them (z = 2). The lines from a quadrant Q of S to R cross z = 2 in
  // (Q + R) / 2, so B = [0.8, 2.2]^2 hides R entirely from the quadrant [0, 2]^2.
  const Tolerance tol{10};
  const ConvexPolygon s = square(0, 0, 4, 4, 0, true);
  const ConvexPolygon r = square(1.8, 1.8, 2.2, 2.2, 4, false);
  const std::vector<ConvexPolygon> blockers{square(0.8, 0.8, 2.2, 2.2, 2, true)};
  const BlockerTable table(blockers);
  const std::vector<uint32_t> list{0};
  // i: the parent interaction is PARTIAL.
  const TubeVerdict parent = classifyTube(Tube(s, r), list, table, tol);
  ASSERT_EQ(parent.status, VisibilityStatus::Partial);
  // ii: S into quadrants: one INVISIBLE, three PARTIAL.
  const std::array<ConvexPolygon, 4> quadrants{
      square(0, 0, 2, 2, 0, true), square(2, 0, 4, 2, 0, true), square(0, 2, 2, 4, 0, true),
      square(2, 2, 4, 4, 0, true)};
  std::array<VisibilityStatus, 4> status{};
  for (int q = 0; q < 4; ++q)
    status[q] = classifyTube(Tube(quadrants[q], r), parent.blockers, table, tol).status;
  EXPECT_EQ(status[0], VisibilityStatus::Invisible);
  EXPECT_EQ(status[1], VisibilityStatus::Partial);
  EXPECT_EQ(status[2], VisibilityStatus::Partial);
  EXPECT_EQ(status[3], VisibilityStatus::Partial);
  const TubeVerdict invisible = classifyTube(Tube(quadrants[0], r), parent.blockers, table, tol);
  EXPECT_EQ(invisible.proof, 0u);  // the retained proof blocker
  // iii: the quadrant [2, 4]^2 subdivided: three children VISIBLE, one PARTIAL.
  const TubeVerdict q3 = classifyTube(Tube(quadrants[3], r), parent.blockers, table, tol);
  const std::array<ConvexPolygon, 4> children{
      square(2, 2, 3, 3, 0, true), square(3, 2, 4, 3, 0, true), square(2, 3, 3, 4, 0, true),
      square(3, 3, 4, 4, 0, true)};
  EXPECT_EQ(classifyTube(Tube(children[0], r), q3.blockers, table, tol).status,
            VisibilityStatus::Partial);
  for (int c = 1; c < 4; ++c)
    EXPECT_EQ(classifyTube(Tube(children[c], r), q3.blockers, table, tol).status,
              VisibilityStatus::Visible)
        << c;
}

TEST(LinespaceTubeTest, BlockerBehindTheReceiverNeverOccludes) {
  // Every line from S through R goes on to meet B (larger, beyond R), but no segment S → R does.
  const Tolerance tol{20};
  const ConvexPolygon s = square(0, 0, 1, 1, 0, true);
  const ConvexPolygon r = square(0, 0, 1, 1, 2, false);
  const std::vector<ConvexPolygon> blockers{square(-5, -5, 6, 6, 3, true),
                                            square(-5, -5, 6, 6, -1, false)};
  const BlockerTable table(blockers);
  for (uint32_t k = 0; k < 2; ++k) {
    const BlockerVerdict v = classifyBlocker(Tube(s, r), table[k], tol);
    EXPECT_EQ(v.outcome, BlockerOutcome::Disjoint) << k;
    EXPECT_TRUE(v.byPlanes);
  }
  // The same blocker between them occludes.
  const std::vector<ConvexPolygon> between{square(-5, -5, 6, 6, 1, true)};
  EXPECT_EQ(classifyBlocker(Tube(s, r), BlockerTable(between)[0], tol).outcome,
            BlockerOutcome::Occludes);
}

TEST(LinespaceTubeTest, SmallBlockerInsideTheTubeIsAPuntThatStabbingKeeps) {
  // A tiny blocker in the middle of the tube, off all 16 extremal lines: no extremal line meets
  // it and no edge separates them (PUNT); lines through it exist, so the stabbing test keeps it.
  const Tolerance tol{20};
  const ConvexPolygon s = square(0, 0, 1, 1, 0, true);
  const ConvexPolygon r = square(0, 0, 1, 1, 2, false);
  const std::vector<ConvexPolygon> blockers{square(0.3, 0.62, 0.32, 0.64, 1, true)};
  const BlockerVerdict v = classifyBlocker(Tube(s, r), BlockerTable(blockers)[0], tol);
  EXPECT_TRUE(v.wasPunt);
  EXPECT_EQ(v.outcome, BlockerOutcome::Punt);
  EXPECT_TRUE(v.between);
}

TEST(LinespaceTubeTest, CoplanarPiecesOfAnOccluderOccludeJointly) {
  // The paper's Fig. 17 case: a wall made of several patches. Every random blocker that occludes
  // on its own is cut in two by a random plane through it; neither piece occludes alone, the two
  // together must (geometry/coplanar_cover.h); with a gap cut out between them they must not, and
  // sampling must usually find a free segment through the gap.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  const Tolerance tol{20};
  int joint = 0, gapsKept = 0, gapsSeen = 0;
  for (int iter = 0; iter < 4000 && joint < 60; ++iter) {
    const Config c = randomConfig(rng, 1);
    const Tube tube(c.s, c.r);
    const ConvexPolygon& b = c.blockers[0];
    if (classifyBlocker(tube, BlockerTable(c.blockers)[0], tol).outcome != BlockerOutcome::Occludes)
      continue;
    // A cutting plane through a random interior point, perpendicular to the blocker.
    const Vec3 centre = test::randomPointOn(b, rng);
    const Vec3 cut = normalize(cross(b.normal(), test::randomUnit(rng)));
    const PolygonSplit halves = split(b, Plane::through(centre, cut), tol);
    if (!halves.front || !halves.back) continue;
    const std::vector<ConvexPolygon> pieces{*halves.front, *halves.back};
    const BlockerTable table(pieces);
    const std::vector<uint32_t> ids{0, 1};
    TubeOptions single;
    single.coplanarCover = false;
    if (classifyTube(tube, ids, table, tol, single).status == VisibilityStatus::Invisible) continue;
    const TubeVerdict v = classifyTube(tube, ids, table, tol);
    EXPECT_EQ(v.status, VisibilityStatus::Invisible) << iter;
    EXPECT_EQ(v.counts.coplanarCovers, 1u);
    ++joint;
    // Open a gap: move the cut apart by a visible width.
    const double width = 0.02 + 0.05 * u(rng);
    const PolygonSplit a = split(b, Plane::through(centre + cut * width, cut), tol);
    const PolygonSplit d = split(b, Plane::through(centre - cut * width, cut), tol);
    if (!a.front || !d.back) continue;
    const std::vector<ConvexPolygon> gapped{*a.front, *d.back};
    const TubeVerdict g = classifyTube(tube, ids, BlockerTable(gapped), tol);
    EXPECT_NE(g.status, VisibilityStatus::Invisible) << iter;
    gapsKept += g.status == VisibilityStatus::Partial;
    // (A gap outside the tube's cross-section frees nothing: then PARTIAL is only conservative.)
    gapsSeen += sample(c.s, c.r, {&gapped[0], &gapped[1]}, 4000, rng).anyFree();
  }
  EXPECT_GE(joint, 20);
  EXPECT_GE(gapsKept, 10);
  EXPECT_GE(gapsSeen, 10);
  std::printf("joint occlusions %d, gapped pairs kept PARTIAL %d (free segment sampled in %d)\n",
              joint, gapsKept, gapsSeen);
}

TEST(LinespaceTubeTest, BlockerRestingOnAnElementCoversIt) {
  // A box's bottom face (facing down) lies on the floor: a floor element entirely under it is
  // covered (every segment from it ends on the bottom face); one half under it is not.
  const Tolerance tol{20};
  const std::vector<ConvexPolygon> bottom{square(0, 0, 2, 2, 0, false)};
  const BlockerTable table(bottom);
  const ConvexPolygon light = square(0, 0, 4, 4, 3, false);
  const BlockerVerdict under =
      classifyBlocker(Tube(square(0.5, 0.5, 1.5, 1.5, 0, true), light), table[0], tol);
  EXPECT_EQ(under.outcome, BlockerOutcome::Occludes);
  const BlockerVerdict half =
      classifyBlocker(Tube(square(1, 0.5, 3, 1.5, 0, true), light), table[0], tol);
  EXPECT_EQ(half.outcome, BlockerOutcome::Disjoint);
  EXPECT_EQ(contactCover(square(1, 0.5, 3, 1.5, 0, true), table[0], tol), ContactCover::Part);
  EXPECT_EQ(contactCover(square(3, 3, 4, 4, 0, true), table[0], tol), ContactCover::None);
  // Sample segments starting on the covered part count as blocked, the others do not.
  const std::vector<uint32_t> ids{0};
  EXPECT_TRUE(segmentBlocked({1, 1, 0}, {1, 1, 3}, ids, table, tol.length()));
  EXPECT_FALSE(segmentBlocked({2.5, 1, 0}, {1, 1, 3}, ids, table, tol.length()));
}

}  // namespace
}  // namespace gv
