// Pairs of nearly coplanar patches that face each other: two pieces of one wall a hair out of
// line (corners 1e-6 off each other's plane, as converted brush geometry has them). Their
// sightlines run along the wall, within the model tolerance of it, where the BSP merged both
// patches' planes into one cell boundary: a line in the thin wedge in front of both planes may
// dip behind that boundary, out of every cell the searches walk (q3-oa_dm4 (235, 264),
// bench/scenes/inplane_graze.obj). Such pairs are added to the searches' answers so that the
// blocker stage lists them, with their blockers, unless it proves them hidden.
#pragma once

#include <vector>

#include "bsp/plane_set.h"
#include "geometry/tolerance.h"
#include "scene/scene.h"
#include "visibility/patch_search.h"

namespace gv {

/// Adds to `seen` (both sources' lists, front seen) every pair of patches that share a merged
/// plane of `planes`, face the same way along it, and face each other by the blocker stage's own
/// rule (a vertex of each more than `tol.length()` in front of the other's plane). Returns the
/// number of pairs added (those the searches had not both seen front to front). Patches with the
/// same plane equation cannot face each other and are not paired: O(pairs of distinct planes
/// within one merged plane).
size_t addCoplanarGrazes(const Scene& scene, const PlaneSet& planes, const Tolerance& tol,
                         std::vector<PatchSearchResult>& seen);

}  // namespace gv
