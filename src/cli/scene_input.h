// The scene every pipeline command reads: the file's patches (input/load_scene.h), for radiosity
// cut at contacts (scene/contact_split.h), then without the faces no air reaches and coincident
// twins (bsp/hidden_faces.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "scene/scene.h"

namespace gv::cli {

struct SceneInputOptions {
  bool contactSplit = false;  ///< radiosity and photons: cut patches at contacts, and partly
                              ///< hidden patches to their parts in air
  bool keepHidden = false;    ///< keep faces inside closed solids and coincident twins
};

/// The `--keep-hidden` flag of every command that reads a scene through loadPipelineScene.
void addKeepHiddenFlag(CLI::App& cmd, bool& keepHidden);

/// Loads `path` and prepares it as `options` say; the import report counts every step.
Scene loadPipelineScene(const std::string& path, const SceneInputOptions& options);

}  // namespace gv::cli
