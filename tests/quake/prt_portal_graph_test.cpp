// Tests of the .prt adapter of the cell PVS: clusters become cells with the file's portal
// orientation, and cluster rows expand to leaf rows (a hand-written PRT2 file, answers by hand).
#include "quake/prt_portal_graph.h"

#include <gtest/gtest.h>

#include <sstream>

namespace gv {
namespace {

// Leafs 0 and 3 form cluster 0, leafs 1, 2, 4 cluster 1; one portal between them.
const char* kTwoClusters =
    "PRT2\n5\n2\n1\n"
    "4 0 1 (1 0 0) (1 1 0) (1 1 1) (1 0 1)\n"
    "0 3 -1\n"
    "1 2 4 -1\n";

PrtFile twoClusters() {
  std::istringstream in(kTwoClusters);
  return parsePrt(in, "two-clusters.prt");
}

TEST(PrtPortalGraph, ClustersAreCellsAndTheWindingPointsFromBackToFront) {
  const PrtFile prt = twoClusters();
  const PortalGraph graph = portalGraphOf(prt);
  EXPECT_EQ(graph.cellCount, 2u);
  ASSERT_EQ(graph.portals.size(), 1u);
  EXPECT_EQ(graph.portals[0].back, 0u);
  EXPECT_EQ(graph.portals[0].front, 1u);
  EXPECT_EQ(graph.portals[0].winding, prt.portals[0].winding);
}

TEST(PrtPortalGraph, ClusterRowsExpandToEveryLeafOfTheSeenClusters) {
  const PrtFile prt = twoClusters();
  // Cluster 0 sees both, cluster 1 only itself (not symmetric: the expansion does not care).
  const LeafPvs pvs = expandToLeafs(prt, {{0, 1}, {1}});
  const std::vector<uint32_t> all{0, 1, 2, 3, 4}, second{1, 2, 4};
  ASSERT_EQ(pvs.visibleLeafs.size(), 5u);
  EXPECT_EQ(pvs.visibleLeafs[0], all);
  EXPECT_EQ(pvs.visibleLeafs[3], all);
  EXPECT_EQ(pvs.visibleLeafs[1], second);
  EXPECT_EQ(pvs.visibleLeafs[2], second);
  EXPECT_EQ(pvs.visibleLeafs[4], second);
  EXPECT_DOUBLE_EQ(pvs.meanLeafsVisible, (5.0 + 5.0 + 3.0 + 3.0 + 3.0) / 5.0);
}

}  // namespace
}  // namespace gv
