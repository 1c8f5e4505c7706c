// Patches in contact: a patch lying on another's plane and overlapping it (a box resting on a
// floor, a wall end against another wall) covers part of it with no gap. Propagation's blocker
// lists (paper §5) are built from patches *seen* from S or R, which misses such a zero-distance
// cover; the tubes add them (§6) so that covered parts of elements get no light.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace gv {

/// For each patch p, the patches b != p with contactCover(p, b) != None (tube.h), sorted.
/// Candidates come from a sweep over bounding boxes, so the cost is near-linear for scenes whose
/// patches' boxes overlap little.
std::vector<std::vector<uint32_t>> contactBlockers(const Scene& scene);

}  // namespace gv
