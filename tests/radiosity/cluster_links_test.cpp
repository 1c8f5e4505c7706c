// Links between clusters (cluster_links.h): the sampled transfer is unbiased (against the exact
// form factor of Howell's C-11, parallel opposed squares), it carries nothing along blocked
// segments or between pairs the oracle does not list, and the bound refuses close clusters.
#include "radiosity/cluster_links.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "generators/scene_builder.h"
#include "radiosity/element_tree.h"

namespace gv {
namespace {

/// Howell C-11: directly opposed parallel squares of side a at distance c.
double howellC11(double a, double c) {
  const double x = a / c, y = a / c;
  const double x1 = std::sqrt(1 + x * x), y1 = std::sqrt(1 + y * y);
  return 2 / (std::numbers::pi * x * y) *
         (std::log(x1 * y1 / std::sqrt(1 + x * x + y * y)) + x * y1 * std::atan(x / y1) +
          y * x1 * std::atan(y / x1) - x * std::atan(x) - y * std::atan(y));
}

/// An oracle for the sampling alone: every pair a candidate (or none), every segment clear (or
/// every one blocked).
class FixedOracle final : public LinkVisibility {
 public:
  FixedOracle(bool pairs, bool blocked) : pairs_(pairs), blocked_(blocked) {}
  std::string_view name() const override { return "fixed"; }
  void forEachCandidatePair(const std::function<void(uint32_t, uint32_t, TubeId)>&) override {}
  VisibilityEstimate estimate(const Element&, const Element&, TubeId, uint64_t) override {
    return {};
  }
  bool answersSegments() const override { return true; }
  bool everyPairIsCandidate() const override { return pairs_; }
  bool segmentBlocked(uint32_t, const Vec3&, uint32_t, const Vec3&, TubeId) const override {
    return blocked_;
  }

 private:
  bool pairs_, blocked_;
};

/// An oracle that lists the given pairs, each with its index as its tube.
class ListOracle final : public LinkVisibility {
 public:
  explicit ListOracle(std::vector<std::pair<uint32_t, uint32_t>> pairs)
      : pairs_(std::move(pairs)) {}
  std::string_view name() const override { return "list"; }
  void forEachCandidatePair(const std::function<void(uint32_t, uint32_t, TubeId)>& visit) override {
    for (size_t i = 0; i < pairs_.size(); ++i)
      visit(pairs_[i].first, pairs_[i].second, static_cast<TubeId>(i));
  }
  VisibilityEstimate estimate(const Element&, const Element&, TubeId, uint64_t) override {
    return {};
  }
  bool answersSegments() const override { return true; }

 private:
  std::vector<std::pair<uint32_t, uint32_t>> pairs_;
};

/// A unit square at z = 0 facing up in four equal pieces, and one at z = c facing down in four
/// unequal ones (a half, a quarter, two eighths: the area-proportional pick matters).
struct OpposedSquares {
  Scene scene;
  explicit OpposedSquares(double c) {
    const uint32_t m = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
    SceneBuilder b(scene, Tolerance{2 + c});
    for (const double x : {0.0, 0.5})
      for (const double y : {0.0, 0.5})
        EXPECT_TRUE(b.addAxisRect(2, true, {x, y, 0}, {x + 0.5, y + 0.5, 0}, m));
    EXPECT_TRUE(b.addAxisRect(2, false, {0, 0, c}, {1, 0.5, c}, m));
    EXPECT_TRUE(b.addAxisRect(2, false, {0, 0.5, c}, {0.5, 1, c}, m));
    EXPECT_TRUE(b.addAxisRect(2, false, {0.5, 0.5, c}, {1, 0.75, c}, m));
    EXPECT_TRUE(b.addAxisRect(2, false, {0.5, 0.75, c}, {1, 1, c}, m));
  }
};

/// What sampleClusterLink needs for a scene: its cluster tree and elements, and a FixedOracle
/// with its candidate pairs (every pair or none; every segment clear or blocked).
struct Sampling {
  ClusterTree tree;
  ElementTree elements;
  FixedOracle oracle;
  CandidatePairs candidates;
  Tolerance tol;
  explicit Sampling(const Scene& scene, bool pairs = true, bool blocked = false)
      : tree(scene),
        elements(scene),
        oracle(pairs, blocked),
        candidates(oracle, tree),
        tol(scene.tolerance()) {}
  /// The link between clusters x and y, sources picked by `brightness` (per patch).
  ClusterSampling sample(std::span<const double> brightness, uint32_t x, uint32_t y,
                         int samplesPerPatch, uint64_t seed) const {
    return sampleClusterLink(tree, SourcePicker(tree, brightness), elements, candidates, oracle,
                             tol, x, y, samplesPerPatch, seed);
  }
  /// The same with every patch dark: sources picked by area alone.
  ClusterSampling sampleByArea(uint32_t x, uint32_t y, int samplesPerPatch, uint64_t seed) const {
    return sample(std::vector<double>(tree.order().size(), 0.0), x, y, samplesPerPatch, seed);
  }
};

/// The receiving square's cluster (patches 0-3) and the other one, under the root.
std::pair<uint32_t, uint32_t> squares(const ClusterTree& tree) {
  const Cluster& root = tree[0];
  const bool leftIsLower = tree.patchesOf(root.left)[0] < 4;
  return leftIsLower ? std::pair{root.left, root.right} : std::pair{root.right, root.left};
}

TEST(ClusterLinkTest, SampledTransferMatchesTheExactFormFactor) {
  const double c = 3;
  OpposedSquares s(c);
  const Sampling open(s.scene);
  const ClusterTree& tree = open.tree;
  const ElementTree& elements = open.elements;
  const auto [lower, upper] = squares(tree);
  ASSERT_EQ(tree[lower].size(), 4u);
  ASSERT_EQ(tree[upper].size(), 4u);
  const ClusterSampling got = open.sampleByArea(lower, upper, 4000, 7);
  // Per receiving patch: Σ coefficient = its form factor to the other square (B = 1 there).
  std::vector<double> into(s.scene.patches.size(), 0.0);
  for (const ClusterTap& t : got.taps) {
    EXPECT_GE(t.source, 0u);
    into[t.receiver] += t.coefficient;
    // Each tap's source lies on the other square.
    EXPECT_EQ(elements[t.source].patch < 4, t.receiver >= 4);
  }
  double lowerToUpper = 0, upperToLower = 0;
  for (uint32_t p = 0; p < 8; ++p)
    (p < 4 ? lowerToUpper : upperToLower) += into[p] * s.scene.patches[p].polygon.area();
  const double exact = howellC11(1, c);
  // 16,000 samples a side, a kernel varying by ~35 % over the squares: the mean's standard
  // error is ~0.1 %; 1 % is ten of them (a bound, not today's error).
  EXPECT_NEAR(lowerToUpper, exact, 0.01 * exact);
  EXPECT_NEAR(upperToLower, exact, 0.01 * exact);
  // Every sample faces and is clear: one ray, then two for the crack test.
  EXPECT_EQ(got.rays, 3u * 4000u * 8u);
  EXPECT_NEAR(howellC11(1, 1), 0.19982, 1e-5);  // the formula itself, against the catalogue
}

TEST(ClusterLinkTest, PowerPickedSourcesKeepTheFormFactorUnbiased) {
  // The same squares with the upper pieces at very different brightness: the picks follow the
  // power half the time, and the taps still sum to the exact form factor.
  const double c = 3;
  OpposedSquares s(c);
  const Sampling open(s.scene);
  const auto [lower, upper] = squares(open.tree);
  const std::vector<double> brightness = {0, 0, 0, 0, 50, 1, 0, 3};
  const ClusterSampling got = open.sample(brightness, lower, upper, 20000, 11);
  double lowerToUpper = 0;
  for (const ClusterTap& t : got.taps)
    if (t.receiver < 4) lowerToUpper += t.coefficient * s.scene.patches[t.receiver].polygon.area();
  // Weights between 0.68 and 2 (A_q / P(q)) and the kernel's ~35 %: a relative spread under
  // ~60 % per sample, 80,000 samples: standard error ≲ 0.2 %; 1 % is five of them.
  const double exact = howellC11(1, c);
  EXPECT_NEAR(lowerToUpper, exact, 0.01 * exact);
}

TEST(ClusterLinkTest, SmallBrightSourceIsFoundByPowerAndMissedByArea) {
  // A 1 x 1 floor in two pieces under a dim 1 x 1 ceiling with a 1 cm lamp just below it: by
  // area the lamp is picked once in 10^4 samples, by power about every other sample, and the
  // light it sends is then estimated within a few per cent of the exact point-source value.
  Scene scene;
  const uint32_t m = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  SceneBuilder b(scene, Tolerance{4.0});
  ASSERT_TRUE(b.addAxisRect(2, true, {0, 0, 0}, {0.5, 1, 0}, m));
  ASSERT_TRUE(b.addAxisRect(2, true, {0.5, 0, 0}, {1, 1, 0}, m));
  ASSERT_TRUE(b.addAxisRect(2, false, {0, 0, 3}, {1, 1, 3}, m));
  ASSERT_TRUE(b.addAxisRect(2, false, {0.495, 0.495, 2.99}, {0.505, 0.505, 2.99}, m));
  const Sampling open(scene);
  const ClusterTree& tree = open.tree;
  const ElementTree& elements = open.elements;
  const uint32_t floor = tree.patchesOf(tree[0].left)[0] < 2 ? tree[0].left : tree[0].right;
  const uint32_t ceiling = floor == tree[0].left ? tree[0].right : tree[0].left;
  ASSERT_EQ(tree[ceiling].size(), 2u);
  const double lampB = 1e4;
  const std::vector<double> brightness = {0, 0, 0.01, lampB};
  auto lampLight = [&](const ClusterSampling& got, size_t& picks) {
    double power = 0;  // Σ over the floor's taps from the lamp of coefficient · area · B
    picks = 0;
    for (const ClusterTap& t : got.taps) {
      if (t.receiver >= 2 || elements[t.source].patch != 3) continue;
      ++picks;
      power += t.coefficient * scene.patches[t.receiver].polygon.area() * lampB;
    }
    return power;
  };
  // Exact: a 1e-4 m² lamp 2.99 above the centre of the floor: A_lamp · B · F(lamp → floor),
  // F from a point over the common corner of four 0.5 x 0.5 rectangles.
  const double h = 2.99, a = 0.5 / h;
  const double corner =
      (a / std::sqrt(1 + a * a) * std::atan(a / std::sqrt(1 + a * a))) / std::numbers::pi;
  const double exact = 1e-4 * lampB * 4 * corner;
  size_t byPower = 0, byArea = 0;
  const double found = lampLight(open.sample(brightness, floor, ceiling, 64, 5), byPower);
  const double missed = lampLight(open.sampleByArea(floor, ceiling, 64, 5), byArea);
  // 128 floor samples: about 64 pick the lamp by power (±~6 at one standard deviation).
  EXPECT_GT(byPower, 40u);
  EXPECT_LT(byPower, 90u);
  // The kernel varies ~10 % over the floor: ~1.3 % standard error with ~64 picks; 8 % is six.
  EXPECT_NEAR(found, exact, 0.08 * exact);
  // By area: no sample finds the lamp (expected 0.013 picks), so the floor would stay dark.
  EXPECT_EQ(byArea, 0u);
  EXPECT_EQ(missed, 0.0);
}

TEST(ClusterLinkTest, BlockedSegmentsAndUnlistedPairsCarryNothing) {
  OpposedSquares s(3);
  const Sampling blocked(s.scene, true, true);
  const auto [lower, upper] = squares(blocked.tree);
  const ClusterSampling b = blocked.sampleByArea(lower, upper, 8, 1);
  EXPECT_TRUE(b.taps.empty());
  EXPECT_EQ(b.rays, 8u * 8u);
  const Sampling none(s.scene, false,
                      false);  // lists no pair (forEachCandidatePair visits nothing)
  EXPECT_EQ(none.candidates.count(), 0u);
  const ClusterSampling n = none.sampleByArea(lower, upper, 8, 1);
  EXPECT_TRUE(n.taps.empty());
  EXPECT_EQ(n.rays, 0u);
}

TEST(ClusterLinkTest, CandidateLookupsAgreeWithTheListByBruteForce) {
  // A few listed pairs among the 8 patches; every pair of disjoint clusters of the tree is then
  // checked against a scan of the list, and every pair of patches against the list's tubes.
  OpposedSquares s(3);
  const ClusterTree tree(s.scene);
  const std::vector<std::pair<uint32_t, uint32_t>> listed = {{0, 5}, {6, 1}, {2, 3}, {7, 4}};
  ListOracle oracle(listed);
  const CandidatePairs candidates(oracle, tree);
  EXPECT_EQ(candidates.count(), listed.size());
  for (uint32_t a = 0; a < 8; ++a)
    for (uint32_t b = 0; b < 8; ++b) {
      if (a == b) continue;
      std::optional<TubeId> expected;
      for (size_t i = 0; i < listed.size(); ++i)
        if ((listed[i].first == a && listed[i].second == b) ||
            (listed[i].first == b && listed[i].second == a))
          expected = static_cast<TubeId>(i);
      EXPECT_EQ(candidates.find(a, b), expected) << a << " " << b;
    }
  size_t checked = 0, without = 0;
  for (uint32_t x = 0; x < tree.size(); ++x)
    for (uint32_t y = 0; y < tree.size(); ++y) {
      const Cluster& cx = tree[x];
      const Cluster& cy = tree[y];
      if (cx.begin < cy.end && cy.begin < cx.end) continue;  // nested or the same
      bool any = false;
      for (const uint32_t p : tree.patchesOf(x))
        for (const uint32_t q : tree.patchesOf(y))
          for (const auto& [a, b] : listed) any = any || (a == p && b == q) || (a == q && b == p);
      EXPECT_EQ(candidates.anyBetween(x, y), any) << x << " " << y;
      ++checked;
      without += any ? 0 : 1;
    }
  // The construction has both answers, at every level (the two squares: 3 pairs between them).
  EXPECT_GT(checked, 100u);
  EXPECT_GT(without, 20u);
  const auto [lower, upper] = squares(tree);
  EXPECT_TRUE(candidates.anyBetween(lower, upper));
}

TEST(ClusterLinkTest, FacesTurnedAwayReceiveNothing) {
  // The upper square turned to face up too: no segment leaves its front towards the lower one.
  Scene scene;
  const uint32_t m = scene.addMaterial({"grey", {0.5, 0.5, 0.5}, {}});
  SceneBuilder b(scene, Tolerance{5.0});
  ASSERT_TRUE(b.addAxisRect(2, true, {0, 0, 0}, {1, 1, 0}, m));
  ASSERT_TRUE(b.addAxisRect(2, true, {0, 0, 3}, {1, 1, 3}, m));
  const Sampling open(scene);
  const ClusterSampling got = open.sampleByArea(open.tree[0].left, open.tree[0].right, 64, 3);
  EXPECT_TRUE(got.taps.empty());
  EXPECT_EQ(got.rays, 0u);
}

TEST(ClusterLinkTest, BoundIsExactArithmeticAndRefusesCloseClusters) {
  OpposedSquares far(3);
  const ClusterTree tree(far.scene);
  const auto [lower, upper] = squares(tree);
  // ρ A_X B_Y A_Y / (π d²) = 0.5 · 1 · 2 · 1 / (9π), the other way 0 (B_X = 0).
  EXPECT_NEAR(clusterTransferBound(tree[lower], tree[upper], 0.0, 2.0),
              1.0 / (9 * std::numbers::pi), 1e-12);
  EXPECT_NEAR(clusterTransferBound(tree[upper], tree[lower], 2.0, 0.0),
              1.0 / (9 * std::numbers::pi), 1e-12);
  // At distance 1, A / (π d²) = 0.32 > kMaxClusterFormFactor: never a cluster link, even dark.
  OpposedSquares near(1);
  const ClusterTree close(near.scene);
  const auto [l2, u2] = squares(close);
  EXPECT_EQ(clusterTransferBound(close[l2], close[u2], 0.0, 0.0), INFINITY);
}

}  // namespace
}  // namespace gv
