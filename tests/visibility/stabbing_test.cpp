// Tests of the stabbing-line test (paper §4.1) and its LP: hand cases with known answers,
// degenerate portals, and seeded random portal chains checked against line sampling (whenever a
// sampled line stabs the chain, the answer must not be Blocked).
#include "visibility/stabbing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "support/oracle_math.h"
#include "visibility/linear_program.h"
#include "visibility/portal_clipping.h"

namespace gv {
namespace {

const Tolerance kTol{10.0};

// Axis-aligned rectangle in the plane z = z0, counter-clockwise seen from +z (travel +z), or from
// -z when `down`.
Winding rectZ(double x0, double x1, double y0, double y1, double z0, bool down = false) {
  Winding w{{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}};
  if (down) std::reverse(w.begin(), w.end());
  return w;
}
// Rectangle in the plane x = x0, counter-clockwise seen from +x (travel +x).
Winding rectX(double x0, double y0, double y1, double z0, double z1) {
  return {{x0, y0, z0}, {x0, y1, z0}, {x0, y1, z1}, {x0, y0, z1}};
}
// Rectangle in the plane y = y0, counter-clockwise seen from +y (travel +y).
Winding rectY(double y0, double x0, double x1, double z0, double z1) {
  return {{x0, y0, z0}, {x0, y0, z1}, {x1, y0, z1}, {x1, y0, z0}};
}

StabbingResult run(const std::vector<Winding>& seq, StabbingOptions options = {}) {
  return testPortalSequence(seq, kTol, options);
}

// The three configurations: both parts, clipping only, LP only. Each must be conservative alone.
const StabbingOptions kBoth{}, kClipOnly{true, false, true}, kLpOnly{false, true, true};

TEST(StabbingLp, SolvesSmallProblemsAndDetectsInfeasibility) {
  SeidelLp lp;
  LpVector c{}, lo{}, hi{};
  c[0] = 1, c[1] = 1;
  lo[0] = lo[1] = -10, hi[0] = hi[1] = 10;
  const double s = 1 / std::sqrt(2.0);
  std::vector<LpConstraint> rows(2);
  rows[0].a[0] = s, rows[0].a[1] = s, rows[0].b = s * 3;  // x + y <= 3
  rows[1].a[0] = 1, rows[1].b = 1;                        // x <= 1
  std::optional<LpVector> x = lp.solve(2, rows, c, lo, hi);
  ASSERT_TRUE(x);
  EXPECT_NEAR((*x)[0] + (*x)[1], 3, 1e-12);
  EXPECT_LE((*x)[0], 1 + 1e-12);
  rows.push_back({});
  rows[2].a[0] = -s, rows[2].a[1] = -s, rows[2].b = -s * 4;  // x + y >= 4: infeasible
  EXPECT_FALSE(lp.solve(2, rows, c, lo, hi));
  // Incremental: optimum of the first two rows, extended by the third.
  EXPECT_FALSE(lp.extend(2, rows, 2, *x, c, lo, hi));
}

TEST(StabbingLp, RandomProblemsMatchVertexEnumerationIn3d) {
  // max c·x over random halfspaces containing the origin's neighbourhood, checked against brute
  // force over all vertices (triples of planes incl. the box).
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g;
  SeidelLp lp;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<LpConstraint> rows;
    for (int i = 0; i < 12; ++i) {
      LpConstraint r;
      double n = 0;
      for (int j = 0; j < 3; ++j) r.a[j] = g(rng), n += r.a[j] * r.a[j];
      n = std::sqrt(n);
      for (int j = 0; j < 3; ++j) r.a[j] /= n;
      r.b = 0.2 + std::abs(g(rng));
      rows.push_back(r);
    }
    LpVector c{}, lo{}, hi{};
    for (int j = 0; j < 3; ++j) c[j] = g(rng), lo[j] = -5, hi[j] = 5;
    std::optional<LpVector> x = lp.solve(3, rows, c, lo, hi);
    ASSERT_TRUE(x);
    double best = -INFINITY;
    std::vector<LpConstraint> all = rows;
    for (int j = 0; j < 3; ++j) {
      LpConstraint u, v;
      u.a[j] = 1, u.b = 5, v.a[j] = -1, v.b = 5;
      all.push_back(u), all.push_back(v);
    }
    for (size_t i = 0; i < all.size(); ++i)
      for (size_t j = i + 1; j < all.size(); ++j)
        for (size_t k = j + 1; k < all.size(); ++k) {
          const Vec3 a{all[i].a[0], all[i].a[1], all[i].a[2]};
          const Vec3 b{all[j].a[0], all[j].a[1], all[j].a[2]};
          const Vec3 d{all[k].a[0], all[k].a[1], all[k].a[2]};
          const double det = dot(a, cross(b, d));
          if (std::abs(det) < 1e-9) continue;
          const Vec3 p =
              (cross(b, d) * all[i].b + cross(d, a) * all[j].b + cross(a, b) * all[k].b) / det;
          bool ok = true;
          for (const LpConstraint& r : all)
            ok = ok && r.a[0] * p.x + r.a[1] * p.y + r.a[2] * p.z <= r.b + 1e-9;
          if (ok) best = std::max(best, c[0] * p.x + c[1] * p.y + c[2] * p.z);
        }
    const double got = c[0] * (*x)[0] + c[1] * (*x)[1] + c[2] * (*x)[2];
    EXPECT_NEAR(got, best, 1e-7) << "trial " << trial;
  }
}

TEST(StabbingHand, AlignedSquaresAreStabbedWithAWitness) {
  const std::vector<Winding> seq{rectZ(0, 1, 0, 1, 0), rectZ(0, 1, 0, 1, 1), rectZ(0, 1, 0, 1, 2),
                                 rectZ(0.2, 0.4, 0.6, 0.9, 3)};
  for (const StabbingOptions& o : {kBoth, kLpOnly}) {
    Segment w;
    EXPECT_EQ(testPortalSequence(seq, kTol, o, &w), StabbingResult::Stabbed);
    // The witness goes up (+z) through the last square.
    EXPECT_GT(w.b.z - w.a.z, 0);
  }
  EXPECT_NE(run(seq, kClipOnly), StabbingResult::Blocked);
}

TEST(StabbingHand, ShiftedSquaresAreBlocked) {
  // Through x in [0,1] at z=0 and x in [2,3] at z=1, a line is at x >= 3 at z=2.
  const std::vector<Winding> seq{rectZ(0, 1, 0, 1, 0), rectZ(2, 3, 0, 1, 1), rectZ(0, 1, 0, 1, 2)};
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
    EXPECT_EQ(run(seq, o), StabbingResult::Blocked);
  // Just reachable: the last square starts where the extreme line arrives (touching counts).
  const std::vector<Winding> touch{rectZ(0, 1, 0, 1, 0), rectZ(2, 3, 0, 1, 1),
                                   rectZ(3, 4, 0, 1, 2)};
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
    EXPECT_NE(run(touch, o), StabbingResult::Blocked);
}

TEST(StabbingHand, CorridorAroundACornerIsBlocked) {
  // Unit cells along +x: x=-1, 0, 1 faces (y, z in [0,1]), then the corridor turns to +y: faces
  // y=1 and y=2 over x in [1,2]. No straight line gets round the corner.
  const std::vector<Winding> seq{rectX(-1, 0, 1, 0, 1), rectX(0, 0, 1, 0, 1), rectX(1, 0, 1, 0, 1),
                                 rectY(1, 1, 2, 0, 1), rectY(2, 1, 2, 0, 1)};
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
    EXPECT_EQ(run(seq, o), StabbingResult::Blocked);
  // Without the first face the diagonal through the corner's edge still sees round it.
  const std::vector<Winding> shorter(seq.begin() + 1, seq.end());
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
    EXPECT_NE(run(shorter, o), StabbingResult::Blocked);
}

// Target checks (mayCrossLater), worked by hand: lines through x = 1 and x = 2 (y, z in [0, 1])
// reach x = 5 at y = 4b - 3a for a, b in [0, 1], i.e. y in [-3, 4] (z likewise).
TEST(StabbingHand, MayCrossLaterKeepsWhatLinesReachAndDropsTheRest) {
  PortalSequenceStabber s(kTol);
  auto mayCross = [&s](const Winding& w) {
    Vec3 c{};
    for (const Vec3& v : w) c += v;
    c = c / double(w.size());
    double r = 0;
    for (const Vec3& v : w) r = std::max(r, length(v - c));
    return s.mayCrossLater(w, c, r * (1 + 1e-9));
  };
  const Winding far = rectX(5, 10, 11, 0, 1);
  ASSERT_NE(s.push(rectX(1, 0, 1, 0, 1)), StabbingResult::Blocked);
  EXPECT_TRUE(mayCross(far));  // one portal: nothing to clip by yet
  ASSERT_NE(s.push(rectX(2, 0, 1, 0, 1)), StabbingResult::Blocked);
  EXPECT_TRUE(mayCross(rectX(5, 0, 1, 0, 1)));          // straight ahead
  EXPECT_TRUE(mayCross(rectX(5, 3.5, 4.5, 0, 1)));      // its lower part is reached (y <= 4)
  EXPECT_TRUE(mayCross(rectX(5, 3.9, 4.5, 3.9, 4.5)));  // the corner y = z = 4 is reached
  EXPECT_FALSE(mayCross(rectX(5, 4.1, 5, 0, 1)));       // just beyond y = 4
  EXPECT_FALSE(mayCross(far));
  EXPECT_FALSE(mayCross(rectX(0.5, 0, 1, 0, 1)));  // behind the first portal
  EXPECT_FALSE(mayCross(rectX(1.5, 0, 1, 0, 1)));  // between the two: behind the last portal
  // A side door in the wall y = -3.5 beyond the pass: the lowest line, y = 2 - x (from y = 1 at
  // x = 1 to y = 0 at x = 2), reaches it at x = 5.5.
  EXPECT_TRUE(mayCross(rectY(-3.5, 4.5, 6, 0, 1)));
  EXPECT_FALSE(mayCross(rectY(-3.5, 2.5, 4, 0, 1)));
  // The ball is only a shortcut: a huge one decides nothing wrongly.
  EXPECT_FALSE(s.mayCrossLater(far, Vec3{5, 10.5, 0.5}, 100));
  EXPECT_TRUE(s.mayCrossLater(rectX(5, 0, 1, 0, 1), Vec3{5, 0.5, 0.5}, 100));
}

// LaterPlanes (the masked test of the over-budget answers and hierarchies of balls) keeps
// exactly what mayCrossLater keeps: the hand sequence above, then random portals beyond it,
// each tested alone with a full mask and after its ball's mask was narrowed by a larger ball
// holding it (as in a tree).
TEST(StabbingHand, LaterPlanesKeepWhatMayCrossLaterKeeps) {
  PortalSequenceStabber s(kTol);
  ASSERT_NE(s.push(rectX(1, 0, 1, 0, 1)), StabbingResult::Blocked);
  EXPECT_TRUE(s.laterPlanes().empty());  // one portal: nothing rejects yet
  ASSERT_NE(s.push(rectX(2, 0.2, 0.9, 0.1, 0.8)), StabbingResult::Blocked);
  const LaterPlanes planes{s.laterPlanes()};
  ASSERT_GE(planes.planes.size(), 4u);  // the two portals' planes and separating planes
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-6, 8), size(0.05, 3);
  int kept = 0, rejected = 0;
  for (int i = 0; i < 4000; ++i) {
    const double x = u(rng), y = u(rng), z = u(rng), w = size(rng), h = size(rng);
    const Winding q = (i % 3 == 0)   ? rectX(x, y, y + w, z, z + h)
                      : (i % 3 == 1) ? rectY(y, x, x + w, z, z + h)
                                     : rectZ(x, x + w, y, y + h, z);
    Vec3 c{};
    for (const Vec3& v : q) c += v;
    c = c / double(q.size());
    double r = 0;
    for (const Vec3& v : q) r = std::max(r, length(v - c));
    r *= 1 + 1e-9;
    const bool expected = s.mayCrossLater(q, c, r);
    uint64_t mask = planes.all();
    EXPECT_EQ(planes.keep(c, r, q, mask), expected) << i;
    // Inside a ball twice as large around a nearby centre: its mask first, then the portal's.
    uint64_t outer = planes.all();
    const Vec3 oc = c + Vec3{0.3 * r, -0.2 * r, 0.1 * r};
    if (planes.keep(oc, 2 * r + 0.5 * r, {}, outer)) {
      EXPECT_EQ(planes.keep(c, r, q, outer), expected) << i;
    } else {
      EXPECT_FALSE(expected) << i;  // a ball holding the portal wholly behind one plane
    }
    ++(expected ? kept : rejected);
  }
  EXPECT_GT(kept, 200);  // both answers well represented
  EXPECT_GT(rejected, 200);
}

TEST(StabbingHand, UpThenDownIsBlocked) {
  // Up through the floor of a cell, out through its side, down through the next cell's floor.
  // The first two share an edge, so no plane separates them and clipping alone cannot decide;
  // the LP can (the line would have to cross z = 0 twice).
  const std::vector<Winding> seq{rectZ(0, 1, 0, 1, 0), rectX(1, 0, 1, 0, 1),
                                 rectZ(1, 2, 0, 1, 0, /*down=*/true)};
  for (const StabbingOptions& o : {kBoth, kLpOnly}) EXPECT_EQ(run(seq, o), StabbingResult::Blocked);
  EXPECT_NE(run(seq, kClipOnly), StabbingResult::Stabbed);
}

TEST(StabbingDegenerate, CollinearVerticesRepeatedPortalAndEdgeOn) {
  // A square with a repeated vertex and a collinear mid-edge vertex.
  Winding messy{{0, 0, 1}, {0.5, 0, 1}, {1, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  const std::vector<Winding> seq{rectZ(0, 1, 0, 1, 0), messy, rectZ(0, 1, 0, 1, 2)};
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
    EXPECT_NE(run(seq, o), StabbingResult::Blocked);
  // The same portal twice: lines through it cross it "twice" at one point.
  const std::vector<Winding> twice{rectZ(0, 1, 0, 1, 0), rectZ(0, 1, 0, 1, 0),
                                   rectZ(0, 1, 0, 1, 1)};
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
    EXPECT_NE(run(twice, o), StabbingResult::Blocked);
  // A portal whose plane contains the main direction (seen edge-on from the first): crossing it
  // needs a sideways component, which lines through the two squares have.
  const std::vector<Winding> edgeOn{rectZ(0, 1, 0, 1, 0), rectY(0.5, 0, 1, 1, 2),
                                    rectZ(0, 1, 0.5, 1, 3)};
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
    EXPECT_NE(run(edgeOn, o), StabbingResult::Blocked);
  // A zero-area portal (a segment) in the middle: never a reason to say blocked.
  const Winding segment{{0.5, 0, 1}, {0.5, 1, 1}, {0.5, 0.5, 1}};
  const std::vector<Winding> withSegment{rectZ(0, 1, 0, 1, 0), segment, rectZ(0, 1, 0, 1, 2)};
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
    EXPECT_NE(run(withSegment, o), StabbingResult::Blocked);
  // Coplanar consecutive portals of opposite orientation (in through one, out through the
  // neighbouring one on the same face): no line crosses both.
  const std::vector<Winding> coplanar{rectZ(0, 1, 0, 1, 0), rectZ(1, 2, 0, 1, 0, true)};
  EXPECT_EQ(run(coplanar, kLpOnly), StabbingResult::Blocked);
}

TEST(StabbingDegenerate, DoorSlightlyAjarKeepsItsThinSightlines) {
  // Three parallel portals with tiny gaps, staggered in x: only lines at a slope of ~1e-3 stab
  // them all (x = 0.5 -> 1.5 -> 2.5 while z rises by 1e-3 per step).
  for (double gap : {1e-2, 1e-3}) {
    const std::vector<Winding> seq{rectZ(0, 1, 0, 1, 0), rectZ(1, 2, 0, 1, gap),
                                   rectZ(2, 3, 0, 1, 2 * gap)};
    for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly})
      EXPECT_NE(run(seq, o), StabbingResult::Blocked) << gap;
    // Bent the other way, the same thin chain is blocked.
    const std::vector<Winding> bent{rectZ(0, 1, 0, 1, 0), rectZ(1, 2, 0, 1, gap),
                                    rectZ(-1, 0.5, 0, 1, 2 * gap)};
    EXPECT_EQ(run(bent, kBoth), StabbingResult::Blocked) << gap;
  }
}

// ---- Random chains against sampling ----

// A random convex polygon around `center` in the plane with unit normal n, counter-clockwise
// seen from the side n points to.
Winding randomPortal(std::mt19937_64& rng, const Vec3& center, const Vec3& n, double radius) {
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 t0 = normalize(std::abs(n.x) < 0.9 ? cross(n, {1, 0, 0}) : cross(n, {0, 1, 0}));
  const Vec3 t1 = cross(n, t0);
  const int k = 3 + static_cast<int>(u(rng) * 5);
  std::vector<double> angles(k);
  for (double& a : angles) a = u(rng) * 2 * std::numbers::pi;
  std::sort(angles.begin(), angles.end());
  Winding w;
  for (double a : angles) {
    const double r = radius * (0.6 + 0.4 * u(rng));
    w.push_back(center + t0 * (r * std::cos(a)) + t1 * (r * std::sin(a)));
  }
  return w;
}

// Does the line p + s·d cross every portal, in order, in its direction? (floating point; used only
// to find lines, which are then nowhere near degenerate)
bool lineStabs(const Vec3& p, const Vec3& d, const std::vector<Winding>& seq) {
  double last = -INFINITY;
  for (const Winding& w : seq) {
    const Vec3 n = newellNormal(w);
    const double dn = dot(d, n);
    if (dn <= 0) return false;
    const double s = dot(w[0] - p, n) / dn;
    if (s < last - 1e-12) return false;
    last = s;
    const Vec3 x = p + d * s;
    for (size_t i = 0; i < w.size(); ++i) {
      const Vec3& a = w[i];
      const Vec3& b = w[(i + 1) % w.size()];
      if (dot(cross(b - a, x - a), n) < 0) return false;
    }
  }
  return true;
}

using test::randomPointIn;

/// A chain of `length` random portals climbing along +z, each tilted and shifted a little.
std::vector<Winding> randomChain(std::mt19937_64& rng, int length) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Winding> seq;
  Vec3 center{0, 0, 0};
  for (int i = 0; i < length; ++i) {
    const Vec3 n = normalize(Vec3{0.5 * u(rng), 0.5 * u(rng), 1});
    seq.push_back(randomPortal(rng, center, n, 0.5 + 0.4 * u(rng)));
    center += Vec3{0.6 * u(rng), 0.6 * u(rng), 0.5 + 0.5 * (u(rng) + 1)};
  }
  return seq;
}

TEST(StabbingDegenerate, AShortEdgeLeavingThePortalsPlaneCutsNoLineThroughIt) {
  // q3-oacmpdm3's patch 3130, a 45° bevel (normal (-1, 0, 1) / sqrt 2) whose corner at
  // (42, 36, 16.125) came out of the importer twice, 1e-6 apart along x: the edge between the two
  // copies leaves the bevel's plane at 45°. Below the bevel, two openings of the floors under it,
  // crossed downwards: the first three portals of a real sightline that `vis` missed.
  const Tolerance levelTol{118.028};  // the level's bounding-box diagonal
  const Winding clean{
      {42, 36, 16.125}, {42, 34, 16.125}, {42.125, 34.125, 16.25}, {42.125, 35.875, 16.25}};
  Winding twinned = clean;
  twinned.insert(twinned.begin(), Vec3{42.000001, 36, 16.125});
  twinned[2] = {42.125, 34.125001, 16.25};
  const std::vector<Winding> below{rectZ(30, 44, 20, 34, 16, true),
                                   rectZ(30, 44, 20, 34, 14, true)};
  // The line `verify` found, from the bevel to a wall 24 units away, stabs the clean chain: the
  // chain has sightlines, and the twinned corner changes the bevel by 1e-6 only.
  const Vec3 from{42.032225, 34.040358, 16.157225}, to{18, 29.529463, 6.424838};
  std::vector<Winding> cleanChain{clean};
  cleanChain.insert(cleanChain.end(), below.begin(), below.end());
  ASSERT_TRUE(lineStabs(from, to - from, cleanChain));
  std::vector<Winding> twinnedChain{twinned};
  twinnedChain.insert(twinnedChain.end(), below.begin(), below.end());
  for (const StabbingOptions& o : {kBoth, kClipOnly, kLpOnly}) {
    EXPECT_NE(testPortalSequence(cleanChain, levelTol, o), StabbingResult::Blocked);
    EXPECT_NE(testPortalSequence(twinnedChain, levelTol, o), StabbingResult::Blocked);
  }
}

TEST(StabbingRandom, NeverBlockedWhenSamplingFindsALine) {
  std::mt19937_64 rng(20261124);
  std::uniform_real_distribution<double> u(-1, 1);
  int sampledYes = 0, blocked = 0, stabbed = 0, chains = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int length = 3 + trial % 6;
    const std::vector<Winding> seq = randomChain(rng, length);
    bool found = false;
    for (int s = 0; s < 3000 && !found; ++s) {
      const Vec3 a = randomPointIn(rng, seq.front()), b = randomPointIn(rng, seq.back());
      found = lineStabs(a, b - a, seq);
    }
    ++chains;
    sampledYes += found;
    const StabbingOptions options[] = {kBoth, kClipOnly, kLpOnly};
    for (int k = 0; k < 3; ++k) {
      Segment w;
      const StabbingResult r = testPortalSequence(seq, kTol, options[k], &w);
      if (found) {
        EXPECT_NE(r, StabbingResult::Blocked)
            << "trial " << trial << " length " << length << " options " << k;
      }
      if (k == 0) {
        blocked += r == StabbingResult::Blocked;
        if (r == StabbingResult::Stabbed) {
          ++stabbed;
          // Confirmed exactly inside; floating point agrees away from edges.
          EXPECT_TRUE(lineStabs(w.a, w.b - w.a, seq) || r == StabbingResult::Stabbed);
        }
      }
    }
  }
  // The generator is not trivial: both answers occur often.
  std::printf("random chains: %d, sampling found a line in %d, blocked %d, stabbed %d\n", chains,
              sampledYes, blocked, stabbed);
  EXPECT_GT(sampledYes, chains / 10);
  EXPECT_GT(blocked, chains / 5);
  EXPECT_GT(stabbed, sampledYes / 2);
  RecordProperty("sampled_yes", sampledYes);
  RecordProperty("blocked", blocked);
}

TEST(StabbingIncremental, PushPopMatchesOneShot) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Winding> pool;
  Vec3 center{};
  for (int i = 0; i < 8; ++i) {
    pool.push_back(randomPortal(rng, center, normalize(Vec3{0.3 * u(rng), 0.3 * u(rng), 1}), 0.8));
    center += Vec3{0.3 * u(rng), 0.3 * u(rng), 1};
  }
  PortalSequenceStabber stabber(kTol);
  // Depth-first over prefixes with one portal skipped, compared with fresh one-shot tests.
  for (size_t skip = 1; skip < pool.size(); ++skip) {
    stabber.clear();
    std::vector<Winding> seq;
    for (size_t i = 0; i < pool.size(); ++i) {
      if (i == skip) continue;
      seq.push_back(pool[i]);
      const StabbingResult oneShot = testPortalSequence(seq, kTol);
      const StabbingResult inc = stabber.push(pool[i]);
      EXPECT_EQ(mayBeVisible(inc), mayBeVisible(oneShot)) << skip << " " << i;
      if (!mayBeVisible(inc)) break;
    }
    while (stabber.depth() > 1) stabber.pop();
    EXPECT_EQ(stabber.depth(), 1u);
  }
}

TEST(StabbingIncremental, DeferredLpPrunesWhereTheImmediateLpDoes) {
  // With deferLp a push whose LP would need a solve answers Unresolved and the solve happens on
  // the next push that gets through the clipping; a blocked LP then shows as that push Blocked
  // with isTopBlocked(). So the first Blocked of the deferred run is the immediate run's, or one
  // portal later (or, on the last portal, no answer at all).
  std::mt19937_64 rng(424242);
  std::uniform_real_distribution<double> u(-1, 1);
  StabbingOptions now;
  now.seekWitness = false;
  StabbingOptions later = now;
  later.deferLp = true;
  PortalSequenceStabber a(kTol, now), b(kTol, later);
  int lpBlocked = 0, deferredCaught = 0;
  for (int trial = 0; trial < 600; ++trial) {
    const int length = 3 + trial % 7;
    const std::vector<Winding> seq = randomChain(rng, length);
    a.clear();
    b.clear();
    const uint64_t lpBefore = a.stats().blockedByLp;
    int firstA = length, firstB = length;
    for (int i = 0; i < length && firstA == length; ++i)
      if (a.push(seq[i]) == StabbingResult::Blocked) firstA = i;
    lpBlocked += a.stats().blockedByLp > lpBefore;
    bool topBlocked = false;
    for (int i = 0; i < length && firstB == length; ++i) {
      if (b.push(seq[i], true) == StabbingResult::Blocked) {
        firstB = i;
        topBlocked = b.isTopBlocked();
      }
    }
    if (firstB == firstA) {
      EXPECT_FALSE(topBlocked) << trial;
    } else if (firstA == length - 1 && firstB == length) {
      // the last portal's LP was put off and never needed
    } else {
      // One portal later: the deferred solve proved the level blocked (top blocked), or the
      // next portal was clipped away before the solve was needed. Either way nothing past the
      // immediate run's first Blocked goes through.
      EXPECT_EQ(firstB, firstA + 1) << trial;
      deferredCaught += topBlocked;
    }
  }
  EXPECT_GT(deferredCaught, 5);
  EXPECT_GT(lpBlocked, 20);
  EXPECT_GT(b.stats().lpDeferred, 20u);
  EXPECT_GT(b.stats().deferredBlocked, 5u);
}

}  // namespace
}  // namespace gv
