// A Quake portal file as a portal graph (geometry/portal_graph.h) and back: the clusters are the
// graph's cells, and a PVS over the clusters is expanded to qbsp's leafs. What `globalvis pvs`
// hands the cell PVS (visibility/cell_pvs.h) and makes of its answer.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/portal_graph.h"
#include "quake/prt_file.h"

namespace gv {

/// Cell c = cluster c (leaf c for PRT1), portal k = prt.portals[k] with back = clusterA and
/// front = clusterB (the file's winding points from A into B).
PortalGraph portalGraphOf(const PrtFile& prt);

/// A PVS over the clusters of a .prt file, expanded to its leafs.
struct LeafPvs {
  /// For each leaf of the file, the 0-based ids of the leafs it may see, ascending, itself
  /// included.
  std::vector<std::vector<uint32_t>> visibleLeafs;
  /// Mean of visibleLeafs[i].size() over leafs: `vis`'s "average leafs visible".
  double meanLeafsVisible = 0;
};

/// A leaf sees every leaf of every cluster its cluster sees. `visibleClusters`: per cluster, the
/// clusters it sees, ascending (CellPvsResult::visibleCells of portalGraphOf(prt)).
LeafPvs expandToLeafs(const PrtFile& prt,
                      const std::vector<std::vector<uint32_t>>& visibleClusters);

/// The same PVS kept per cluster: every leaf of a cluster has the same row (ids of the leafs it
/// may see, ascending), so it is built once per cluster and not copied per leaf (e3m4: 1,135
/// rows for 7,071 leafs).
struct ClusterLeafRows {
  std::vector<std::vector<uint32_t>> rows;  ///< per cluster
  double meanLeafsVisible = 0;              ///< as LeafPvs::meanLeafsVisible
  const std::vector<uint32_t>& ofLeaf(const PrtFile& prt, size_t leaf) const {
    return rows[static_cast<size_t>(prt.leafCluster[leaf])];
  }
};
ClusterLeafRows clusterLeafRows(const PrtFile& prt,
                                const std::vector<std::vector<uint32_t>>& visibleClusters);

}  // namespace gv
