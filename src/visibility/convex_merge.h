// Cells merged where no surface lies between them. A BSP cuts open space by the planes of
// surfaces far away (on a sector level a wall's plane runs through every room it passes), so one
// room becomes a stack of slivers joined by portals that no surface bounds. The searches of §4
// then see every order of those slivers as a different portal sequence, and on real levels they
// fan out combinatorially.
//
// Why merging is exact here: a merged cell K is kept only when no patch enters the interior of
// its convex hull conv(K). Every sightline of the searches is a segment; the part of it between
// two points of K lies in conv(K), so no patch blocks it there, and K's patches all lie on the
// boundary of conv(K), where the facing rule of a convex cell holds. To the searches K is then
// the convex cell conv(K), patch-free inside, as the paper's cells are. Its regions outside K (if
// any) are air of other cells, which a segment may cross freely anyway. And a segment that leaves
// K and comes back is still found: dropping the loop leaves a portal sequence it stabs.
#pragma once

#include <cstddef>

#include "bsp/subdivision.h"
#include "scene/scene.h"

namespace gv {

/// What mergeConvexCells did.
struct ConvexMergeStats {
  size_t cellsBefore = 0, cellsAfter = 0;
  size_t portalsBefore = 0, portalsAfter = 0;
};

/// A copy of `sub` in which adjacent cells (linked by a portal) are merged, greedily (largest
/// portals first) and repeatedly, while
/// - neither holds a patch inside it (an interior patch is seen from every side of its cell, so a
///   larger cell would see it from more places), and
/// - no patch of `scene` enters the interior of the convex hull of their union (shrunk by the
///   model tolerance: a patch touching it within Tolerance::planeOffset() does not count).
/// The merged cell's `shape` is that hull (so cells may overlap where a hull spans another cell's
/// air); its patches are the union of its parts' (all on the hull's boundary). Portals between
/// parts are dropped and the others renumbered (kept in order). The result's cells have no
/// `faces` (nothing after the merge reads them). `leafCell` maps each BSP leaf to its cell.
Subdivision mergeConvexCells(const Scene& scene, const Subdivision& sub,
                             ConvexMergeStats* stats = nullptr);

}  // namespace gv
