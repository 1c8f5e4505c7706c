// Cells merged before the searches (§4), in two ways.
//
// 1. Neighbours whose union is convex and whose common face is all open. A BSP cuts open space by
//    the planes of surfaces far away, so one room becomes a stack of slabs joined by portals that
//    no surface bounds, and the searches try every order of the slabs. Exact: to a sightline two
//    such cells are one convex cell (a segment between two of its points stays in it), and no
//    patch lies inside it.
// 2. Blind cells, those no patch faces into (no patch inside, every patch on the boundary looking
//    away, or no patch at all), joined with their blind neighbours into one cell of several convex
//    parts whatever their shapes. On a real level these are the level's outside, seen only through
//    the backs of its walls and through cracks between them; measured on doom-fd1-e1m2
//    (docs/BENCHMARKS.md), more than half the cells and two thirds of the portals, where the cell
//    searches explode. Conservative: a segment's cells, read as merged cells, form a walk of
//    portals it crosses in order; where the walk enters a merged cell twice, dropping the loop
//    between leaves a shorter sequence of portals it still crosses in order, so the searches (which
//    never enter a cell twice) still find it. What is lost is only the outside's own occlusion (the
//    backs of walls seen across it), which makes the lists longer, never shorter. A non-convex cell
//    never gives the same-cell VISIBLE shortcut (patch_search.cpp).
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

/// A copy of `sub` with its cells merged:
/// - first every blind cell with its blind neighbours (linked by a portal), into cells whose
///   `parts` list the convex leaves (and their patches);
/// - then, greedily (largest portals first) and repeatedly, two other neighbours when neither
///   holds a patch inside it, no patch of either lies in their common plane (every vertex within
///   the model tolerance of the BSP's splitting plane, or a fragment on the BSP node holding the
///   portal), and their union is convex
///   (every vertex of each lies within every halfspace of the other except those on the common
///   plane, and the intersection of those halfspaces has the two volumes): the merged cell's
///   `shape` is that intersection.
/// Patches are the union of the parts' (all on the boundary). Portals between parts leave the
/// cell graph (a part's leaves keep them as the cell's `innerPortals`, and each part lists its
/// portals) and the others are renumbered (kept in order). The result's cells have no `faces`
/// (nothing after the merge reads them). `leafCell` maps each BSP leaf to its cell. Deterministic.
/// `sub` is taken by value so that a caller done with it can move it in (its BSP tree is moved
/// on, not copied).
Subdivision mergeConvexCells(const Scene& scene, Subdivision sub,
                             ConvexMergeStats* stats = nullptr);

}  // namespace gv
