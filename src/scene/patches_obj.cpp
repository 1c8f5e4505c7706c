// The patch-file check of patches_obj.h.
#include "scene/patches_obj.h"

#include "scene/scene_io.h"
#include "util/input_error.h"

namespace gv {

Scene importPatchesObj(const std::string& path, std::string_view writer) {
  // Slivers kept: the BSP and the CSG of .map files make pieces thinner than the model tolerance
  // (e3m4.map: 33), which user input would lose, and dropping them would renumber the patches.
  Scene scene = importObj(path, /*keepSlivers=*/true);
  const ImportReport& r = scene.report;
  if (r.droppedDegenerate || r.splitNonConvex || r.triangulatedNonPlanar)
    throw InputError(path, 0,
                     "not a patch file written by " + std::string(writer) +
                         " (its faces are not all convex planar patches, so face k would not be "
                         "patch k)");
  return scene;
}

}  // namespace gv
