// Patches cut along the outlines of the patches that rest on them or hang just in front of them
// (a wall's bottom face on a floor slab, a desk on the floor, a light panel 2 cm below the
// ceiling). Supports paper §6 / HSA91: elements then follow the contact lines.
#pragma once

#include <cstddef>

#include "scene/scene.h"

namespace gv {

/// A parallel patch q "shadows" patch p when it lies in front of p's plane (or in it, either
/// orientation) at a gap no more than this fraction of sqrt(area(q)) and overlaps p seen along p's
/// normal. The part of p under q then sees (almost) nothing but q, while the rest of p is open:
/// a quadtree element straddling the outline averages the two, re-emits the light of the open
/// part from the covered part into q's back, and the whole solution turns a few percent dark
/// (measured on the office; docs/BENCHMARKS.md). 0.05 takes a 2 cm gap under a 0.7 m panel.
inline constexpr double kContactShadowGapRatio = 0.05;

/// Cuts that would leave a piece narrower than this fraction of the scene's diagonal are not made
/// (the piece stays whole): no slivers, and the pieces still tile the patch exactly.
inline constexpr double kContactMinPieceWidth = 1e-4;

/// What splitPatchesAtContacts did.
struct ContactSplitReport {
  size_t patchesSplit = 0;  ///< patches replaced by pieces
  size_t piecesMade = 0;    ///< pieces that replaced them
};

/// Replaces every patch shadowed by parallel patches (kContactShadowGapRatio) with the convex
/// pieces of the cuts along the shadows' outlines, in place (a patch's pieces take its position
/// in `scene.patches`, in order; ids of later patches shift). Pieces keep the patch's plane,
/// material and source face, and tile it exactly. Geometry is unchanged: only the patch
/// boundaries follow the contact lines, so visibility and lighting are the same physics with
/// better elements. Shadows are the input patches, not their pieces, so a second pass can still
/// cut along edges that a first pass made inside a shadow. Adds the counts to `scene.report`.
ContactSplitReport splitPatchesAtContacts(Scene& scene);

}  // namespace gv
