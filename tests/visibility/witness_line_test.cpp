// Lines of a given direction through chains of convex polygons (the stabbing test's cheap witness
// step): built around a known line, the answer must cross every polygon (checked exactly with
// orient3d); with disjoint projections there is no answer.
#include "visibility/witness_line.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace gv {
namespace {

// Exact: the line meets the closed convex loop (all sides of one sign, some non-zero).
bool meets(const Segment& line, const std::vector<Vec3>& w) {
  int pos = 0, neg = 0;
  for (size_t i = 0; i < w.size(); ++i) {
    const int s = sideExact(line, Segment{w[i], w[(i + 1) % w.size()]});
    pos += s > 0, neg += s < 0;
  }
  return (pos == 0 || neg == 0) && pos + neg > 0;
}

// A random convex polygon (regular-ish n-gon with jitter) around centre c in the plane ⟂ n.
std::vector<Vec3> polygonAround(std::mt19937_64& rng, const Vec3& c, const Vec3& n, double r) {
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 a = normalize(cross(n, std::abs(n.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0}));
  const Vec3 b = cross(normalize(n), a);
  const int k = 3 + static_cast<int>(rng() % 6);
  std::vector<Vec3> w;
  for (int i = 0; i < k; ++i) {
    const double t = 2 * M_PI * (i + 0.3 * u(rng)) / k;  // gaps < π: contains c
    w.push_back(c + (a * std::cos(t) + b * std::sin(t)) * (r * (0.5 + u(rng))));
  }
  return w;
}

TEST(WitnessLine, FindsALineThroughPolygonsBuiltAroundOne) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0, 1);
  WitnessScratch scratch;
  int found = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 p{g(rng), g(rng), g(rng)};
    const Vec3 d = normalize(Vec3{g(rng), g(rng), 2 + std::abs(g(rng))});
    std::vector<std::vector<Vec3>> loops;
    for (int k = 0; k < 2 + trial % 8; ++k) {
      // Tilted planes crossing the line at increasing parameters; the line's point is inside.
      const Vec3 n = normalize(d + Vec3{0.3 * g(rng), 0.3 * g(rng), 0.3 * g(rng)});
      loops.push_back(polygonAround(rng, p + d * (2.0 * k), n, 0.5));
    }
    std::vector<std::span<const Vec3>> spans(loops.begin(), loops.end());
    const std::optional<Segment> line = lineAlongDirection(spans, d, scratch);
    ASSERT_TRUE(line) << "trial " << trial;
    bool all = true;
    for (const auto& w : loops) all = all && meets(*line, w);
    found += all;
  }
  // The common region has the line's point well inside: its centroid line crosses every polygon.
  EXPECT_EQ(found, 300);
}

TEST(WitnessLine, NoLineWhenProjectionsAreDisjoint) {
  WitnessScratch scratch;
  const std::vector<Vec3> a{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<Vec3> b{{3, 0, 1}, {4, 0, 1}, {4, 1, 1}, {3, 1, 1}};
  const std::vector<std::span<const Vec3>> spans{a, b};
  EXPECT_FALSE(lineAlongDirection(spans, Vec3{0, 0, 1}, scratch));
  // Tilted enough, the same squares line up.
  const std::optional<Segment> line = lineAlongDirection(spans, Vec3{3, 0, 1}, scratch);
  ASSERT_TRUE(line);
  EXPECT_TRUE(meets(*line, a) && meets(*line, b));
}

TEST(WitnessLine, EdgeOnPolygonGivesNoCandidate) {
  WitnessScratch scratch;
  const std::vector<Vec3> a{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<std::span<const Vec3>> spans{a};
  EXPECT_FALSE(lineAlongDirection(spans, Vec3{1, 0, 0}, scratch));  // seen edge-on
}

}  // namespace
}  // namespace gv
