// Cell-to-cell visibility over the BSP subdivision (paper §4.1): which cells a sightline from
// each cell may reach, and where it may go after crossing each portal. The patch searches
// (patch_search.h) are bounded by both.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "bsp/subdivision.h"
#include "visibility/cell_set.h"
#include "visibility/might_see.h"
#include "visibility/propagation.h"
#include "visibility/visibility_graph.h"

namespace gv {

/// Where a sightline may go after crossing a portal (a superset): the cell-PVS flow of that
/// directed portal (the cells its stabbable sequences reach) when it was computed, else the
/// might-see flood.
struct PortalReach {
  const std::vector<CellSet>* flow = nullptr;  ///< cell_pvs.h numbering: 2i = into portal i's front
  const MightSee* might = nullptr;
  const CellSet& through(uint32_t pid, bool forward) const {
    return flow ? (*flow)[2 * pid + (forward ? 0 : 1)] : might->through(pid, forward);
  }
};

/// The cell-to-cell stage's answer.
struct CellVisibility {
  /// Per cell, the cells it may see (symmetric); empty when unknown (too many cells for the
  /// sets).
  std::vector<CellSet> cellReach;
  /// Per directed portal, the cells its stabbable sequences reach (CellPvsResult::portalFlow),
  /// when the cell PVS ran; else the might-see flood is kept.
  std::vector<CellSet> flow;
  std::optional<MightSee> flood;
  /// Where sightlines go after each portal: `flow` when the cell PVS ran, else `flood`. Points
  /// into this object.
  PortalReach reach() const {
    PortalReach r;
    if (flood) {
      r.might = &*flood;
    } else {
      r.flow = &flow;
    }
    return r;
  }
};

/// Cell to cell (§4.1). Where the sets fit (portals × cells bits), the cell PVS of cell_pvs.h
/// over the subdivision's cells: one search per directed portal, in waves that let finished
/// portals' results narrow later searches; its per-portal results (flows) then bound the patch
/// searches far more tightly than the might-see flood. Otherwise a search per cell, pruned by
/// the flood. Fills the cell fields of `st` (not cellSeconds); `threads` as resolved by
/// computeVisibility; options' cell budget, cellProgress and deadline apply.
CellVisibility computeCellVisibility(const Subdivision& sub, int threads,
                                     const PropagationOptions& options, VisibilityStats& st);

}  // namespace gv
