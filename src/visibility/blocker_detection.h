// Blocker lists (paper §5): the pairs that interact (seen front to front from both ends by the
// patch searches) and, per pair, the patches seen from S or from R that meet conv(S, R).
#pragma once

#include <vector>

#include "geometry/tolerance.h"
#include "scene/scene.h"
#include "visibility/patch_search.h"
#include "visibility/propagation.h"
#include "visibility/visibility_graph.h"

namespace gv {

/// The interactions of `scene` from the seen lists of searchPatches, with their blocker lists,
/// handed on in (s, r) order (to options.interactionSink, else into graph.interactions). The
/// first patch a segment from S meets lies in a cell the search from S reached through the
/// portals that segment crossed, and the segment crosses that patch after those portals, so that
/// search saw it: the lists hold every real blocker. Fills the pair and blocker fields of
/// graph.stats, blockerSeconds, and the shaft-culling sample; `threads` as resolved by
/// computeVisibility; options' blockerProgress and deadline apply.
void detectBlockers(const Scene& scene, const std::vector<PatchSearchResult>& seen,
                    const Tolerance& tol, int threads, const PropagationOptions& options,
                    VisibilityGraph& graph);

}  // namespace gv
