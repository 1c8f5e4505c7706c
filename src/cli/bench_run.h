// `globalvis bench`, one scene: the pipeline's stages timed under a budget, each stage's result
// checked before its time counts, and a hash of each result (STYLE.md: benchmarks check first).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bsp/bsp_tree.h"
#include "scene/scene.h"

namespace gv::cli {

/// Rays and segments of the verifyVisibility check of each vis result: a few thousand, so the
/// check costs less than the stage it checks.
inline constexpr uint64_t kBenchVerifyRays = 4000;
inline constexpr uint64_t kBenchVerifySegments = 2000;

/// Cells must fill the root box: |sum of cell volumes − root volume| ≤ this × root volume. The
/// cells are clipped polyhedra, exact up to rounding (~1e-12 relative); 1e-6 leaves room for
/// millions of cells and still catches one lost cell.
inline constexpr double kBenchVolumeTolerance = 1e-6;

/// What to run on each scene.
struct BenchOptions {
  double maxSeconds = 60;             ///< per scene; later stages are skipped once exceeded
  bool radiosity = false;             ///< also solve radiosity (rays mode, 16 rays per link)
  size_t radiosityMaxPatches = 3000;  ///< larger scenes skip radiosity (its initial links are n²)
  /// BSP stop rule; none: `vis`'s own choice (buildVisibilitySubdivision's steps).
  std::optional<double> minCoverage;
  int threads = 0;  ///< propagation and PVS threads (0 = all cores)
  /// Light-tracing photons of a lit level's reference. A leak is judged at >= 10 hits expected
  /// at the solution's value: with few photons a dim patch the solution gets a few times too
  /// bright draws none by chance (at 4 M, a floor strip at the bottom of a 0.125-unit slot of
  /// lit-doom-fd2-map03, 2x too bright: 2.4 hits expected at its true value). 16 M keeps each
  /// level's reference under ~8 s.
  uint64_t photons = 16'000'000;
};

/// One scene's figures. Empty optionals: the stage did not run (see `notes`).
struct BenchRow {
  std::string name, kind;  ///< kind: "office" or "map"
  size_t patches = 0;
  std::optional<double> loadSeconds, bspSeconds, portalSeconds, visSeconds, radiositySeconds,
      pvsSeconds;
  std::optional<size_t> cells, portals;
  std::optional<uint64_t> pairsListed, pairsVisible, pairsPartial;
  std::optional<double> meanBlockers;
  /// Tightness (`verify`'s excess): of the sampled listed pairs, the share none of 48 segments
  /// reaches free (issue #17's target: at most 0.5).
  std::optional<double> excess;
  std::optional<size_t> radiosityLinks;
  std::optional<size_t> radiosityInteractions;
  std::optional<uint64_t> radiosityRays;
  std::optional<double> radiosityPeakBytes;  ///< peak resident memory of the radiosity stage
  /// A lit level's radiosity against light tracing (comparePhotons, as `photons --compare`):
  /// area-weighted L2 of B − Ke, surfaces lit where the tracer expected >= 10 hits and got none,
  /// the worst region's signed relative error, and the reference's time.
  std::optional<double> photonL2, worstRegion, photonSeconds;
  /// What the photon reference's own noise alone gives photonL2 (PhotonComparison::l2PhotonNoise).
  std::optional<double> photonNoiseL2;
  std::optional<size_t> leaks;
  /// The region channels the worst region was taken over, of all occupied ones (the others are
  /// noisy or hold under 0.1 % of the reflected power).
  std::optional<size_t> regionsCompared, regionChannels;
  std::optional<size_t> pvsLeafs;
  std::optional<double> pvsMeanLeafs;
  std::string visHash, radiosityHash, pvsHash;  ///< FNV-1a, 16 hex digits; empty if not run
  std::vector<std::string> checks;              ///< checks passed
  std::vector<std::string> failures;            ///< checks failed (bench exits non-zero)
  std::vector<std::string> notes;               ///< stages skipped and why
};

/// Makes a scene (generator or importer); timed as the row's load stage.
using SceneMaker = std::function<Scene()>;

/// Runs load, BSP + portals, visibility (and radiosity) on one scene. A stage that reports
/// progress is abandoned at its next report once `options.maxSeconds` have passed since the
/// scene started; stages after the budget is spent are skipped. Both are noted in the row.
BenchRow benchScene(const std::string& name, const std::string& kind, const SceneMaker& make,
                    const BenchOptions& options);

/// Adds to `row` the radiosity of `litPath`, the lit variant of a level (loaded as `radiosity`
/// loads it: cut at contacts; no patch-count limit, the solver clusters), and its comparison with
/// a light tracer of options.photons photons. A leak fails the row; the L2 and the worst region
/// are figures (issue #18's targets: 5 %, 15 %). Its own budget of maxSeconds.
void benchLitLevel(const std::string& litPath, const BenchOptions& options, BenchRow& row);

/// Adds the leaf PVS of the portal file `prtPath` to `row` (its own budget of maxSeconds).
void benchPvs(const std::string& prtPath, const BenchOptions& options, BenchRow& row);

}  // namespace gv::cli
