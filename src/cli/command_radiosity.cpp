// `globalvis radiosity SCENE -o DIR`: hierarchical radiosity (HSA91; paper §6, §7.4) with a
// choice of link visibility; writes patches.obj(+mtl), radiosity.txt, stats.json, elements.ply.
#include <fmt/core.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "bsp/subdivision.h"
#include "cli/commands.h"
#include "cli/output_files.h"
#include "cli/scene_input.h"
#include "cli/thread_limit.h"
#include "radiosity/blocker_visibility.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/radiosity_io.h"
#include "radiosity/radiosity_quality.h"
#include "radiosity/ray_visibility.h"
#include "radiosity/shaft_visibility.h"
#include "raycast/embree_scene.h"
#include "render/radiosity_pictures.h"
#include "scene/scene_io.h"
#include "util/input_error.h"
#include "util/peak_memory.h"
#include "util/progress_bar.h"
#include "util/timing.h"
#include "visibility/patch_cell_reach.h"
#include "visibility/propagation.h"

namespace gv::cli {

Action addRadiosityCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "radiosity",
      "Hierarchical radiosity (Hanrahan, Salzman & Aupperle 1991); write "
      "patches.obj, radiosity.txt, stats.json and elements.ply into a directory");
  struct State {
    std::string scene, output, visibility = "rays";
    std::string quality{radiosityQualityLevel(kDefaultRadiosityQuality).name};
    int rays = 16;
    bool quiet = false, json = false, customQuality = false;
    RadiosityOptions options;
    std::string camera, imageSize = "800x600";
    bool noPictures = false, flat = false, noContactSplit = false, keepHidden = false;
    bool noCellCulling = false, sceneThreshold = false;
    BspOptions bsp;  // blockers mode: the subdivision its visibility graph is computed on
  };
  auto s = std::make_shared<State>();
  s->bsp.minCoverage = kVisibilityMinCoverage;  // the same cells as `vis`
  s->options.maxLinks = 0;  // `auto` unless given: from the machine's memory (see below)
  cmd->add_option("scene", s->scene,
                  "Scene file (.obj with .mtl: Kd reflectance, Ke emission; or a Quake .map, or a "
                  "mesh Assimp reads)")
      ->required();
  cmd->add_option("-o,--output", s->output, "Output directory (created if missing)")->required();
  cmd->add_option("--visibility", s->visibility,
                  "Link visibility: rays = N jittered rays per link against the whole scene "
                  "(Embree), all facing patch pairs linked (HSA91); shaft = the same rays tested "
                  "only against the patches meeting the hull of the two elements (Haines & "
                  "Wallace); blockers = links only for the pairs of the conservative visibility "
                  "graph (BSP + propagation), blocker lists reclassified in linespace on "
                  "refinement, rays only for PARTIAL links and only against their blockers "
                  "(paper §6)")
      ->check(CLI::IsMember({"rays", "shaft", "blockers"}));
  cmd->add_flag("--no-cell-culling", s->noCellCulling,
                "rays mode: link every pair of patches, instead of only the pairs whose cells may "
                "see each other (the BSP and cell-to-cell stage of `vis`, conservative; no link "
                "or ray between rooms that cannot see each other; scenes of 1000 patches or "
                "more)");
  cmd->add_flag("--scene-threshold", s->sceneThreshold,
                "Judge every link against the whole scene's emitted power (HSA91's BF rule) "
                "instead of against the power whose cells may see its ends' cells (rays mode "
                "with cell culling): in a building of many rooms, each room is otherwise refined "
                "as if it were the whole scene");
  cmd->add_flag("--no-contact-split", s->noContactSplit,
                "Keep the patches whole instead of cutting them along the outlines of the patches "
                "resting on them or hanging just in front (scene/contact_split.h)");
  auto* coverage = cmd->add_option("--min-coverage", s->bsp.minCoverage,
                                   "blockers mode and rays mode's cell culling: BSP stop rule (see "
                                   "`globalvis cells --help`); "
                                   "default: chosen as `vis` chooses it")
                       ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--rays", s->rays, "Visibility rays per link")->check(CLI::Range(1, 4096));
  std::string qualityHelp = "Accuracy against time:";
  for (const RadiosityQualityLevel& level : kRadiosityQualityLevels)
    qualityHelp +=
        fmt::format(" {} = {} (epsilon {:g});", level.name, level.summary, level.epsilon);
  qualityHelp += " figures measured against light tracing in docs/BENCHMARKS.md";
  std::vector<std::string> qualityNames;
  for (const RadiosityQualityLevel& level : kRadiosityQualityLevels)
    qualityNames.emplace_back(level.name);
  auto* quality = cmd->add_option("--quality", s->quality, qualityHelp)
                      ->capture_default_str()
                      ->check(CLI::IsMember(qualityNames));
  auto* epsilon =
      cmd->add_option(
             "--epsilon", s->options.epsilon,
             "BF refinement threshold, as a fraction of the total emitted power (instead of "
             "the one --quality sets; the default quality's other settings apply)")
          ->check(CLI::PositiveNumber)
          ->excludes(quality);
  auto* relativeEpsilon =
      cmd->add_option("--relative-epsilon", s->options.relativeEpsilon,
                      "Receiver consistency bound: per subdivided element, the signed form-factor "
                      "error its links hand its children, as a fraction of its radiosity (instead "
                      "of the one --quality sets)")
          ->check(CLI::PositiveNumber)
          ->excludes(quality);
  auto* clusterSamples =
      cmd->add_option("--cluster-samples", s->options.clusterSamples,
                      "Clustering: sampled segments per patch and direction of a link between "
                      "clusters of patches; 0 links every pair of patches (instead of the value "
                      "--quality sets)")
          ->check(CLI::Range(0, 1000));
  cmd->add_option("--min-area", s->options.minArea,
                  "Smallest subdividable element, as a fraction of the total patch area")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--tolerance", s->options.tolerance,
                  "Stop solving when no radiosity changes by more than this fraction of the "
                  "largest in a sweep")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--max-links", s->options.maxLinks,
                  "Stop refining once this many links exist (a memory guard: links over the "
                  "threshold are then kept as they are and the run is reported not converged; "
                  "8 links between clusters count as one). Default `auto`: as many as 60 % of the "
                  "machine's memory holds at ~160 bytes each, at least 20 M")
      ->transform(CLI::Transformer({{"auto", "0"}}).description(""))
      ->check(CLI::Range(size_t{0}, size_t{4'000'000'000}))
      ->type_name("UINT|auto")
      ->default_str("auto");
  cmd->add_option("--max-refinements", s->options.maxRefinements, "Refine/solve rounds at most")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--seed", s->options.seed, "Seed of the visibility samples");
  cmd->add_option("--threads", s->options.threads,
                  "Worker threads (0 = all cores); the solution is the same on any number")
      ->check(CLI::Range(0, 1024));
  cmd->add_flag("-q,--quiet", s->quiet,
                "No progress on stderr (there is none unless stderr is a terminal)");
  cmd->add_flag("--json", s->json, "Print the statistics as JSON on stdout");
  addKeepHiddenFlag(*cmd, s->keepHidden);
  cmd->add_option("--camera", s->camera,
                  "Viewpoint of the pictures: ex,ey,ez,tx,ty,tz[,fov] (eye, target, vertical "
                  "field of view in degrees; default: a view into the scene, roof cut away)")
      ->check([](const std::string& v) { return pictureOptionsError(v, "800x600"); });
  cmd->add_option("--image-size", s->imageSize, "Size of the pictures, WxH")
      ->check([](const std::string& v) { return pictureOptionsError("", v); });
  cmd->add_flag("--flat", s->flat, "Pictures with one colour per element instead of smooth");
  cmd->add_flag("--no-pictures", s->noPictures,
                "Do not write render.png, mesh.png, links_visible.png, links_partial.png");
  return [s, coverage, epsilon, relativeEpsilon, clusterSamples] {
    const ThreadLimit threadLimit(s->options.threads);
    const auto start = Clock::now();
    // The quality's settings, then an explicit --epsilon, --relative-epsilon (with the default
    // quality's other settings) or --cluster-samples (with the chosen quality's) over them: a
    // "custom" quality.
    s->customQuality =
        epsilon->count() > 0 || relativeEpsilon->count() > 0 || clusterSamples->count() > 0;
    // 0 is what `auto` parses to (a budget of no links would make nothing).
    if (s->options.maxLinks == 0) s->options.maxLinks = linkBudgetForMemory(usableMemoryBytes());
    const RadiosityOptions given = s->options;
    applyRadiosityQuality(parseRadiosityQuality(s->quality).value_or(kDefaultRadiosityQuality),
                          s->options);
    if (epsilon->count() > 0) s->options.epsilon = given.epsilon;
    if (relativeEpsilon->count() > 0) s->options.relativeEpsilon = given.relativeEpsilon;
    if (clusterSamples->count() > 0) s->options.clusterSamples = given.clusterSamples;
    const Scene scene = loadPipelineScene(s->scene, {!s->noContactSplit, s->keepHidden});
    const double loadSeconds = secondsSince(start);
    const std::filesystem::path dir = makeOutputDirectory(s->output);
    // Progress (a bar per refinement round, a line per round) only on a terminal.
    const bool progress = !s->quiet && stderrIsTerminal();
    std::unique_ptr<ProgressBar> bar;
    if (progress) {
      s->options.progress = [&bar](const std::string& line) {
        if (bar) bar->finish();
        std::cerr << line << std::endl;
        bar = std::make_unique<ProgressBar>("radiosity refinement (links)");
      };
      s->options.refineProgress = [&bar](size_t done, size_t total) {
        if (bar) bar->update(done, total);
      };
    }

    std::unique_ptr<EmbreeScene> bvh;
    std::unique_ptr<LinkVisibility> visibility;
    VisibilityGraph graph;
    double visibilitySeconds = 0;
    std::unique_ptr<PatchCellReach> cellReach;
    // The cells `vis` would use, with progress (blockers mode and rays mode's cell culling).
    auto subdivide = [&] {
      ProgressBar bspBar("BSP", progress);
      if (progress) s->bsp.progress = [&bspBar](double f) { bspBar.update(f); };
      Subdivision sub = coverage->count() > 0 ? buildSubdivision(scene, s->bsp)
                                              : buildVisibilitySubdivision(scene, s->bsp);
      bspBar.finish();
      return sub;
    };
    if (s->visibility == "blockers") {
      const auto t0 = Clock::now();
      const Subdivision sub = subdivide();
      ProgressBar cellBar("visibility (per source cell)", progress);
      ProgressBar visBar("visibility (per source patch)", progress);
      PropagationOptions propagation;
      propagation.threads = s->options.threads;
      propagation.cellProgress = cellBar.callback();
      propagation.progress = visBar.callback();
      ProgressBar blockerBar("blocker lists (per source patch)", progress);
      propagation.blockerProgress = blockerBar.callback();
      graph = computeVisibility(scene, sub, propagation);
      visBar.finish();
      visibilitySeconds = secondsSince(t0);
      if (progress)
        fmt::print(stderr, "visibility graph: {} VISIBLE + {} PARTIAL pairs, {:.2f} s\n",
                   graph.stats.pairsVisible, graph.stats.pairsPartial, visibilitySeconds);
      visibility = std::make_unique<BlockerVisibility>(scene, graph, s->rays);
    } else if (s->visibility == "shaft") {
      visibility = std::make_unique<ShaftVisibility>(scene, s->rays);
    } else {
      const auto t0 = Clock::now();
      if (!s->noCellCulling && scene.patches.size() >= kMinPatchesForCellCulling) {
        const Subdivision sub = subdivide();
        ProgressBar cellBar("cell-to-cell visibility", progress);
        PropagationOptions propagation;
        propagation.threads = s->options.threads;
        propagation.cellProgress = cellBar.callback();
        cellReach = std::make_unique<PatchCellReach>(scene, sub, propagation);
        cellBar.finish();
        if (!s->sceneThreshold && cellReach->known()) {
          s->options.thresholdPower = cellReach->powerInView(scene.emittedPower());
        }
      }
      bvh = std::make_unique<EmbreeScene>(scene);
      visibility = std::make_unique<RayVisibility>(scene, *bvh, s->rays, cellReach.get());
      visibilitySeconds = secondsSince(t0);
    }
    const RadiosityResult result = solveRadiosity(scene, *visibility, s->options);
    bar.reset();

    const auto written = Clock::now();
    writeObj(scene, (dir / "patches.obj").string());
    writeRadiosityTxt(result, (dir / "radiosity.txt").string());
    writeElementsPly(result, (dir / "elements.ply").string());
    const double writeSeconds = secondsSince(written);
    double pictureSeconds = 0;
    if (!s->noPictures) {
      const PictureStats pictures = writeRadiosityPictures(
          scene, result, dir, parsePictureOptions(s->camera, s->imageSize, s->flat));
      pictureSeconds = pictures.seconds;
      if (progress) std::cerr << fmt::format("pictures: {:.2f} s\n", pictures.seconds);
    }
    nlohmann::json stats = radiosityStatsJson(result.stats, s->options, s->rays);
    stats["options"]["quality"] = s->customQuality ? "custom" : s->quality;
    if (const auto* blockers = dynamic_cast<const BlockerVisibility*>(visibility.get())) {
      stats["linespace"] = blockers->statsJson();
      stats["linespace"]["visibility_graph_seconds"] = visibilitySeconds;
    }
    if (cellReach) {
      const VisibilityStats& cs = cellReach->stats();
      stats["cell_culling"] = {{"known", cellReach->known()},
                               {"cells", cs.cells},
                               {"portals", cs.portals},
                               {"cell_pairs_visible", cs.cellPairsVisible},
                               {"cell_searches_over_budget", cs.cellSearchesOverBudget},
                               {"unplaced_patches", cellReach->unplacedPatches()},
                               {"candidate_pairs", result.stats.candidatePairs},
                               {"threshold_per_room", !s->options.thresholdPower.empty()},
                               {"seconds", cs.seconds}};
    }
    stats["contact_split"] = {{"enabled", !s->noContactSplit},
                              {"patches_split", scene.report.splitAtContacts},
                              {"pieces", scene.report.contactPieces}};
    // Where the whole command's time and memory went (issue #19: every run says so).
    const double peakBytes = peakResidentBytes();
    stats["run"] = {
        {"load_seconds", loadSeconds},           {"visibility_seconds", visibilitySeconds},
        {"solve_seconds", result.stats.seconds}, {"write_seconds", writeSeconds},
        {"picture_seconds", pictureSeconds},     {"total_seconds", secondsSince(start)},
        {"peak_resident_bytes", peakBytes}};
    writeJsonFile(stats, dir / "stats.json");
    if (s->json) {
      stats["scene"] = s->scene;
      stats["output"] = dir.string();
      fmt::print("{}\n", stats.dump(2));
      return 0;
    }

    const RadiosityStats& st = result.stats;
    const size_t links = st.rounds.empty() ? 0 : st.rounds.back().links.total();
    const size_t elements = st.rounds.empty() ? 0 : st.rounds.back().elements;
    fmt::print("patches {}  links {}  elements {}  interactions {}  rays {}\n", st.patches, links,
               elements, st.interactions, st.rays);
    if (st.clustered && !st.rounds.empty()) {
      size_t invisible = 0;
      for (const RefinementStats& r : st.rounds) invisible += r.clusterPairsInvisible;
      fmt::print(
          "clusters: {} links between clusters of patches, {} clear samples; {} cluster pairs "
          "dropped with no candidate pair between them\n",
          st.rounds.back().clusterLinks, st.rounds.back().clusterTaps, invisible);
    }
    if (cellReach) {
      const VisibilityStats& cs = cellReach->stats();
      if (cellReach->known())
        fmt::print(
            "cell culling: {} cells, {} candidate pairs of patches ({:.1f} % of all), {:.2f} s\n",
            cs.cells, st.candidatePairs,
            st.patches > 1
                ? 200.0 * double(st.candidatePairs) / (double(st.patches) * double(st.patches - 1))
                : 0.0,
            cs.seconds);
      else
        fmt::print("cell culling: {} cells, too many for the cell sets; every pair linked\n",
                   cs.cells);
    }
    if (scene.report.splitAtContacts > 0)
      fmt::print("contact split: {} patches cut along the patches resting on them into {} pieces\n",
                 scene.report.splitAtContacts, scene.report.contactPieces);
    fmt::print("{} rounds, {:.2f} s, {}; wrote {}\n", st.rounds.size(), st.seconds,
               st.converged ? "converged"
               : st.linkBudgetReached
                   ? "NOT converged: stopped at --max-links (a coarser --quality "
                     "or a larger budget)"
                   : "NOT converged (raise --max-refinements)",
               dir.string());
    fmt::print(
        "quality {} (epsilon {:g}); whole command {:.2f} s (load {:.2f}, visibility {:.2f}, "
        "solve {:.2f}, write {:.2f}, pictures {:.2f}), peak memory {:.0f} MB\n",
        s->customQuality ? "custom" : s->quality, s->options.epsilon, secondsSince(start),
        loadSeconds, visibilitySeconds, st.seconds, writeSeconds, pictureSeconds, peakBytes / 1e6);
    return 0;
  };
}

}  // namespace gv::cli
