#include "cli/scene_input.h"

#include "bsp/hidden_faces.h"
#include "scene/contact_split.h"
#include "input/load_scene.h"

namespace gv::cli {
namespace {

void dropHidden(Scene& scene) {
  HiddenFaceReport h;
  Scene cleaned = removeHiddenFaces(scene, {}, &h);
  ImportReport& r = cleaned.report;
  r.hiddenDropped += h.hidden;
  r.coincidentDropped += h.coincident;
  r.partlyHiddenKept = h.partlyKept;
  scene = std::move(cleaned);
}

}  // namespace

void addKeepHiddenFlag(CLI::App& cmd, bool& keepHidden) {
  cmd.add_flag("--keep-hidden", keepHidden,
               "Keep the faces no air reaches (inside closed solids) and coincident same-facing "
               "twins, which are dropped by default (bsp/hidden_faces.h)");
}

Scene loadPipelineScene(const std::string& path, const SceneInputOptions& options) {
  Scene scene = loadScene(path);
  if (!options.keepHidden) dropHidden(scene);
  if (options.contactSplit) {
    splitPatchesAtContacts(scene);
    // The split cuts overlapping coplanar patches along each other's outlines into identical
    // pieces: twins, of which one is kept (a photon lands on one of them, not on both).
    if (!options.keepHidden) dropHidden(scene);
  }
  return scene;
}

}  // namespace gv::cli
