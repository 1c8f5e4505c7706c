// Faces that no air reaches, and coincident twins: what a level's brush soup holds beside the
// surfaces a renderer shows. Decided on a BSP split by every patch plane, whose cells are each
// wholly inside or wholly outside every closed solid, by the generalized winding number of the
// patches at each cell (Jacobson, Kavan & Sorkine-Hornung 2013, "Robust inside-outside
// segmentation using generalized winding numbers"). Real levels: Quake 3 brush sides inside
// other brushes, zero-thickness two-sided contacts, coplanar duplicates (issue #18).
#pragma once

#include <cstddef>

#include "scene/scene.h"
#include "scene/winding_number.h"

namespace gv {

/// A cell whose winding number reaches this is inside a closed solid. Outward-facing closed
/// solids (brushes, boxes) count +1 inside; inward-facing shells (a 2.5D sector's floor,
/// ceiling and walls) count -1, so their air is never taken for solid. Open surfaces give
/// fractions: just behind a lone one-sided quad it tends to +1/2, the usual threshold for a soup,
/// so the threshold sits above it: a face is dropped only inside a solid, never for lying behind
/// an open sheet (dropping too little costs time; dropping a visible face would be a leak).
inline constexpr double kSolidWindingNumber = 0.75;

struct HiddenFaceOptions {
  /// Replace a patch of which only a part is hidden or covered by its remaining pieces (cut
  /// along the all-planes BSP: often many). Off: such a patch is kept whole.
  bool cutPartly = false;
};

struct HiddenFaceReport {
  size_t hidden = 0;            ///< patches dropped whole: their front looks only into solid
  size_t partlyHidden = 0;      ///< patches cut to the parts whose front looks into air
  size_t coincident = 0;        ///< patches dropped whole as a same-facing twin of an earlier one
  size_t partlyCoincident = 0;  ///< patches cut where an earlier same-facing patch covers them
  size_t piecesOut = 0;         ///< pieces the cut patches became
  size_t partlyKept = 0;        ///< partly hidden or covered patches kept whole (!cutPartly)
  size_t frontBeyondAir = 0;    ///< patches out with a Scene::beyondAirBounds box
  bool shells = false;          ///< air is inside inward-facing shells (a 2.5D sector level)
  bool changed() const { return hidden + partlyHidden + coincident + partlyCoincident > 0; }
};

/// The scene without what no sightline from air can reach:
/// - the parts of patches whose front looks into a closed solid (inside another brush, the
///   hidden side of two solids in contact) are removed;
/// - where two patches lie on one plane facing the same way and overlap (coincident or
///   overlapping coplanar faces), the earlier patch keeps the overlap and the later loses it.
/// A patch left with nothing is dropped; one left with a part is kept whole, or replaced by its
/// remaining convex pieces (same material and source face) with `cutPartly`. Patches keep their
/// order, so a clean scene comes back unchanged but for Scene::beyondAirBounds, which is set for
/// every patch out: the box of the parts of its front that look into cells no air reaches.
/// `report` (if given) counts what happened.
Scene removeHiddenFaces(const Scene& scene, const HiddenFaceOptions& options = {},
                        HiddenFaceReport* report = nullptr);

}  // namespace gv
