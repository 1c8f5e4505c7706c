// Tests for the maze generator: validity, determinism, perfectness and closedness by ray casting.
#include "generators/maze.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "generators/scene_oracle.h"

namespace gv {
namespace {

bool sameGeometry(const Scene& a, const Scene& b) {
  if (a.patches.size() != b.patches.size()) return false;
  for (size_t i = 0; i < a.patches.size(); ++i) {
    if (a.patches[i].polygon.vertices != b.patches[i].polygon.vertices) return false;
  }
  return true;
}

TEST(MazeTest, PatchesAreValidAndLightsCounted) {
  const MazeOptions o{.width = 12, .height = 9, .seed = 4};
  const Scene scene = generateMaze(o);
  const double scale = scene.bounds().diagonal();
  for (const Patch& p : scene.patches) ASSERT_TRUE(testing::isValidPatch(p, scale));
  EXPECT_EQ(scene.emitterCount(), 12u * 9u / 16u);
  EXPECT_EQ(generateMaze({.width = 3, .height = 3, .lights = 5}).emitterCount(), 5u);
}

TEST(MazeTest, SameSeedSameMazeOtherSeedOtherMaze) {
  const MazeOptions o{.width = 10, .height = 10, .seed = 42};
  EXPECT_TRUE(sameGeometry(generateMaze(o), generateMaze(o)));
  MazeOptions other = o;
  other.seed = 43;
  EXPECT_FALSE(sameGeometry(generateMaze(o), generateMaze(other)));
}

// Walls recovered by casting a segment between neighbouring cell centres at mid-height: the
// maze is perfect iff exactly cells - 1 passages are open and they connect every cell. The
// enclosed volume then follows from the recovered walls alone.
TEST(MazeTest, IsAPerfectMazeAndItsWallsAreClosedDisjointBoxes) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    const MazeOptions o{.width = 7, .height = 5, .seed = seed};
    const Scene scene = generateMaze(o);
    const double s = o.cellSize, zMid = 0.5 * o.wallHeight;
    const int w = o.width, h = o.height;
    auto center = [&](int i, int j) { return Vec3{(i + 0.5) * s, (j + 0.5) * s, zMid}; };
    // wallX[j][i]: wall on line y = j between x = i and i+1; wallY[i][j]: on line x = i.
    std::vector<std::vector<char>> wallX(h + 1, std::vector<char>(w, 1));
    std::vector<std::vector<char>> wallY(w + 1, std::vector<char>(h, 1));
    std::vector<int> parent(static_cast<size_t>(w * h));
    for (size_t k = 0; k < parent.size(); ++k) parent[k] = static_cast<int>(k);
    auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    int open = 0;
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        if (i + 1 < w && !testing::segmentBlocked(scene, center(i, j), center(i + 1, j))) {
          wallY[i + 1][j] = 0;
          ++open;
          parent[find(j * w + i)] = find(j * w + i + 1);
        }
        if (j + 1 < h && !testing::segmentBlocked(scene, center(i, j), center(i, j + 1))) {
          wallX[j + 1][i] = 0;
          ++open;
          parent[find(j * w + i)] = find((j + 1) * w + i);
        }
      }
    }
    EXPECT_EQ(open, w * h - 1) << seed;
    for (int k = 0; k < w * h; ++k) EXPECT_EQ(find(k), find(0)) << seed;

    // Volume: slabs + wall height x plan area of the walls, each standing wall segment being a
    // (s - t) x t strip and each vertex square t x t present when any wall touches it.
    const double t = o.wallThickness;
    double planArea = 0;
    for (int j = 0; j <= h; ++j)
      for (int i = 0; i < w; ++i) planArea += wallX[j][i] ? (s - t) * t : 0;
    for (int i = 0; i <= w; ++i)
      for (int j = 0; j < h; ++j) planArea += wallY[i][j] ? (s - t) * t : 0;
    for (int i = 0; i <= w; ++i) {
      for (int j = 0; j <= h; ++j) {
        const bool touched = (i > 0 && wallX[j][i - 1]) || (i < w && wallX[j][i]) ||
                             (j > 0 && wallY[i][j - 1]) || (j < h && wallY[i][j]);
        planArea += touched ? t * t : 0;
      }
    }
    const double slabs = 2 * (w * s + t) * (h * s + t) * o.slabThickness;
    EXPECT_NEAR(testing::divergenceVolume(scene), slabs + planArea * o.wallHeight, 1e-9) << seed;
  }
}

TEST(MazeTest, EveryRayFromInsideHitsAPatch) {
  const MazeOptions o{.width = 6, .height = 6, .seed = 9};
  const Scene scene = generateMaze(o);
  std::mt19937 rng(1);
  const double half = 0.5 * o.wallThickness;
  for (int k = 0; k < 2000; ++k) {
    // A point in the air of a random cell (away from its walls), a long segment in any direction.
    const int i = static_cast<int>(rng() % 6), j = static_cast<int>(rng() % 6);
    const Vec3 p{testing::uniform(rng, i * o.cellSize + half + 0.01, (i + 1) * o.cellSize - half - 0.01),
                 testing::uniform(rng, j * o.cellSize + half + 0.01, (j + 1) * o.cellSize - half - 0.01),
                 testing::uniform(rng, 0.01, o.wallHeight - 0.05)};
    const Vec3 d{testing::uniform(rng, -1, 1), testing::uniform(rng, -1, 1),
                 testing::uniform(rng, -1, 1)};
    if (lengthSquared(d) < 1e-6) continue;
    ASSERT_TRUE(testing::segmentBlocked(scene, p, p + normalize(d) * 100.0)) << p << d;
  }
}

TEST(MazeTest, LargeMazeIsBuiltWithoutRecursion) {
  const Scene scene = generateMaze({.width = 300, .height = 300});
  EXPECT_GT(scene.patches.size(), 300u * 300u);
}

}  // namespace
}  // namespace gv
