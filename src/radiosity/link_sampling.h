// Sampled visibility of a link, shared by every mode that samples (HSA91's jittered rays; the
// paper's §6.3 ray/blocker tests): where the samples go and how they are weighted decides whether
// a solution agrees with light tracing, so it is written once.
#pragma once

#include <functional>
#include <optional>

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"
#include "radiosity/link_visibility.h"
#include "radiosity/polygon_sampling.h"

namespace gv {

struct SampledVisibility {
  double fraction = 1;                    ///< kernel-weighted fraction of free samples, in [0, 1]
  size_t samples = 0;                     ///< segments tested
  size_t clear = 0;                       ///< of which free
  std::vector<ClearSample> clearSamples;  ///< the free ones, weights summing to `fraction`
};

/// `count` segments between stratified points of the parts of `a` and `b` that exchange light
/// (exchangingParts: what the unoccluded form factor integrates over), the strata of `b` paired
/// with a random permutation of `a`'s so that the segments do not all run parallel, each decided
/// by `blocked(from, to)` and weighted by the form-factor kernel (kernelWeight). nullopt when the
/// two exchange no light at all.
std::optional<SampledVisibility> sampleLinkVisibility(
    const ConvexPolygon& a, const ConvexPolygon& b, int count, const Tolerance& tol,
    SplitMix64& rng, const std::function<bool(const Vec3& from, const Vec3& to)>& blocked);

/// What sampled visibility says when nothing else is known: Invisible when no sample is clear,
/// Visible when all are, else Partial, keeping the clear samples (the solver's taps).
VisibilityEstimate estimateFromSamples(SampledVisibility&& sampled);

}  // namespace gv
