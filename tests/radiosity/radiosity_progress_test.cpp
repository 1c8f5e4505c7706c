// RadiosityOptions::refineProgress: per round, rising counts ending at the round's link count,
// and the same answer with or without the callback.
#include <gtest/gtest.h>

#include <vector>

#include "generators/cornell_box.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/ray_visibility.h"
#include "raycast/embree_scene.h"

namespace gv {
namespace {

TEST(RadiosityProgressTest, RefinementReportsEveryRoundUpToItsLinkCount) {
  const Scene scene = generateCornellBox();
  const EmbreeScene bvh(scene);
  RadiosityOptions options;
  options.maxRefinements = 3;
  RayVisibility plainVisibility(scene, bvh, 4);
  const RadiosityResult plain = solveRadiosity(scene, plainVisibility, options);

  std::vector<std::pair<size_t, size_t>> reports;
  options.refineProgress = [&](size_t done, size_t total) { reports.emplace_back(done, total); };
  RayVisibility visibility(scene, bvh, 4);
  const RadiosityResult watched = solveRadiosity(scene, visibility, options);
  EXPECT_EQ(watched.patchRadiosity, plain.patchRadiosity);

  // The rounds' link counts at their start: the links alive after the round before.
  const auto& rounds = watched.stats.rounds;
  ASSERT_GE(rounds.size(), 2u);
  size_t round = 1, last = 0;
  for (const auto& [done, total] : reports) {
    ASSERT_LT(round, rounds.size());
    EXPECT_EQ(total, rounds[round - 1].links.total());
    EXPECT_LE(done, total);
    EXPECT_GT(done, last);
    last = done;
    if (done == total) {
      ++round;
      last = 0;
    }
  }
  EXPECT_EQ(round, rounds.size());  // every refinement round ended with a (total, total) report
}

}  // namespace
}  // namespace gv
