// Coincident patches: patches with the same vertices facing the same way, as a level's brush soup
// holds them where two brushes share a side (`--keep-hidden` keeps them). A photon lands on one
// of them only, so a comparison with light tracing must take each such group as one surface.
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace gv {

/// Per patch, the id of the first patch of its group of coincident patches (itself when it has
/// no twin). Coincident: the same number of vertices, the same vertex set once every coordinate is
/// rounded to the scene's plane-offset tolerance (geometry/tolerance.h), and normals on the same
/// side (so two faces back to back are two surfaces). Found through a hash of the rounded,
/// sorted vertices: linear in the patches. Two vertices within the tolerance that round to
/// different grid points are not matched (a limit of hashing; patches of one input share their
/// vertices exactly).
std::vector<uint32_t> coincidentPatchGroups(const Scene& scene);

}  // namespace gv
