// .prt clusters as portal-graph cells, and cluster visibility expanded to leafs (see header).
#include "quake/prt_portal_graph.h"

#include <algorithm>

namespace gv {

PortalGraph portalGraphOf(const PrtFile& prt) {
  PortalGraph graph;
  graph.cellCount = prt.clusterCount;
  graph.portals.reserve(prt.portals.size());
  for (const PrtPortal& p : prt.portals)
    graph.portals.push_back(
        {p.winding, static_cast<uint32_t>(p.clusterA), static_cast<uint32_t>(p.clusterB)});
  return graph;
}

LeafPvs expandToLeafs(const PrtFile& prt,
                      const std::vector<std::vector<uint32_t>>& visibleClusters) {
  std::vector<std::vector<uint32_t>> clusterRow(prt.clusterCount);
  for (size_t c = 0; c < prt.clusterCount; ++c) {
    for (uint32_t d : visibleClusters[c])
      for (int leaf : prt.clusterLeafs[d]) clusterRow[c].push_back(static_cast<uint32_t>(leaf));
    std::sort(clusterRow[c].begin(), clusterRow[c].end());
  }
  LeafPvs pvs;
  pvs.visibleLeafs.resize(prt.leafCount);
  double total = 0;
  for (size_t l = 0; l < prt.leafCount; ++l) {
    pvs.visibleLeafs[l] = clusterRow[prt.leafCluster[l]];
    total += static_cast<double>(pvs.visibleLeafs[l].size());
  }
  pvs.meanLeafsVisible = prt.leafCount ? total / static_cast<double>(prt.leafCount) : 0;
  return pvs;
}

}  // namespace gv
