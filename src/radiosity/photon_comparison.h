// Comparison of a radiosity solution with the photon reference (photon_reference.h): the figures
// the tests, `globalvis photons --compare` and the benchmarks report. Everything is counted: the
// channels left out as noisy, the channels no photon reached (leaks among them), rooms off as a
// whole (regions), and coincident twins taken as one surface (issue #18 item 3).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "geometry/vec3.h"
#include "radiosity/photon_reference.h"
#include "scene/scene.h"

namespace gv {

/// Surface channels whose photon estimate has a relative standard error above this are left out
/// of the per-channel figures (small or dim patches get few photons; their estimate says little).
constexpr double kMeaningfulPhotonNoise = 0.01;

/// A surface channel no photon reached is a leak when the solution's value would have drawn at
/// least this many photon hits: the chance of none is then e^-10 ≈ 5e-5.
constexpr double kLeakExpectedHits = 10;

/// The side of the region cubes, scene units: the shared levels are in map units / 32, so 3 is
/// 96 map units, about a room's height (`--region-size`).
constexpr double kDefaultRegionSize = 3;

/// The per-patch tolerance `photons --compare` and `bench` judge with by default: this many
/// photon standard errors plus this fraction of the value.
constexpr double kDefaultSigmas = 4, kDefaultAllowance = 0.01;

/// Region channels whose photon estimate has a relative standard error above this (or no photon
/// at all) are left out of the worst region.
constexpr double kMeaningfulRegionNoise = 0.05;

/// Region channels holding less than this share of the scene's reflected power in the channel
/// (by the solution and by the photons) are left out: the outside check's rule
/// (shared/DESIGN.md, "How the outside checks measure").
constexpr double kMinRegionShare = 0.001;

/// How many leaks `PhotonComparison::worstLeaks` lists.
constexpr size_t kReportedLeaks = 5;

/// Where every surface channel went (a surface: a patch, or a group of coincident patches, see
/// scene/coincident_patches.h). total = compared + noisy + zeroPhoton;
/// zeroPhoton = leaks + tooDim + unlit.
struct PhotonChannelCounts {
  size_t total = 0;
  size_t compared = 0;    ///< photons came, relative standard error within kMeaningfulPhotonNoise
  size_t noisy = 0;       ///< photons came, relative standard error above kMeaningfulPhotonNoise
  size_t zeroPhoton = 0;  ///< no photon reached the surface (its reflected estimate is 0)
  size_t leaks = 0;       ///< ... where the solution's value expected >= kLeakExpectedHits hits
  size_t tooDim = 0;      ///< ... where the solution is lit but expected fewer: cannot tell
  size_t unlit = 0;       ///< ... where the solution reflects nothing either (or ρ = 0)
};

/// A surface channel the solution lights where the tracer, expecting many photons, saw none.
struct PhotonLeak {
  size_t patch = 0;  ///< the surface's first patch
  int channel = 0;
  double expectedHits = 0;  ///< at the solution's value (a lower bound, see photonPower)
  double solver = 0;        ///< the solution's B − Ke there (area-weighted over the surface)
};

/// One region cube and channel: reflected power (area-weighted sums of B − Ke) of both.
struct PhotonRegion {
  Vec3 low;  ///< the cube's lower corner (a multiple of the region size)
  int channel = 0;
  double solver = 0, photons = 0;
  double relative = 0;  ///< (solver − photons) / photons, signed
  size_t patches = 0;   ///< patches whose centroid lies in the cube
};

/// Solver against photons. The per-channel figures (compared … worstChannel) are over the
/// compared surface channels, B as written (Ke included); the rest over all of them, B − Ke.
struct PhotonComparison {
  size_t compared = 0;  ///< surface channels compared (= channels.compared)
  size_t failures = 0;  ///< beyond `sigmas` standard errors plus `allowance` of the value
  double maxRelative = 0, rmsRelative = 0, meanSigned = 0;
  /// Area-weighted mean signed relative error (big patches count more: what a viewer sees).
  double areaWeightedSigned = 0;
  size_t worstPatch = 0;  ///< patch of maxRelative (the surface's first patch)
  int worstChannel = 0;

  /// sqrt(Σ A (b − p)² / Σ A p²) of B − Ke over every patch and channel, nothing left out; a
  /// patch with twins is held to its surface's photon estimate (the headline figure).
  double l2Reflected = 0;
  /// What the reference's own noise adds to l2Reflected: sqrt(Σ A σ² / Σ A p²), σ the standard
  /// error of the photon estimate each patch is held to. An exact solution would score this in
  /// expectation (its squared L2 is l2PhotonNoise² on average), so the solver's own error is
  /// about sqrt(l2Reflected² − l2PhotonNoise²) when l2Reflected is clearly above it. On a level
  /// of thousands of small patches 1.6·10^7 photons leave several percent (q3-oa_pvomit: 6.5 %
  /// alone, against its 7.3 %).
  double l2PhotonNoise = 0;
  size_t surfaces = 0;     ///< patches, each group of coincident twins counted once
  size_t twinGroups = 0;   ///< surfaces of more than one patch
  size_t twinPatches = 0;  ///< the patches in them
  PhotonChannelCounts channels;
  size_t leakSurfaces = 0, leakPatches = 0;  ///< surfaces with a leak channel, and their patches
  /// The leaking channels' share of the solution's reflected power (all channels).
  double leakedPowerShare = 0;
  std::vector<PhotonLeak> worstLeaks;  ///< most expected hits first, at most kReportedLeaks

  double regionSize = 0;
  size_t regionChannels = 0;  ///< occupied region cubes × 3
  size_t regionsCompared = 0;
  size_t regionsNoisy = 0;  ///< photon relative standard error above kMeaningfulRegionNoise
  size_t regionsSmall = 0;  ///< below kMinRegionShare of the reflected power
  std::optional<PhotonRegion> worstRegion;  ///< largest |relative| among the compared
};

/// Compares `solver` (per patch of `scene`, B as written) with `reference`: surfaces from
/// coincidentPatchGroups, whose photon estimate is the photons' power over the group divided by
/// one member's area (a photon lands on one twin only) and whose solution is the area-weighted
/// mean of the group. Leaks need `reference.photonPower`. Region cubes of side `regionSize` bin
/// the surfaces by centroid; a region's standard error takes its surfaces' as independent.
PhotonComparison comparePhotons(const Scene& scene, const std::vector<Rgb>& solver,
                                const PhotonResult& reference, double sigmas, double allowance,
                                double regionSize = kDefaultRegionSize);

}  // namespace gv
