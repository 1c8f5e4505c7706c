// `globalvis vis SCENE -o DIR`: cells, propagation and blocker lists (paper §3–§5); writes the
// DESIGN.md contract: DIR/patches.obj (+.mtl), DIR/visibility.txt, DIR/stats.json.
#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "bsp/subdivision.h"
#include "bsp/subdivision_io.h"
#include "cli/commands.h"
#include "cli/output_files.h"
#include "cli/scene_input.h"
#include "cli/thread_limit.h"
#include "scene/scene_io.h"
#include "util/input_error.h"
#include "util/progress_bar.h"
#include "visibility/propagation.h"
#include "visibility/visibility_graph.h"

namespace gv::cli {

Action addVisCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "vis",
      "Conservative patch-to-patch visibility with blocker lists (paper §3-§5); writes "
      "patches.obj, visibility.txt and stats.json into a directory");
  struct State {
    std::string scene, output;
    BspOptions bsp;
    PropagationOptions propagation;
    bool keepHidden = false;
    bool json = false, contactSplit = false;
  };
  auto s = std::make_shared<State>();
  s->bsp.minCoverage = kVisibilityMinCoverage;
  cmd->add_option(
         "scene", s->scene,
         "Scene file (.obj with .mtl, Quake .map, or a mesh Assimp reads: .ply, .gltf, .glb ...)")
      ->required();
  cmd->add_option("-o,--output", s->output, "Output directory (created if missing)")->required();
  cmd->add_option("--threads", s->propagation.threads, "Worker threads (0 = all cores)")
      ->check(CLI::Range(0, 1024));
  auto* coverage =
      cmd->add_option("--min-coverage", s->bsp.minCoverage,
                      "BSP stop rule (see `globalvis cells --help`); 0 splits on every patch "
                      "plane. Default: the coarsest of 0.3, 0.1, 0.03, 0.01, 0 whose cells hold "
                      "at most 1/16 of the patches' area inside them (bsp/subdivision.h)")
          ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--cell-budget", s->propagation.cellSequenceBudget,
                  "Portal sequences one cell-to-cell search (one directed portal) may test; past "
                  "it, the branches not yet explored are answered with every cell they might "
                  "reach (0 = no limit; conservative either way)")
      ->capture_default_str();
  cmd->add_option("--patch-budget", s->propagation.patchSequenceBudget,
                  "Stabbing tests one source patch's search may run; past it, the branches not "
                  "yet explored are answered with every patch they might reach (0 = no limit; "
                  "conservative either way). Default `auto`: the larger of 1000 and 1.2e7 / "
                  "patches, so that small scenes get longer, tighter searches")
      ->transform(
          CLI::Transformer({{"auto", std::to_string(kAutoPatchSequenceBudget)}}).description(""))
      ->type_name("UINT|auto")
      ->default_str("auto");
  cmd->add_option("--target-checks", s->propagation.cellTargetChecks,
                  "Target checks in the cell-to-cell search (as `pvs --target-checks`): tests "
                  "per sequence pushed spent on dropping cells no line can enter (0 = none)")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  cmd->add_flag("--no-cell-merge{false}", s->propagation.mergeConvexCells,
                "Search the BSP's cells as they are, without first merging neighbours whose "
                "union is convex and joining the cells no patch faces into (conservative either "
                "way; for measuring what the merge saves)");
  cmd->add_flag("--outside-slivers", s->propagation.outsideSlivers,
                "Also search from the slivers of patches that end at a one-sided wall with the "
                "level's outside behind it (rays crossing the wall within the model tolerance "
                "of their start): conservative at the contact distance 1e-5 on sector levels, "
                "at 2.4-4.5 times the pairs");
  cmd->add_flag("--json", s->json, "Print the statistics as JSON on stdout");
  addKeepHiddenFlag(*cmd, s->keepHidden);
  cmd->add_flag("--contact-split", s->contactSplit,
                "Cut patches along the outlines of the patches resting on them first, as "
                "`radiosity` does (scene/contact_split.h): more patches, much shorter blocker "
                "lists, and the same patches as a radiosity run");
  return [s, coverage] {
    const ThreadLimit threadLimit(s->propagation.threads);
    const Scene scene = loadPipelineScene(s->scene, {s->contactSplit, s->keepHidden});
    for (const std::string& w : scene.report.warnings) fmt::print(stderr, "warning: {}\n", w);
    ProgressBar bspBar("BSP");
    if (bspBar.enabled()) s->bsp.progress = [&bspBar](double f) { bspBar.update(f); };
    const Subdivision sub = coverage->count() > 0 ? buildSubdivision(scene, s->bsp)
                                                  : buildVisibilitySubdivision(scene, s->bsp);
    bspBar.finish();
    ProgressBar cellBar("visibility (per source cell)");
    ProgressBar visBar("visibility (per source patch)");
    s->propagation.cellProgress = cellBar.callback();
    s->propagation.progress = visBar.callback();
    ProgressBar blockerBar("blocker lists (per source patch)");
    s->propagation.blockerProgress = blockerBar.callback();
    // visibility.txt is written while the blocker lists are built (they need not fit in memory),
    // under a temporary name until complete: a failed run leaves no truncated (or stale)
    // visibility.txt.
    const std::filesystem::path dir = makeOutputDirectory(s->output);
    const std::filesystem::path visPath = dir / "visibility.txt";
    const std::filesystem::path partPath = dir / "visibility.txt.part";
    std::filesystem::remove(visPath);
    VisibilityTxtWriter writer(partPath.string());
    s->propagation.interactionSink = [&writer](const BlockerLists& lists) { writer.add(lists); };
    const VisibilityGraph graph = computeVisibility(scene, sub, s->propagation);
    visBar.finish();
    writer.close();
    std::filesystem::rename(partPath, visPath);
    writeObj(scene, (dir / "patches.obj").string());
    const nlohmann::json stats = {{"scene", s->scene},
                                  {"subdivision", statsJson(sub.stats)},
                                  {"visibility", visibilityStatsJson(graph.stats)}};
    writeJsonFile(stats, dir / "stats.json");
    if (s->json) {
      fmt::print("{}\n", stats.dump(2));
      return 0;
    }
    const VisibilityStats& v = graph.stats;
    const double pairs = double(v.patches) * double(v.patches - 1) / 2;
    const uint64_t listed = v.pairsVisible + v.pairsPartial;
    fmt::print(
        "patches {}  cells {}  portals {}  (stop rule {}, {:.1f} % of the patch area inside "
        "cells{}; BSP {:.3f} s, portals {:.3f} s)\n",
        sub.stats.patches, sub.stats.cells, sub.stats.portals, sub.stats.minCoverage,
        100 * sub.stats.interiorAreaFraction,
        builtOfClosedSolids(sub.stats) ? ", built of closed solids" : "", sub.stats.bspSeconds,
        sub.stats.portalSeconds);
    if (v.cellsBeforeMerge != v.cells)
      fmt::print(
          "searched {} cells and {} portals (of {} and {}: neighbours with a convex union, and "
          "the cells no patch faces into, merged; {} portals before coplanar pieces of one "
          "opening were joined)\n",
          v.cells, v.portals, v.cellsBeforeMerge, v.portalsBeforeMerge, v.portalsBeforeJoin);
    fmt::print("pairs listed {} of {:.0f} ({:.2f} %): VISIBLE {}, PARTIAL {} ({:.1f} %)\n", listed,
               pairs, pairs > 0 ? 100.0 * double(listed) / pairs : 0.0, v.pairsVisible,
               v.pairsPartial, listed ? 100.0 * double(v.pairsPartial) / double(listed) : 0.0);
    fmt::print(
        "stabbing tests: {} cell-level, {} patch-level ({} unresolved); mean sequence {:.2f}\n",
        v.cellStabbingTests, v.patchStabbingTests, v.unresolvedStabbing, v.meanSequenceLength);
    if (v.cellSearchesOverBudget + v.patchSearchesOverBudget > 0)
      fmt::print(
          "searches over budget (their unexplored branches answered with all they might "
          "reach): {} of {} directed portals (--cell-budget), {} of {} source patches "
          "(--patch-budget {})\n",
          v.cellSearchesOverBudget, 2 * v.portals, v.patchSearchesOverBudget, v.patches,
          v.patchBudget);
    if (v.thinWallSlivers > 0)
      fmt::print("pieces of patches searched across one-sided walls they end against: {}{}\n",
                 v.thinWallSlivers,
                 v.beyondAirSlivers > 0
                     ? fmt::format(" ({} into the outside, looking for {} parts of faces "
                                   "looking out of the air)",
                                   v.beyondAirSlivers, v.beyondAirFragments)
                     : "");
    if (v.acrossPortalPieces > 0)
      fmt::print("pieces of patches searched across openings lying along them: {}\n",
                 v.acrossPortalPieces);
    if (v.acrossThinSlabPieces > 0)
      fmt::print("pieces of patches searched across sealed slabs thinner than the tolerance: {}\n",
                 v.acrossThinSlabPieces);
    if (v.pairsHiddenByOne > 0)
      fmt::print("pairs dropped as hidden whole behind one of their blockers: {}\n",
                 v.pairsHiddenByOne);
    if (v.pairsHiddenByWall > 0)
      fmt::print("pairs dropped as hidden by blockers lying in one plane together: {}\n",
                 v.pairsHiddenByWall);
    fmt::print("blockers per PARTIAL pair {:.2f} (shaft cull {:.2f})\n", v.meanBlockersPerPartial,
               v.meanShaftCullPerPartial);
    fmt::print(
        "visibility {:.3f} s on {} threads (cells {:.3f}, patches {:.3f}, blockers {:.3f}); "
        "wrote {}\n",
        v.seconds, v.threads, v.cellSeconds, v.patchSeconds, v.blockerSeconds, dir.string());
    return 0;
  };
}

}  // namespace gv::cli
