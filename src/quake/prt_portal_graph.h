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

}  // namespace gv
