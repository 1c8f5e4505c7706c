// `globalvis pvs MAP.prt -o PVS.txt`: the potentially visible set of a Quake portal file by
// stabbing-line search over portal sequences (paper §4 applied to qbsp's leafs), written one line
// per leaf: `L n v1 ... vn` (0-based leaf ids, ascending, L itself included).
#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "quake/prt_file.h"
#include "quake/prt_portal_graph.h"
#include "util/input_error.h"
#include "util/progress_bar.h"
#include "util/timing.h"
#include "visibility/cell_pvs.h"

namespace gv::cli {

Action addPvsCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "pvs",
      "Leaf-to-leaf potentially visible set of a Quake portal file (.prt, PRT1 or PRT2); "
      "writes one line per leaf: L n v1 ... vn");
  struct State {
    std::string input, output;
    bool serial = false, quiet = false, noLp = false, backClip = false, json = false,
         witness = false, closed = false, bothSides = false;
    double targetChecks = CellPvsOptions{}.targetCheckRatio;
  };
  auto s = std::make_shared<State>();
  cmd->add_option("portals", s->input, "Portal file written by qbsp (.prt)")->required();
  cmd->add_option("-o,--output", s->output, "PVS text file to write")->required();
  cmd->add_flag("--serial", s->serial, "One thread (the output is the same either way)");
  cmd->add_flag("-q,--quiet", s->quiet,
                "No progress bar on stderr (there is none unless it is a terminal)");
  cmd->add_flag("--json", s->json, "Print the statistics as JSON on stdout");
  cmd->add_flag("--no-lp", s->noLp,
                "Decide by separating-plane clipping only (faster, looser; still conservative)");
  cmd->add_flag("--back-clip", s->backClip,
                "Also clip the first portal by the separating planes of the last two (vis's back "
                "clip): prunes more sequences, costs more per sequence");
  cmd->add_flag("--closed-portals", s->closed,
                "Keep sightlines that only touch portal edges (the default drops lines clearing "
                "no edge by 1e-9 of the map's size: more leafs visible, slower)");
  cmd->add_flag("--witness", s->witness,
                "Also look for exact witness lines (counts 'stabbed' sequences; same PVS, slower)");
  cmd->add_flag("--both-sides", s->bothSides,
                "Find every leaf pair from both of its leafs and keep it only if both found it "
                "(the tightest PVS, 0.1-0.6 % smaller; 3-45 % slower)");
  cmd->add_option("--target-checks", s->targetChecks,
                  "Target checks (vis's -targetchecks): tests of the portals into the cells a "
                  "search might see, to drop those no line can enter, at most this many per "
                  "sequence pushed (default 100; 0: none)")
      ->check(CLI::Range(0.0, 100.0));
  return [s] {
    const auto t0 = Clock::now();
    auto elapsed = [&] { return secondsSince(t0); };
    const PrtFile prt = readPrtFile(s->input);
    CellPvsOptions options;
    options.parallel = !s->serial;
    options.stabbing.useLinearProgram = !s->noLp;
    options.stabbing.backClip = s->backClip;
    options.stabbing.seekWitness = s->witness;
    options.bothSides = s->bothSides;
    options.targetCheckRatio = s->targetChecks;
    if (s->closed) options.stabbing.blockedBelow = -kStabbingLpMargin;
    ProgressBar bar("pvs (directed portals)", !s->quiet && stderrIsTerminal());
    options.progress = bar.callback();
    // The search runs over the clusters; the file is written per leaf.
    const CellPvsResult pvs = computeCellPvs(portalGraphOf(prt), options);
    bar.finish();
    const ClusterLeafRows leafs = clusterLeafRows(prt, pvs.visibleCells);

    std::FILE* out = std::fopen(s->output.c_str(), "w");
    if (!out) throw InputError(s->output, 0, "cannot write");
    // Each cluster's row formatted once (" n v1 ... vn\n"), then written after the id of every
    // leaf of the cluster: e3m4 formats 1.0 M numbers instead of 6.3 M.
    std::vector<std::string> rowText(leafs.rows.size());
    for (size_t c = 0; c < leafs.rows.size(); ++c) {
      std::string& text = rowText[c];
      text = fmt::format(" {}", leafs.rows[c].size());
      for (uint32_t v : leafs.rows[c]) {
        const fmt::format_int digits(v);
        text += ' ';
        text.append(digits.data(), digits.size());
      }
      text += '\n';
    }
    for (size_t l = 0; l < prt.leafCount; ++l) {
      const fmt::format_int id(l);
      std::fwrite(id.data(), 1, id.size(), out);
      const std::string& text = rowText[static_cast<size_t>(prt.leafCluster[l])];
      std::fwrite(text.data(), 1, text.size(), out);
    }
    const bool ok = std::ferror(out) == 0;
    if (std::fclose(out) != 0 || !ok) throw InputError(s->output, 0, "cannot write");

    const StabbingStats& st = pvs.stabbing;
    if (s->json) {
      const nlohmann::json j = {{"portals_file", s->input},
                                {"output", s->output},
                                {"prt_version", prt.version},
                                {"leafs", prt.leafCount},
                                {"clusters", pvs.cellCount},
                                {"portals", pvs.portalCount},
                                {"mean_leafs_visible", leafs.meanLeafsVisible},
                                {"mean_clusters_might_see", pvs.meanCellsMightSee},
                                {"sequences_searched", pvs.sequencesSearched},
                                {"target_tests", pvs.targetTests},
                                {"target_cells_dropped", pvs.targetCellsDropped},
                                {"stabbing_tests", st.tests},
                                {"blocked_by_clipping", st.blockedByClipping},
                                {"blocked_by_lp", st.blockedByLp},
                                {"stabbed", st.stabbed},
                                {"unresolved", st.unresolved},
                                {"lp_numerical_failures", st.lpNumericalFailures},
                                {"degenerate_portals", st.degeneratePortals},
                                {"lp_solves", st.lpSolves},
                                {"lp_shortcuts", st.lpShortcuts},
                                {"lp_deferred", st.lpDeferred},
                                {"deferred_blocked", st.deferredBlocked},
                                {"simplex_fallbacks", st.simplexFallbacks},
                                {"one_sided_pairs_dropped", pvs.oneSidedPairsDropped},
                                {"settled_pairs", pvs.settledPairs},
                                {"self_portals_skipped", prt.selfPortalsSkipped},
                                {"seconds", elapsed()},
                                {"flood_seconds", pvs.floodSeconds},
                                {"search_seconds", pvs.searchSeconds}};
      fmt::print("{}\n", j.dump(2));
      return 0;
    }
    fmt::print("PRT{}: leafs {}  clusters {}  portals {}\n", prt.version, prt.leafCount,
               pvs.cellCount, pvs.portalCount);
    fmt::print("mean leafs visible {:.1f}  (might-see flood: {:.1f} clusters per cluster)\n",
               leafs.meanLeafsVisible, pvs.meanCellsMightSee);
    fmt::print(
        "sequences {}  stabbing tests {}: blocked by clipping {}, by LP {}; "
        "stabbed {}, unresolved (kept) {}\n",
        pvs.sequencesSearched, st.tests, st.blockedByClipping, st.blockedByLp, st.stabbed,
        st.unresolved);
    if (st.lpNumericalFailures || st.degeneratePortals || pvs.oneSidedPairsDropped ||
        prt.selfPortalsSkipped)
      fmt::print(
          "LP breakdowns {}  degenerate portals {}  one-sided pairs dropped {}  "
          "self portals skipped {}\n",
          st.lpNumericalFailures, st.degeneratePortals, pvs.oneSidedPairsDropped,
          prt.selfPortalsSkipped);
    fmt::print("seconds {:.2f} (flood {:.2f}, search {:.2f}); wrote {}\n", elapsed(),
               pvs.floodSeconds, pvs.searchSeconds, s->output);
    return 0;
  };
}

}  // namespace gv::cli
