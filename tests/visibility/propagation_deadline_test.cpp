// PropagationOptions::deadline, cellProgress and blockerProgress: a passed deadline stops the
// searches with PropagationDeadlineExceeded; the callbacks change nothing in the result.
#include <gtest/gtest.h>

#include "bsp/subdivision.h"
#include "generators/office.h"
#include "visibility/propagation.h"

namespace gv {
namespace {

TEST(PropagationDeadlineTest, PassedDeadlineThrowsAndCallbacksChangeNothing) {
  const Scene scene = generateOffice();
  BspOptions bsp;
  bsp.minCoverage = kVisibilityMinCoverage;
  const Subdivision sub = buildSubdivision(scene, bsp);

  PropagationOptions late;
  late.deadline = Clock::now() - std::chrono::seconds(1);
  EXPECT_THROW(computeVisibility(scene, sub, late), PropagationDeadlineExceeded);

  const VisibilityGraph plain = computeVisibility(scene, sub);
  PropagationOptions watched;
  size_t lastCells = 0, cellTotal = 0;
  watched.cellProgress = [&](size_t done, size_t total) {
    EXPECT_GT(done, lastCells);
    lastCells = done;
    cellTotal = total;
  };
  size_t lastSources = 0;
  watched.blockerProgress = [&](size_t done, size_t total) {
    EXPECT_GT(done, lastSources);
    EXPECT_EQ(total, scene.patches.size());
    lastSources = done;
  };
  watched.deadline = Clock::now() + std::chrono::hours(1);
  const VisibilityGraph g = computeVisibility(scene, sub, watched);
  // Units of the cell stage's work: the searched (merged) cells, or their directed portals when
  // it runs the leaf-PVS search.
  EXPECT_TRUE(cellTotal == g.stats.cells || cellTotal == 2 * g.stats.portals);
  EXPECT_EQ(lastCells, cellTotal);
  EXPECT_EQ(lastSources, scene.patches.size());
  ASSERT_EQ(g.interactions.size(), plain.interactions.size());
  for (size_t i = 0; i < g.interactions.size(); ++i) {
    EXPECT_EQ(g.interactions[i].s, plain.interactions[i].s);
    EXPECT_EQ(g.interactions[i].r, plain.interactions[i].r);
    EXPECT_EQ(g.interactions[i].blockers, plain.interactions[i].blockers);
  }
}

}  // namespace
}  // namespace gv
