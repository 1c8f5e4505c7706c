// BallTree against brute force: a query by a half-space visits exactly the items whose own ball
// the half-space keeps, when the test of a ball is monotone (a ball inside a rejected ball is
// rejected too), and the state handed down reaches the leaves; findKept finds one when there is.
#include "geometry/ball_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace gv {
namespace {

TEST(BallTree, HalfSpaceQueriesVisitWhatBruteForceKeeps) {
  const Tolerance tol{100.0};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-50, 50), rad(0, 4);
  for (size_t n : {0u, 1u, 3u, 4u, 5u, 17u, 200u}) {
    std::vector<Ball> balls(n);
    for (Ball& b : balls) b = Ball{Vec3{u(rng), u(rng), u(rng)}, rad(rng)};
    const BallTree tree(balls, tol), single(balls, tol, 1);
    for (const Ball& b : balls) {  // the root holds every ball
      EXPECT_LE(length(b.center - tree.bounds().center) + b.radius,
                tree.bounds().radius * (1 + 1e-12));
    }
    for (int q = 0; q < 50; ++q) {
      const Vec3 normal = normalize(Vec3{u(rng), u(rng), u(rng)});
      const double offset = u(rng) * 0.5;
      // Kept: not wholly behind the plane. The state counts the depth walked. A node's range
      // names the items inside its ball, the whole of order() at the root.
      const BallTree* walked = &tree;
      auto keep = [&](const Ball& b, BallTree::ItemRange range, int& depth) {
        if (depth == 0) {
          EXPECT_EQ(range.begin, 0u);
          EXPECT_EQ(range.end, n);
        }
        EXPECT_LT(range.begin, range.end);
        for (uint32_t k = range.begin; k < range.end; ++k) {
          const Ball& item = balls[walked->order()[k]];
          EXPECT_LE(length(item.center - b.center) + item.radius, b.radius * (1 + 1e-12) + 1e-12);
        }
        ++depth;
        return dot(normal, b.center) - offset >= -b.radius;
      };
      std::vector<uint32_t> visited;
      tree.forEachKept(0, keep, [&](uint32_t i, int depth) {
        EXPECT_GE(depth, 1);
        visited.push_back(i);
      });
      std::vector<uint32_t> expected;
      for (uint32_t i = 0; i < n; ++i)
        if (dot(normal, balls[i].center) - offset >= -balls[i].radius) expected.push_back(i);
      std::sort(visited.begin(), visited.end());
      // Every item whose ball is kept is visited once; an item visited beyond those is one whose
      // leaf ball was kept though its own is not (the caller tests the item itself).
      EXPECT_TRUE(std::includes(visited.begin(), visited.end(), expected.begin(), expected.end()));
      EXPECT_TRUE(std::adjacent_find(visited.begin(), visited.end()) == visited.end());
      // With one item per leaf, exactly those.
      visited.clear();
      walked = &single;
      single.forEachKept(0, keep, [&](uint32_t i, int) { visited.push_back(i); });
      std::sort(visited.begin(), visited.end());
      EXPECT_EQ(visited, expected);
      // findKept: is there an item the plane keeps, stopping at the first one accepted.
      walked = &tree;
      size_t accepted = 0;
      const bool found = tree.findKept(0, keep, [&](uint32_t i, int) {
        const bool in = dot(normal, balls[i].center) - offset >= -balls[i].radius;
        accepted += in;
        return in;
      });
      EXPECT_EQ(found, !expected.empty());
      EXPECT_EQ(accepted, found ? 1u : 0u);
    }
  }
}

}  // namespace
}  // namespace gv
