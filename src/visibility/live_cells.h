// The cells a sightline between two patches can enter at all, and the subdivision without the
// others: a closed solid's inside (a wall slab, a brush union) is a region of cells linked to one
// another by portals but to nothing else, and no patch faces into it, so the searches have
// nothing to find there. Removing such regions is exact, not a heuristic (see live_cells.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "bsp/subdivision.h"
#include "scene/scene.h"

namespace gv {

/// The cells of a subdivision split into live and dead ones.
struct LiveCells {
  /// Per cell: 1 when the cell's portal-connected region holds a patch whose front looks into
  /// it (a boundary patch facing in, or any patch inside a cell).
  std::vector<uint8_t> live;
  size_t deadCells = 0;
  size_t deadPortals = 0;  ///< portals between two dead cells (a portal never links live to dead)
};

/// Finds the live cells: the union of the portal-connected regions (connected components of the
/// adjacency graph) that hold a patch facing into one of their cells.
LiveCells findLiveCells(const Scene& scene, const Subdivision& sub);

/// A copy of `sub` whose dead cells keep their shapes and patches but have no portals, and whose
/// portal list holds only the live portals (renumbered in their order). Cell ids are unchanged.
Subdivision withoutDeadPortals(const Subdivision& sub, const LiveCells& live);

}  // namespace gv
