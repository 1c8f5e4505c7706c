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

ClusterLeafRows clusterLeafRows(const PrtFile& prt,
                                const std::vector<std::vector<uint32_t>>& visibleClusters) {
  ClusterLeafRows out;
  out.rows.resize(prt.clusterCount);
  for (size_t c = 0; c < prt.clusterCount; ++c) {
    std::vector<uint32_t>& row = out.rows[c];
    for (uint32_t d : visibleClusters[c])
      for (int leaf : prt.clusterLeafs[d]) row.push_back(static_cast<uint32_t>(leaf));
    std::sort(row.begin(), row.end());
  }
  double total = 0;
  for (size_t l = 0; l < prt.leafCount; ++l)
    total += static_cast<double>(out.ofLeaf(prt, l).size());
  out.meanLeafsVisible = prt.leafCount ? total / static_cast<double>(prt.leafCount) : 0;
  return out;
}

LeafPvs expandToLeafs(const PrtFile& prt,
                      const std::vector<std::vector<uint32_t>>& visibleClusters) {
  const ClusterLeafRows rows = clusterLeafRows(prt, visibleClusters);
  LeafPvs pvs;
  pvs.visibleLeafs.resize(prt.leafCount);
  for (size_t l = 0; l < prt.leafCount; ++l) pvs.visibleLeafs[l] = rows.ofLeaf(prt, l);
  pvs.meanLeafsVisible = rows.meanLeafsVisible;
  return pvs;
}

}  // namespace gv
