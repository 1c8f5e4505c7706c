// An independent Monte Carlo reference for radiosity: light tracing (photons shot from emitters,
// cosine-distributed, bounced diffusely with Russian roulette) with per-patch power tallies. It
// shares nothing with the solver's form factors; used to check hierarchical radiosity (HSA91) on
// real scenes, and as the "converged reference" of the paper's §7.4 comparisons.
#pragma once

#include <cstdint>
#include <vector>

#include "raycast/embree_scene.h"
#include "scene/scene.h"

namespace gv {

/// Parameters of photonReference.
struct PhotonOptions {
  uint64_t photons = 1'000'000;  ///< photons shot in all (shared out over the batches)
  int batches = 16;              ///< independent batches, for the per-patch standard error (>= 2)
  uint64_t seed = 1;
  int maxBounces = 1000;  ///< a safety net; Russian roulette ends paths long before
};

/// Per-patch radiosity estimate with its Monte Carlo standard error.
struct PhotonResult {
  std::vector<Rgb> radiosity;      ///< emitted + reflected exitance per patch (power / area)
  std::vector<Rgb> standardError;  ///< of `radiosity`, from the spread of the batch estimates
  uint64_t photons = 0;
  uint64_t rays = 0;  ///< rays traced (one per photon segment)
  /// Per channel, the most that one photon's tally adds to a patch's reflected power (before the
  /// patch's ρ): W e_c / (Σ_c e_c · photons) for the brightest-in-c emitter e, W the emitted power
  /// summed over channels. Bounces never raise it (Russian roulette divides ρ_c by max ρ), so
  /// reflected power / (ρ · photonPower) is a lower bound on the photon hits it takes.
  Rgb photonPower;
};

/// Light tracing with the solver's physics: patches are one-sided Lambertian (emission E = Ke,
/// radiosity units; reflectance Kd). A photon leaves a uniform point of an emitter (chosen by
/// emitted power) in a cosine-distributed direction; at the first patch it meets, if it arrives
/// on the front, ρ times its power is tallied as reflected there and it continues from the hit
/// point in a new cosine direction with power ρ P / q, surviving with probability q = max(ρ);
/// arriving on a back it is absorbed (light is exchanged front to front only, as in the
/// solver). Radiosity = E + tallied reflected power / area. Deterministic for a seed, whatever
/// the thread count (batches are independent and summed in order).
PhotonResult photonReference(const Scene& scene, const EmbreeScene& rays,
                             const PhotonOptions& options = {});

}  // namespace gv
