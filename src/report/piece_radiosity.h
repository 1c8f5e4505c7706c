// Radiosity per patch of one patch file from radiosity per patch of a finer one: `radiosity` cuts
// patches along contacts (scene/contact_split.h), `vis` does not, and the viewer shows both runs
// on the vis patches.
#pragma once

#include <optional>
#include <vector>

#include "scene/scene.h"

namespace gv {

/// The area-weighted mean of `pieceRadiosity` over the pieces of each patch of `patches`, where
/// `pieces` is `patches` with some patches replaced in place by pieces tiling them (what
/// splitPatchesAtContacts makes: the pieces of patch k come after those of patch k - 1 and lie
/// in its plane). Nullopt when `pieces` is not such a refinement of `patches` (a piece outside
/// the patch its position says, or patches left without pieces).
std::optional<std::vector<Rgb>> radiosityOnPatches(const Scene& patches, const Scene& pieces,
                                                   const std::vector<Rgb>& pieceRadiosity);

}  // namespace gv
