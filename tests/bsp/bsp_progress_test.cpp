// BspOptions::progress: the fraction of the root's volume in finished leaves rises to 1 and the
// tree is the same with or without the callback.
#include <gtest/gtest.h>

#include <vector>

#include "bsp/bsp_tree.h"
#include "generators/office.h"

namespace gv {
namespace {

TEST(BspProgressTest, VolumeFractionRisesToOneAndChangesNothing) {
  const Scene scene = generateOffice();
  BspOptions options;
  options.minCoverage = kVisibilityMinCoverage;
  const BspTree plain = buildBspTree(scene, options);
  std::vector<double> reports;
  options.progress = [&](double f) { reports.push_back(f); };
  const BspTree watched = buildBspTree(scene, options);
  ASSERT_EQ(reports.size(), watched.leaves.size());  // one report per leaf
  EXPECT_EQ(watched.leaves.size(), plain.leaves.size());
  EXPECT_EQ(watched.nodes.size(), plain.nodes.size());
  for (size_t i = 1; i < reports.size(); ++i) EXPECT_GT(reports[i], reports[i - 1]);
  // Independent of the reports: the leaves' volumes over the root's.
  double volume = 0;
  for (const BspLeaf& leaf : watched.leaves) volume += leaf.shape.volume();
  EXPECT_NEAR(reports.back(), volume / watched.root.volume(), 1e-12);
  EXPECT_NEAR(reports.back(), 1.0, 1e-9);
}

}  // namespace
}  // namespace gv
