// The data the web viewer shows (paper §7.4-§7.5): patches, materials, radiosity, cells,
// portals and interactions of a run, as the compact JSON embedded in viewer.html.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "report/run_files.h"

namespace gv {

/// Limits that keep the page a sane size on big runs.
struct ViewerDataOptions {
  /// elements.ply is embedded (smooth radiosity shading) only up to this many vertices; above
  /// it the page shades each patch by its radiosity.txt value.
  size_t maxElementVertices = 400'000;
  /// Blocker lists are embedded only while their total length is at most this; above it the
  /// page keeps each pair's blocker count but not the lists (tubes still show, blockers not).
  size_t maxBlockerEntries = 2'000'000;
};

/// The viewer's JSON (format "globalvis-viewer-1"; read by web/src/scene_data.js). Needs
/// `files.patchesObj`; every other file is optional. Coordinates are rounded to 1e-6 of the
/// scene diagonal. Throws InputError on unreadable or inconsistent files (a radiosity.txt or
/// visibility.txt naming patches that patches.obj does not have).
nlohmann::json viewerDataJson(const RunFiles& files, const std::string& title,
                              const ViewerDataOptions& options = {});

}  // namespace gv
