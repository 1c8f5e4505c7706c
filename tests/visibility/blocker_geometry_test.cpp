// Tests of the blocker stage's geometry (paper §4.2, §5): PairHull against a brute-force
// separating-axis oracle, PatchGrid against a scan of every box, and facingLines against sampled
// segments and the stabbing kernel.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "visibility/facing_lines.h"
#include "visibility/hull_overlap.h"
#include "visibility/patch_grid.h"
#include "visibility/stabbing.h"

namespace gv {
namespace {

const Tolerance kTol{10.0};

// A random convex polygon (3..6 vertices on an ellipse) around `center` in the plane with unit
// normal n, counter-clockwise seen from the side n points to.
ConvexPolygon randomPolygon(std::mt19937_64& rng, const Vec3& center, const Vec3& n,
                            double radius) {
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 t0 = normalize(std::abs(n.x) < 0.9 ? cross(n, {1, 0, 0}) : cross(n, {0, 1, 0}));
  const Vec3 t1 = cross(n, t0);
  for (;;) {
    const int k = 3 + static_cast<int>(u(rng) * 4);
    std::vector<double> angles(k);
    for (double& a : angles) a = u(rng) * 2 * std::numbers::pi;
    std::sort(angles.begin(), angles.end());
    // On an ellipse, so convex whatever the angles.
    const double ra = radius * (0.5 + 0.5 * u(rng)), rb = radius * (0.5 + 0.5 * u(rng));
    std::vector<Vec3> v;
    for (double a : angles) v.push_back(center + t0 * (ra * std::cos(a)) + t1 * (rb * std::sin(a)));
    if (auto p = ConvexPolygon::fromVertices(v, kTol); p && p->area() > 0.05 * radius * radius)
      return *p;
  }
}

Vec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return normalize(Vec3{g(rng), g(rng), g(rng)});
}

// Axis-aligned normals half of the time: the office's parallel and perpendicular patches, where
// side planes repeat and the de-duplication matters.
Vec3 randomNormal(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> pick(0, 11);
  const int k = pick(rng);
  if (k < 6) {
    Vec3 n{};
    (k % 3 == 0 ? n.x : k % 3 == 1 ? n.y : n.z) = k < 3 ? 1 : -1;
    return n;
  }
  return randomUnit(rng);
}

Vec3 randomPoint(std::mt19937_64& rng, double half) {
  std::uniform_real_distribution<double> u(-half, half);
  return {u(rng), u(rng), u(rng)};
}

// One end of a random pair (S or R) for the hull tests: a polygon of radius 0.6 about a point
// of [-1, 1]^3, facing anywhere.
ConvexPolygon pairEnd(std::mt19937_64& rng) {
  return randomPolygon(rng, randomPoint(rng, 1), randomNormal(rng), 0.6);
}

// Runs f(rng, trial, s, r) on `trials` random pairs (pairEnd) drawn from one generator.
template <class F>
void forRandomPairs(uint64_t seed, int trials, F&& f) {
  std::mt19937_64 rng(seed);
  for (int trial = 0; trial < trials; ++trial) {
    const ConvexPolygon s = pairEnd(rng);
    const ConvexPolygon r = pairEnd(rng);
    f(rng, trial, s, r);
  }
}

Vec3 randomPointIn(std::mt19937_64& rng, const ConvexPolygon& p) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<double> w(p.vertices.size());
  double sum = 0;
  for (double& x : w) x = -std::log(u(rng) + 1e-300), sum += x;
  Vec3 q{};
  for (size_t i = 0; i < w.size(); ++i) q += p.vertices[i] * (w[i] / sum);
  return q;
}

// Separating-axis oracle for conv(hull points) against the polygon b: the largest gap between
// their projections over a complete set of axes (every plane through three hull points, b's
// normal, b's in-plane edge normals, and every hull-pair direction crossed with a b edge).
// Positive: separated by that much; negative: every axis overlaps. `faceGap` counts only the
// separations by a plane of the hull's boundary (b beyond one of its facets) or by b's plane.
struct Oracle {
  double gap = -INFINITY;
  double faceGap = -INFINITY;
};
/// The vertices of s and of r: the points whose convex hull is conv(s ∪ r), for `separation`.
std::vector<Vec3> pointsOf(const ConvexPolygon& s, const ConvexPolygon& r) {
  std::vector<Vec3> points = s.vertices;
  points.insert(points.end(), r.vertices.begin(), r.vertices.end());
  return points;
}

Oracle separation(const std::vector<Vec3>& hull, const ConvexPolygon& b) {
  Oracle o;
  enum Kind { kAny, kOutwardFacet, kOwnPlane };
  auto axis = [&](Vec3 d, Kind kind) {
    const double len = length(d);
    if (len < 1e-9) return;
    d = d * (1 / len);
    double hlo = INFINITY, hhi = -INFINITY, blo = INFINITY, bhi = -INFINITY;
    for (const Vec3& p : hull) hlo = std::min(hlo, dot(d, p)), hhi = std::max(hhi, dot(d, p));
    for (const Vec3& p : b.vertices) blo = std::min(blo, dot(d, p)), bhi = std::max(bhi, dot(d, p));
    const double beyond = blo - hhi, below = hlo - bhi;
    o.gap = std::max({o.gap, beyond, below});
    if (kind == kOutwardFacet) o.faceGap = std::max(o.faceGap, beyond);  // d points out of it
    if (kind == kOwnPlane) o.faceGap = std::max({o.faceGap, beyond, below});
  };
  const size_t h = hull.size();
  for (size_t i = 0; i < h; ++i)
    for (size_t j = i + 1; j < h; ++j)
      for (size_t k = j + 1; k < h; ++k) {
        const Vec3 n = cross(hull[j] - hull[i], hull[k] - hull[i]);
        if (length(n) < 1e-9) continue;
        // A facet plane: every hull point on one side; its outward normal points away from them.
        double lo = INFINITY, hi = -INFINITY;
        for (const Vec3& p : hull) {
          const double d = dot(n, p - hull[i]) / length(n);
          lo = std::min(lo, d), hi = std::max(hi, d);
        }
        if (hi < 1e-9) {
          axis(n, kOutwardFacet);
        } else if (lo > -1e-9) {
          axis(-n, kOutwardFacet);
        } else {
          axis(n, kAny);
        }
      }
  axis(b.plane.normal, kOwnPlane);
  const auto& bv = b.vertices;
  for (size_t e = 0; e < bv.size(); ++e) {
    const Vec3 edge = bv[(e + 1) % bv.size()] - bv[e];
    axis(cross(edge, b.plane.normal), kAny);
    for (size_t i = 0; i < h; ++i)
      for (size_t j = i + 1; j < h; ++j) axis(cross(hull[j] - hull[i], edge), kAny);
  }
  return o;
}

TEST(BlockerHull, ConservativeAndTightOnFacetSeparations) {
  std::mt19937_64 rng(20261201);
  int meets = 0, misses = 0, robustMeets = 0, facetSeparated = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const ConvexPolygon s = pairEnd(rng);
    const ConvexPolygon r = pairEnd(rng);
    const ConvexPolygon b = randomPolygon(rng, randomPoint(rng, 1), randomNormal(rng), 0.5);
    const Oracle o = separation(pointsOf(s, r), b);
    const PairHull ph(s, r, kTol);
    const bool m = ph.meets(b);
    (m ? meets : misses)++;
    EXPECT_EQ(m, ph.boxMeets(b.bounds()) && ph.meetsInBox(b));
    if (o.gap < -1e-6) {  // clearly overlapping: must be reported (conservative)
      ++robustMeets;
      EXPECT_TRUE(m) << "trial " << trial;
    }
    if (o.faceGap > 1e-6) {  // a facet of the hull or b's plane separates: must not be reported
      ++facetSeparated;
      EXPECT_FALSE(m) << "trial " << trial;
    }
  }
  // The generator is not trivial: both answers, both oracle cases, in numbers.
  EXPECT_GT(meets, 300);
  EXPECT_GT(misses, 300);
  EXPECT_GT(robustMeets, 300);
  EXPECT_GT(facetSeparated, 300);
}

TEST(BlockerHull, ParallelBoxFacesKeepOnePlanePerHullFace) {
  // Two aligned unit squares facing each other: the hull is a box, 6 faces (each side face
  // would otherwise come from 4 edge-vertex planes).
  const auto a = ConvexPolygon::fromVertices({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, kTol);
  const auto b = ConvexPolygon::fromVertices({{0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}}, kTol);
  const PairHull h(*a, *b, kTol);
  EXPECT_EQ(h.planeCount(), 6u);
  const auto inside =
      ConvexPolygon::fromVertices({{0.2, 0.2, 0.5}, {0.8, 0.2, 0.5}, {0.8, 0.8, 0.5}}, kTol);
  const auto outside =
      ConvexPolygon::fromVertices({{1.2, 0.2, 0.5}, {1.8, 0.2, 0.5}, {1.8, 0.8, 0.5}}, kTol);
  const auto touching =  // on the hull's side face x = 1: blocks nothing of positive measure
      ConvexPolygon::fromVertices({{1, 0.2, 0.2}, {1, 0.8, 0.2}, {1, 0.8, 0.8}}, kTol);
  EXPECT_TRUE(h.meets(*inside));
  EXPECT_FALSE(h.meets(*outside));
  EXPECT_FALSE(h.meets(*touching));
}

std::vector<Aabb> randomBoxes(std::mt19937_64& rng, size_t n, bool flat) {
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Aabb> boxes;
  for (size_t i = 0; i < n; ++i) {
    Aabb b;
    if (i % 97 == 5) {  // empty: meets nothing
      boxes.push_back(b);
      continue;
    }
    Vec3 lo{u(rng) * 100, u(rng) * 100, flat ? 3.0 : u(rng) * 100};
    const double size = i % 53 == 0 ? 150 : (i % 7 == 0 ? 20 : 2) * u(rng);  // a few huge
    Vec3 hi = lo + Vec3{size * u(rng), size * u(rng), flat ? 0.0 : size * u(rng)};
    b.add(lo);
    b.add(hi);
    boxes.push_back(b);
  }
  return boxes;
}

TEST(BlockerGrid, GatherReturnsExactlyTheMeetingBoxesOnce) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  size_t returned = 0, queries = 0;
  // Cells per patch: the default (sparse fine levels scanned row by row, dense coarse ones with
  // per-cell bounds), and few cells, so that every level skips or takes whole cells.
  for (const double cellsPerPatch : {2.0, 0.02})
    for (const bool flat : {false, true}) {
      const std::vector<Aabb> boxes = randomBoxes(rng, 3000, flat);
      const PatchGrid grid(boxes, cellsPerPatch);
      EXPECT_GT(grid.levelCount(), 2u);
      for (int q = 0; q < 400; ++q) {
        Aabb box;
        const Vec3 lo{u(rng) * 120 - 10, u(rng) * 120 - 10, flat ? 3.0 : u(rng) * 120 - 10};
        const double size = q % 10 == 0 ? 80 : 10 * u(rng);
        box.add(lo);
        box.add(lo + Vec3{size * u(rng), size * u(rng), flat ? 0.0 : size * u(rng)});
        const double e = q % 3 == 0 ? 0.0 : 0.01;
        std::vector<uint32_t> got;
        grid.gather(box, e, got);
        std::sort(got.begin(), got.end());
        EXPECT_TRUE(std::adjacent_find(got.begin(), got.end()) == got.end()) << "repeats";
        std::vector<uint32_t> want;
        for (uint32_t p = 0; p < boxes.size(); ++p) {
          const Aabb& b = boxes[p];
          if (box.lo.x <= b.hi.x + e && b.lo.x <= box.hi.x + e && box.lo.y <= b.hi.y + e &&
              b.lo.y <= box.hi.y + e && box.lo.z <= b.hi.z + e && b.lo.z <= box.hi.z + e)
            want.push_back(p);
        }
        EXPECT_EQ(got, want) << "query " << q << (flat ? " (flat scene)" : "") << " cells/patch "
                             << cellsPerPatch;
        std::vector<uint32_t> into(grid.patchCount());
        into.resize(grid.gatherInto(box, e, into.data()));
        std::sort(into.begin(), into.end());
        EXPECT_EQ(into, want);
        returned += got.size();
        ++queries;
      }
    }
  EXPECT_GT(returned, queries * 5);  // queries are not trivially empty
}

TEST(BlockerHull, ASeparatedBoxHoldsNoMeetingPolygon) {
  // separatesBox(box) promises that no polygon inside the box meets the hull: checked on
  // random polygons placed inside random boxes, with the brute-force oracle for the meeting ones.
  std::uniform_real_distribution<double> u(0, 1);
  int separatedBoxes = 0, keptBoxes = 0;
  forRandomPairs(
      7, 2000,
      [&](std::mt19937_64& rng, int trial, const ConvexPolygon& s, const ConvexPolygon& r) {
        const PairHull hull(s, r, kTol);
        const ConvexPolygon b = randomPolygon(rng, randomPoint(rng, 1.5), randomNormal(rng), 0.3);
        Aabb box = b.bounds();  // b's box, grown a little at random: b lies inside it
        box.add(box.lo - Vec3{u(rng), u(rng), u(rng)} * 0.2);
        box.add(box.hi + Vec3{u(rng), u(rng), u(rng)} * 0.2);
        if (!hull.separatesBox(box)) {
          ++keptBoxes;
          return;
        }
        ++separatedBoxes;
        EXPECT_FALSE(hull.meets(b)) << "trial " << trial;
        EXPECT_GT(separation(pointsOf(s, r), b).gap, 0)
            << "trial " << trial << ": b meets the hull";
      });
  EXPECT_GT(separatedBoxes, 200);  // both answers occur (in numbers)
  EXPECT_GT(keptBoxes, 100);
}

TEST(BlockerHull, AShaftSeparatesOnlyWhatEveryPairHullMisses) {
  // The shaft form conv(S ∪ box) drops a patch box for a whole group of receivers inside the
  // box: checked with the brute-force oracle against each receiver's own hull conv(S ∪ R), on
  // random polygons and on polygons placed across a segment from S to one of the receivers
  // (those meet that hull, and the shaft must keep them).
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int separated = 0, kept = 0, across = 0;
  for (int trial = 0; trial < 1500; ++trial) {
    const ConvexPolygon s = randomPolygon(rng, randomPoint(rng, 1), randomNormal(rng), 0.5);
    const Vec3 groupCenter = randomPoint(rng, 1.5);
    std::vector<ConvexPolygon> receivers;
    Aabb groupBox;
    for (int k = 0; k < 4; ++k) {
      receivers.push_back(
          randomPolygon(rng, groupCenter + randomPoint(rng, 0.3), randomNormal(rng), 0.2));
      groupBox.add(receivers.back().bounds());
    }
    const PairHull shaft(s, groupBox, kTol);
    ConvexPolygon b = randomPolygon(rng, randomPoint(rng, 2), randomNormal(rng), 0.2);
    if (trial % 3 == 0) {  // across a segment from S to a receiver
      const ConvexPolygon& r = receivers[trial % receivers.size()];
      const double t = 0.1 + 0.8 * u(rng);
      const Vec3 on = randomPointIn(rng, s) * (1 - t) + randomPointIn(rng, r) * t;
      b = randomPolygon(rng, on, randomNormal(rng), 0.05);
      ++across;
    }
    if (!shaft.separatesBox(b.bounds())) {
      ++kept;
      continue;
    }
    ++separated;
    for (const ConvexPolygon& r : receivers)
      EXPECT_GT(separation(pointsOf(s, r), b).gap, 0)
          << "trial " << trial << ": b meets conv(S, R)";
  }
  EXPECT_GT(across, 400);
  EXPECT_GT(separated, 300);  // both answers occur (in numbers)
  EXPECT_GT(kept, 300);
}

TEST(BlockerHull, KeepUnseparatedAnswersAsSeparatesBoxDoes) {
  // The plane-by-plane filter over many boxes (the blocker stage's group candidates) must keep
  // exactly the boxes, in their order, that separatesBox keeps, for a pair hull and for a shaft;
  // every fourth box has a corner at a vertex of R (on the hull), every fifth is a point.
  std::uniform_real_distribution<double> u(0, 1);
  size_t kept = 0, dropped = 0;
  forRandomPairs(
      13, 300,
      [&](std::mt19937_64& rng, int trial, const ConvexPolygon& s, const ConvexPolygon& r) {
        const PairHull pair(s, r, kTol);
        const PairHull shaft(s, r.bounds(), kTol);
        std::vector<Aabb> boxes;
        for (int k = 0; k < 60; ++k) {
          Aabb b;
          const Vec3 c = k % 4 == 0 ? r.vertices[k % r.vertices.size()] : randomPoint(rng, 1.5);
          b.add(c);
          b.add(c + Vec3{u(rng), u(rng), u(rng)} * (k % 5 == 0 ? 0.0 : 0.3));
          boxes.push_back(b);
        }
        for (const PairHull* hull : {&pair, &shaft}) {
          std::vector<uint32_t> ids, want;
          for (uint32_t k = 0; k < boxes.size(); k += 1 + (k % 3 == 0)) {  // a subset, in order
            ids.push_back(k);
            if (!hull->separatesBox(boxes[k])) want.push_back(k);
          }
          const size_t n = ids.size();
          ids.resize(hull->keepUnseparated(ids.data(), n, boxes));
          EXPECT_EQ(ids, want) << "trial " << trial << (hull == &shaft ? " (shaft)" : " (pair)");
          kept += want.size();
          dropped += n - want.size();
        }
      });
  EXPECT_GT(kept, 1000);  // both answers occur (in numbers)
  EXPECT_GT(dropped, 1000);
}

TEST(BlockerGrid, AHullLeavesOutOnlyPatchesThatCannotMeetIt) {
  // gatherInto with a hull may drop the patches of cells the hull separates: it must keep every
  // patch whose polygon meets the hull (PairHull::meets) and drop some on these dense grids.
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<ConvexPolygon> polygons;
  std::vector<Aabb> boxes;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 c{u(rng) * 10, u(rng) * 10, u(rng) * 10};
    polygons.push_back(randomPolygon(rng, c, randomNormal(rng), 0.1 + 0.4 * u(rng)));
    boxes.push_back(polygons.back().bounds());
  }
  const PatchGrid grid(boxes, 0.02);  // few cells: every level keeps per-cell bounds
  size_t dropped = 0;
  for (int q = 0; q < 200; ++q) {
    const ConvexPolygon s =
        randomPolygon(rng, Vec3{u(rng), u(rng), u(rng)} * 10, randomNormal(rng), 1.5);
    const ConvexPolygon r =
        randomPolygon(rng, Vec3{u(rng), u(rng), u(rng)} * 10, randomNormal(rng), 1.5);
    const PairHull hull(s, r, kTol);
    Aabb box = s.bounds();
    box.add(r.bounds());
    std::vector<uint32_t> all(grid.patchCount()), kept(grid.patchCount());
    all.resize(grid.gatherInto(box, kTol.length(), all.data()));
    kept.resize(grid.gatherInto(box, kTol.length(), kept.data(), &hull));
    std::sort(all.begin(), all.end());
    std::sort(kept.begin(), kept.end());
    EXPECT_TRUE(std::includes(all.begin(), all.end(), kept.begin(), kept.end()));
    dropped += all.size() - kept.size();
    for (uint32_t p : all) {
      if (!hull.meets(polygons[p], boxes[p])) continue;
      EXPECT_TRUE(std::binary_search(kept.begin(), kept.end(), p))
          << "query " << q << " lost " << p;
    }
  }
  EXPECT_GT(dropped, 100u);
}

TEST(BlockerGrid, DegenerateInputs) {
  std::vector<uint32_t> got;
  PatchGrid none({});
  none.gather(Aabb{{0, 0, 0}, {1, 1, 1}}, 0, got);
  EXPECT_TRUE(got.empty());
  // Every box the same point: one flat cell on every axis.
  const std::vector<Aabb> same(5, Aabb{{1, 2, 3}, {1, 2, 3}});
  PatchGrid point(same);
  point.gather(Aabb{{1, 2, 3}, {1, 2, 3}}, 0, got);
  EXPECT_EQ(got.size(), 5u);
  got.clear();
  point.gather(Aabb{{2, 2, 3}, {3, 3, 3}}, 0, got);
  EXPECT_TRUE(got.empty());
}

TEST(BlockerFacingLines, AgreesWithSampledSegmentsAndTheKernel) {
  std::mt19937_64 rng(5);
  const double eps = kTol.length();
  int front = 0, back = 0, neither = 0, kernelStabbed = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const ConvexPolygon s = randomPolygon(rng, randomPoint(rng, 1), randomNormal(rng), 0.7);
    const ConvexPolygon t = randomPolygon(rng, randomPoint(rng, 1), randomNormal(rng), 0.7);
    const FacingLines f = facingLines(s, t, eps);
    front += f.throughFront;
    back += f.throughBack;
    neither += !f.throughFront && !f.throughBack;
    // Sampled segments p -> q with the required signs prove a line exists.
    bool sampledFront = false, sampledBack = false;
    for (int k = 0; k < 200; ++k) {
      const Vec3 p = randomPointIn(rng, s), q = randomPointIn(rng, t);
      const Vec3 d = q - p;
      if (dot(d, s.plane.normal) <= 1e-6) continue;
      const double dt = dot(d, t.plane.normal);
      sampledFront = sampledFront || dt < -1e-6;
      sampledBack = sampledBack || dt > 1e-6;
    }
    if (sampledFront) {
      EXPECT_TRUE(f.throughFront) << "trial " << trial;
    }
    if (sampledBack) {
      EXPECT_TRUE(f.throughBack) << "trial " << trial;
    }
    // The kernel's confirmed lines (Stabbed carries an exact witness) must be found too; its
    // "Blocked" is exact, so the rule may not find a line it excludes (beyond grazing ones).
    std::vector<Vec3> reversed(t.vertices.rbegin(), t.vertices.rend());
    const StabbingResult kf = testPortalSequence(std::vector<Winding>{s.vertices, reversed}, kTol);
    const StabbingResult kb =
        testPortalSequence(std::vector<Winding>{s.vertices, t.vertices}, kTol);
    kernelStabbed += (kf == StabbingResult::Stabbed) + (kb == StabbingResult::Stabbed);
    if (kf == StabbingResult::Stabbed) {
      EXPECT_TRUE(f.throughFront) << "trial " << trial;
    }
    if (kb == StabbingResult::Stabbed) {
      EXPECT_TRUE(f.throughBack) << "trial " << trial;
    }
  }
  EXPECT_GT(front, 300);
  EXPECT_GT(back, 300);
  EXPECT_GT(neither, 300);
  EXPECT_GT(kernelStabbed, 300);
}

TEST(BlockerFacingLines, AdjacentFacesOfABoxSeeNothingOfEachOther) {
  // Two outward faces of one box meeting at an edge: every line between them grazes a plane.
  const auto bottom =
      ConvexPolygon::fromVertices({{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, kTol);
  const auto side = ConvexPolygon::fromVertices({{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, kTol);
  ASSERT_TRUE(bottom && side);
  ASSERT_LT(bottom->plane.normal.z, 0);
  ASSERT_LT(side->plane.normal.x, 0);
  const FacingLines f = facingLines(*bottom, *side, kTol.length());
  EXPECT_FALSE(f.throughFront);
  EXPECT_FALSE(f.throughBack);
  // A floor and a wall of one room (inward faces): they see each other's fronts.
  const auto floor =
      ConvexPolygon::fromVertices({{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, kTol);
  const auto wall = ConvexPolygon::fromVertices({{0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}}, kTol);
  ASSERT_TRUE(floor && wall);
  EXPECT_TRUE(facingLines(*floor, *wall, kTol.length()).throughFront);
  EXPECT_FALSE(facingLines(*floor, *wall, kTol.length()).throughBack);
}

}  // namespace
}  // namespace gv
