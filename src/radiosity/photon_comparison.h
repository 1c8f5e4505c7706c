// Per-patch comparison of a radiosity solution with the photon reference (photon_reference.h):
// the figures the tests, `globalvis photons --compare` and the benchmarks report.
#pragma once

#include <cstddef>
#include <vector>

#include "radiosity/photon_reference.h"
#include "scene/scene.h"

namespace gv {

/// Patch channels whose photon estimate has a relative standard error above this are left out
/// (small or dim patches get few photons; their estimate says little).
constexpr double kMeaningfulPhotonNoise = 0.01;

/// Solver minus photons, relative to the photons, over the meaningful patch channels.
struct PhotonComparison {
  size_t compared = 0;  ///< patch channels compared
  size_t failures = 0;  ///< beyond `sigmas` standard errors plus `allowance` of the value
  double maxRelative = 0, rmsRelative = 0, meanSigned = 0;
  /// Area-weighted mean signed relative error (big patches count more: what a viewer sees).
  double areaWeightedSigned = 0;
  size_t worstPatch = 0;  ///< patch of maxRelative
  int worstChannel = 0;
};

/// Compares `solver` (per patch of `scene`) with `reference`.
PhotonComparison comparePhotons(const Scene& scene, const std::vector<Rgb>& solver,
                                const PhotonResult& reference, double sigmas, double allowance);

}  // namespace gv
