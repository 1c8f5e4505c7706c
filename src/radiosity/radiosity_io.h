// Writing a radiosity solution: per-patch radiosity (the output contract of DESIGN.md), the
// paper's Table 1 statistics (§7.4) as JSON, and the refined mesh as a coloured PLY.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "radiosity/hierarchical_radiosity.h"

namespace gv {

/// DIR/radiosity.txt: `#` comment lines, then one line `patch R G B` per patch in patch order
/// (= face order of patches.obj), the area-weighted mean radiosity of the patch. Throws
/// InputError when the file cannot be written.
void writeRadiosityTxt(const RadiosityResult& result, const std::string& path);
/// One line per patch, `patch R G B`, after `#` comment lines (the last are `# header`): the
/// format of radiosity.txt, also used for the photon reference and its standard errors.
void writePatchRgbTxt(const std::vector<Rgb>& values, const std::string& header,
                      const std::string& path);

/// Table 1 of the paper for this run: per round the links by class (V/P/I with percentages of
/// the links created), elements, interactions, rays and seconds; plus totals and the options.
nlohmann::json radiosityStatsJson(const RadiosityStats& stats, const RadiosityOptions& options,
                                  int raysPerLink);

/// The leaf elements as an ASCII PLY mesh with per-vertex colours: each vertex gets the
/// area-weighted mean radiosity of the leaves of its patch that touch it (smooth shading within
/// a patch, sharp between patches). Tone mapping: radiosity divided by `white` (default: the
/// 99th percentile of leaf radiosity by area, so a few bright lights do not darken the rest),
/// clamped to 1, then sRGB-like gamma 1/2.2, to 8 bits. Also stores the raw linear radiosity as
/// float properties `radiosity_r/g/b`. Throws InputError when the file cannot be written.
void writeElementsPly(const RadiosityResult& result, const std::string& path, double white = 0);

}  // namespace gv
