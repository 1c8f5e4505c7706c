// `globalvis bench`, one scene: timed stages, their checks and result hashes.
#include "cli/bench_run.h"

#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bsp/subdivision.h"
#include "cli/scene_input.h"
#include "quake/prt_file.h"
#include "quake/prt_portal_graph.h"
#include "radiosity/hierarchical_radiosity.h"
#include "radiosity/photon_comparison.h"
#include "radiosity/photon_reference.h"
#include "radiosity/radiosity_checks.h"
#include "radiosity/radiosity_quality.h"
#include "radiosity/ray_visibility.h"
#include "raycast/embree_scene.h"
#include "util/fnv_hash.h"
#include "util/peak_memory.h"
#include "util/progress_bar.h"
#include "util/timing.h"
#include "visibility/cell_pvs.h"
#include "visibility/patch_cell_reach.h"
#include "visibility/propagation.h"
#include "visibility/verify.h"

namespace gv::cli {
namespace {

/// Rays per link of the bench's radiosity (the `radiosity` command's default).
constexpr int kBenchRadiosityRays = 16;

/// Thrown from a progress callback to abandon a stage over the scene's budget.
struct BudgetExceeded {};

class Budget {
 public:
  explicit Budget(double maxSeconds) : maxSeconds_(maxSeconds) {}
  bool spent() const { return secondsSince(start_) > maxSeconds_; }
  double maxSeconds() const { return maxSeconds_; }
  Clock::time_point deadline() const {
    return start_ +
           std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(maxSeconds_));
  }

 private:
  Clock::time_point start_ = Clock::now();
  double maxSeconds_;
};

/// Progress callback of a stage: the bar (on a terminal) and the budget.
std::function<void(size_t, size_t)> watch(ProgressBar& bar, const Budget& budget) {
  return [&bar, &budget](size_t done, size_t total) {
    bar.update(done, total);
    if (budget.spent()) throw BudgetExceeded{};
  };
}

/// The cells fill the root box, every patch lies in some cell, portals link two real cells.
std::optional<std::string> checkSubdivision(const Subdivision& sub, size_t patches) {
  double volume = 0;
  for (const Cell& c : sub.cells) volume += c.shape.volume();
  const double root = sub.tree.root.volume();
  if (!(std::abs(volume - root) <= kBenchVolumeTolerance * root))
    return fmt::format("cell volumes sum to {:.9g}, root box {:.9g}", volume, root);
  std::vector<char> placed(patches, 0);
  for (const Cell& c : sub.cells)
    for (uint32_t p : c.patches)
      if (p < patches) placed[p] = 1;
  const size_t unplaced = static_cast<size_t>(std::count(placed.begin(), placed.end(), 0));
  if (unplaced) return fmt::format("{} patches in no cell", unplaced);
  for (const Portal& p : sub.portals)
    if (p.back == p.front || p.back >= sub.cells.size() || p.front >= sub.cells.size())
      return fmt::format("portal linking cells {} and {}", p.back, p.front);
  return std::nullopt;
}

/// Pairs sorted with s < r, ids valid, blocker lists sorted without s or r.
std::optional<std::string> checkGraphShape(const VisibilityGraph& g, size_t patches) {
  for (size_t i = 0; i < g.interactions.size(); ++i) {
    const Interaction& in = g.interactions[i];
    if (in.s >= in.r || in.r >= patches) return fmt::format("pair ({}, {})", in.s, in.r);
    if (i > 0) {
      const Interaction& prev = g.interactions[i - 1];
      if (std::pair(prev.s, prev.r) >= std::pair(in.s, in.r))
        return fmt::format("pairs not sorted at ({}, {})", in.s, in.r);
    }
    if (!std::is_sorted(in.blockers.begin(), in.blockers.end()) ||
        std::binary_search(in.blockers.begin(), in.blockers.end(), in.s) ||
        std::binary_search(in.blockers.begin(), in.blockers.end(), in.r))
      return fmt::format("blocker list of ({}, {})", in.s, in.r);
  }
  return std::nullopt;
}

std::string visibilityHash(const VisibilityGraph& g) {
  Fnv1a h;
  for (const Interaction& in : g.interactions) {
    h.integer(in.s);
    h.integer(in.r);
    h.integer(in.blockers.size());
    for (uint32_t b : in.blockers) h.integer(b);
  }
  return h.hex();
}

void record(BenchRow& row, const std::string& check, const std::optional<std::string>& error) {
  if (error)
    row.failures.push_back(check + ": " + *error);
  else
    row.checks.push_back(check);
}

std::string overBudget(const std::string& stage, const Budget& b) {
  return fmt::format("{} stopped: over the {:g} s budget", stage, b.maxSeconds());
}

std::string skipped(const std::string& stages, const Budget& b) {
  return fmt::format("{} skipped: {:g} s budget spent", stages, b.maxSeconds());
}

/// Solves radiosity as `radiosity` does by default on a level (rays visibility; from
/// kMinPatchesForCellCulling patches on, links only between patches whose cells may see each
/// other, with a threshold per room; the link budget from the machine's memory) and records its
/// figures and checks in `row`; nullopt when the budget stopped it. Its seconds are the cell
/// stage and the solve (the command counts the first in `visibility_seconds`, with its BVH).
std::optional<RadiosityResult> benchRadiosity(const Scene& scene, const EmbreeScene& bvh,
                                              const BenchOptions& options, const Budget& budget,
                                              BenchRow& row) {
  try {
    RadiosityOptions ro;
    applyRadiosityQuality(kDefaultRadiosityQuality, ro);  // what `radiosity` runs by default
    ro.threads = options.threads;
    ro.maxLinks = linkBudgetForMemory(usableMemoryBytes());
    const bool peakReset = resetPeakResident();
    const auto t0 = Clock::now();
    std::unique_ptr<PatchCellReach> cellReach;
    if (scene.patches.size() >= kMinPatchesForCellCulling) {
      ProgressBar cellBar(row.name + ": radiosity, cells");
      BspOptions bsp;
      bsp.progress = [&](double) {
        if (budget.spent()) throw BudgetExceeded{};
      };
      const Subdivision sub = buildVisibilitySubdivision(scene, bsp);  // `radiosity`'s cells
      PropagationOptions propagation;
      propagation.threads = options.threads;
      propagation.cellProgress = watch(cellBar, budget);
      propagation.deadline = budget.deadline();
      cellReach = std::make_unique<PatchCellReach>(scene, sub, propagation);
      if (cellReach->known()) ro.thresholdPower = cellReach->powerInView(scene.emittedPower());
    }
    RayVisibility visibility(scene, bvh, kBenchRadiosityRays, cellReach.get());
    ProgressBar bar(row.name + ": radiosity refinement");
    ro.refineProgress = watch(bar, budget);
    RadiosityResult result = solveRadiosity(scene, visibility, ro);
    row.radiositySeconds = secondsSince(t0);
    if (peakReset) row.radiosityPeakBytes = peakResidentBytes();
    record(row, "radiosity", checkRadiosity(scene, result));
    row.radiosityLinks = result.stats.rounds.empty() ? 0 : result.stats.rounds.back().links.total();
    row.radiosityInteractions = result.stats.interactions;
    row.radiosityRays = result.stats.rays;
    row.radiosityHash = fmt::format("{:016x}", radiosityHash(result));
    return result;
  } catch (const BudgetExceeded&) {
    row.notes.push_back(overBudget("radiosity", budget));
    return std::nullopt;
  } catch (const PropagationDeadlineExceeded&) {
    row.notes.push_back(overBudget("radiosity", budget));
    return std::nullopt;
  }
}

}  // namespace

BenchRow benchScene(const std::string& name, const std::string& kind, const SceneMaker& make,
                    const BenchOptions& options) {
  BenchRow row;
  row.name = name;
  row.kind = kind;
  const Budget budget(options.maxSeconds);

  auto t0 = Clock::now();
  Scene scene;
  try {
    scene = make();
  } catch (const std::exception& e) {  // bad input: this row fails, the others still run
    row.failures.push_back(fmt::format("load: {}", e.what()));
    return row;
  }
  row.loadSeconds = secondsSince(t0);
  row.patches = scene.patches.size();
  if (budget.spent()) {
    row.notes.push_back(skipped("cells, vis", budget));
    return row;
  }

  Subdivision sub;
  try {
    ProgressBar bar(name + ": BSP");
    BspOptions bsp;
    if (options.minCoverage) bsp.minCoverage = *options.minCoverage;
    bsp.progress = [&](double f) {
      bar.update(f);
      if (budget.spent()) throw BudgetExceeded{};
    };
    sub = options.minCoverage ? buildSubdivision(scene, bsp)
                              : buildVisibilitySubdivision(scene, bsp);  // as `vis` builds
  } catch (const BudgetExceeded&) {
    row.notes.push_back(overBudget("BSP", budget));
    return row;
  }
  record(row, "cells", checkSubdivision(sub, scene.patches.size()));
  row.bspSeconds = sub.stats.bspSeconds;
  row.portalSeconds = sub.stats.portalSeconds;
  row.cells = sub.stats.cells;
  row.portals = sub.stats.portals;
  if (budget.spent()) {
    row.notes.push_back(skipped("vis", budget));
    return row;
  }

  VisibilityGraph graph;
  try {
    ProgressBar cellBar(name + ": visibility, cells");
    ProgressBar bar(name + ": visibility, patches");
    ProgressBar blockerBar(name + ": visibility, blockers");
    PropagationOptions propagation;
    propagation.threads = options.threads;
    propagation.cellProgress = watch(cellBar, budget);
    propagation.progress = watch(bar, budget);
    propagation.blockerProgress = watch(blockerBar, budget);
    propagation.deadline = budget.deadline();
    graph = computeVisibility(scene, sub, propagation);
  } catch (const BudgetExceeded&) {
    row.notes.push_back(overBudget("vis", budget));
    return row;
  } catch (const PropagationDeadlineExceeded&) {
    row.notes.push_back(overBudget("vis", budget));
    return row;
  }
  record(row, "pairs", checkGraphShape(graph, scene.patches.size()));
  VerifyReport verifyReport;
  {
    VerifyOptions verify;
    verify.rays = kBenchVerifyRays;
    verify.segments = kBenchVerifySegments;
    const VerifyReport& v = verifyReport = verifyVisibility(scene, graph, verify);
    std::optional<std::string> error;
    if (!v.ok())
      error = fmt::format("{} missing pairs, {} blocked VISIBLE, {} missing blockers{}",
                          v.missingPairs, v.blockedVisible, v.missingBlockers,
                          v.examples.empty() ? "" : " (" + v.examples.front() + ")");
    record(row, fmt::format("verify {} rays", v.rays), error);
  }
  const VisibilityStats& vs = graph.stats;
  row.visSeconds = vs.seconds;
  row.pairsVisible = vs.pairsVisible;
  row.pairsPartial = vs.pairsPartial;
  row.pairsListed = vs.pairsVisible + vs.pairsPartial;
  row.meanBlockers = vs.meanBlockersPerPartial;
  if (verifyReport.tightnessPairs > 0)
    row.excess = double(verifyReport.excess) / double(verifyReport.tightnessPairs);
  row.visHash = visibilityHash(graph);

  if (!options.radiosity) return row;
  if (scene.patches.size() > options.radiosityMaxPatches) {
    row.notes.push_back(
        fmt::format("radiosity skipped: over {} patches", options.radiosityMaxPatches));
    return row;
  }
  if (budget.spent()) {
    row.notes.push_back(skipped("radiosity", budget));
    return row;
  }
  const EmbreeScene bvh(scene);
  benchRadiosity(scene, bvh, options, budget, row);
  return row;
}

void benchLitLevel(const std::string& litPath, const BenchOptions& options, BenchRow& row) {
  const Budget budget(options.maxSeconds);
  Scene scene;
  try {
    SceneInputOptions input;
    input.contactSplit = true;  // as `radiosity` and `photons` read a scene
    scene = loadPipelineScene(litPath, input);
  } catch (const std::exception& e) {
    row.failures.push_back(fmt::format("lit level: {}", e.what()));
    return;
  }
  if (scene.emitterCount() == 0) {
    row.notes.push_back(fmt::format("{}: no emitter, radiosity skipped", litPath));
    return;
  }
  const EmbreeScene bvh(scene);  // shared by the solve and the photon reference
  const std::optional<RadiosityResult> result = benchRadiosity(scene, bvh, options, budget, row);
  if (!result) return;
  const auto t0 = Clock::now();
  PhotonOptions po;
  po.photons = options.photons;
  const PhotonResult reference = photonReference(scene, bvh, po);
  row.photonSeconds = secondsSince(t0);
  const PhotonComparison c =
      comparePhotons(scene, result->patchRadiosity, reference, kDefaultSigmas, kDefaultAllowance);
  row.photonL2 = c.l2Reflected;
  row.photonNoiseL2 = c.l2PhotonNoise;
  row.leaks = c.leakSurfaces;
  if (c.worstRegion) row.worstRegion = c.worstRegion->relative;
  row.regionsCompared = c.regionsCompared;
  row.regionChannels = c.regionChannels;
  std::optional<std::string> leak;
  if (c.leakSurfaces > 0)
    leak = fmt::format(
        "{} surfaces lit where light tracing expected >= {:g} hits and got none "
        "(patch {} first)",
        c.leakSurfaces, kLeakExpectedHits, c.worstLeaks.front().patch);
  record(row, fmt::format("no leak against {} photons", options.photons), leak);
}

void benchPvs(const std::string& prtPath, const BenchOptions& options, BenchRow& row) {
  const Budget budget(options.maxSeconds);
  const auto t0 = Clock::now();
  PrtFile prt;
  try {
    prt = readPrtFile(prtPath);
  } catch (const std::exception& e) {
    row.failures.push_back(fmt::format("PVS: {}", e.what()));
    return;
  }
  LeafPvs pvs;
  try {
    ProgressBar bar(row.name + ": PVS");
    CellPvsOptions lo;
    lo.parallel = options.threads != 1;
    lo.progress = watch(bar, budget);
    pvs = expandToLeafs(prt, computeCellPvs(portalGraphOf(prt), lo).visibleCells);
  } catch (const BudgetExceeded&) {
    row.notes.push_back(overBudget("PVS", budget));
    return;
  }
  row.pvsSeconds = secondsSince(t0);
  // Each row sorted and holding its own leaf; the relation symmetric (computeCellPvs promises
  // both; a broken symmetrisation or expansion would show here).
  std::optional<std::string> error;
  const auto& rows = pvs.visibleLeafs;
  for (size_t l = 0; l < rows.size() && !error; ++l) {
    if (!std::is_sorted(rows[l].begin(), rows[l].end()) ||
        !std::binary_search(rows[l].begin(), rows[l].end(), static_cast<uint32_t>(l)))
      error = fmt::format("leaf {}'s row is unsorted or lacks itself", l);
    for (uint32_t v : rows[l]) {
      if (v >= rows.size() ||
          !std::binary_search(rows[v].begin(), rows[v].end(), static_cast<uint32_t>(l))) {
        error = fmt::format("leaf {} sees {} but not back", l, v);
        break;
      }
    }
  }
  record(row, "pvs", error);
  Fnv1a h;
  for (const auto& r : rows) {
    h.integer(r.size());
    for (uint32_t v : r) h.integer(v);
  }
  row.pvsHash = h.hex();
  row.pvsLeafs = prt.leafCount;
  row.pvsMeanLeafs = pvs.meanLeafsVisible;
}

}  // namespace gv::cli
