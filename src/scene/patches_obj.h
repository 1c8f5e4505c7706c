// Reading back a `patches.obj` that globalvis wrote (`vis`, `radiosity`, `photons`): the file
// the output contract's patch ids refer to, face k = patch k.
#pragma once

#include <string>
#include <string_view>

#include "scene/scene.h"

namespace gv {

/// importObj, then the check that every face came back as exactly one patch: a face dropped as
/// degenerate, split as non-convex or triangulated as non-planar would shift the ids, so such a
/// file is not a patch file and this throws InputError naming it. `writer` names the command the
/// file should come from in that message (e.g. "`globalvis vis`").
Scene importPatchesObj(const std::string& path, std::string_view writer);

}  // namespace gv
