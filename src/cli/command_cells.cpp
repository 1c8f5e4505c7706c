// `globalvis cells SCENE -o DIR`: the spatial subdivision (paper §3) for viewing, with the §7.1
// figures: DIR/cells.obj, DIR/portals.obj, DIR/stats.json, and the cell graph as a Quake portal
// file, DIR/cells.prt (for `globalvis pvs` or Quake's `vis`).
#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "bsp/subdivision.h"
#include "bsp/subdivision_io.h"
#include "cli/commands.h"
#include "cli/output_files.h"
#include "cli/scene_input.h"
#include "util/input_error.h"
#include "util/progress_bar.h"

namespace gv::cli {

Action addCellsCommand(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("cells",
                         "Build the BSP cells and portals of a scene (paper §3); write cells.obj, "
                         "portals.obj, cells.prt (the cell graph as a Quake PRT1 portal file) "
                         "and stats.json into a directory");
  struct State {
    std::string scene, output;
    BspOptions options;
    bool keepHidden = false;
    bool json = false;
  };
  auto s = std::make_shared<State>();
  cmd->add_option(
         "scene", s->scene,
         "Scene file (.obj with .mtl, Quake .map, or a mesh Assimp reads: .ply, .gltf, .glb ...)")
      ->required();
  cmd->add_option("-o,--output", s->output, "Output directory (created if missing)")->required();
  cmd->add_option("--min-coverage", s->options.minCoverage,
                  "Stop rule: split a cell on a plane only if its patches cover at least this "
                  "fraction of the cell's section (0 = split on every patch)")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--max-candidates", s->options.maxCandidates,
                  "Planes scored per cell (largest patch area first)")
      ->check(CLI::Range(1, 1'000'000));
  cmd->add_flag("--json", s->json, "Print the statistics as JSON on stdout");
  addKeepHiddenFlag(*cmd, s->keepHidden);
  return [s] {
    const Scene scene = loadPipelineScene(s->scene, {false, s->keepHidden});
    ProgressBar bar("BSP");
    if (bar.enabled()) s->options.progress = [&bar](double f) { bar.update(f); };
    const Subdivision sub = buildSubdivision(scene, s->options);
    bar.finish();
    const std::filesystem::path dir = makeOutputDirectory(s->output);
    writeCellsObj(sub, (dir / "cells.obj").string());
    writePortalsObj(sub, (dir / "portals.obj").string());
    writePortalsPrt(sub, (dir / "cells.prt").string());
    writeJsonFile(statsJson(sub.stats), dir / "stats.json");
    if (s->json) {
      nlohmann::json j = statsJson(sub.stats);
      j["scene"] = s->scene;
      j["output"] = dir.string();
      fmt::print("{}\n", j.dump(2));
      return 0;
    }
    const SubdivisionStats& st = sub.stats;
    fmt::print("patches {}  planes {}  leaf cells {}  portals {}\n", st.patches, st.planes,
               st.cells, st.portals);
    fmt::print("per cell: {:.2f} boundary faces, {:.2f} coaffine patches, {:.2f} portals\n",
               st.meanFacesPerCell, st.meanCoaffinePatchesPerCell, st.meanPortalsPerCell);
    fmt::print("BSP {:.3f} s, portals {:.3f} s; wrote {}\n", st.bspSeconds, st.portalSeconds,
               dir.string());
    return 0;
  };
}

}  // namespace gv::cli
