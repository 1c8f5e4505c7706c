// Writing a subdivision for viewing and its §7.1 statistics: cells and portals as OBJ groups,
// stats as JSON. Paper §3, §7.1.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "bsp/subdivision.h"

namespace gv {

/// Writes every cell's boundary faces as OBJ, one group `cell_<id>` per cell, faces
/// counter-clockwise seen from outside the cell. Throws InputError when the file cannot be written.
void writeCellsObj(const Subdivision& sub, const std::string& path);

/// Writes every portal as an OBJ face in group `portal_<id>_<back>_<front>`, counter-clockwise
/// seen from its front cell. Throws InputError when the file cannot be written.
void writePortalsObj(const Subdivision& sub, const std::string& path);

/// Writes the cells and portals as a Quake portal file (PRT1: leaf i = cell i, each portal as
/// `points back front (x y z) ...`, its winding's counter-clockwise normal pointing from the
/// first cell into the second, as quake/prt_file.h reads qbsp's files), so that `globalvis pvs`
/// and Quake's `vis` tools can run on the cells of any scene. Throws InputError when the file
/// cannot be written.
void writePortalsPrt(const Subdivision& sub, const std::string& path);

/// The §7.1 figures: `patches`, `planes`, `bsp_nodes`, `bsp_depth`, `leaf_cells`, `portals`,
/// `mean_boundary_faces_per_cell`, `mean_coaffine_patches_per_cell`, `mean_portals_per_cell`,
/// `bsp_seconds`, `portal_seconds`.
nlohmann::json statsJson(const SubdivisionStats& stats);

}  // namespace gv
