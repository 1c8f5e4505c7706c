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
/// by `blocked(from, to)` and weighted by the form-factor kernel (kernelWeight). When some are
/// blocked and some clear, the clear ones are tested for cracks (throughCrack) and count as
/// blocked if they pass through one (those extra segments are not in `samples`, which is the N
/// of the sampling uncertainty). nullopt when the two exchange no light at all.
std::optional<SampledVisibility> sampleLinkVisibility(
    const ConvexPolygon& a, const ConvexPolygon& b, int count, const Tolerance& tol,
    SplitMix64& rng, const std::function<bool(const Vec3& from, const Vec3& to)>& blocked);

/// Real levels have cracks: faces that meet along edges with T-junctions or vertices a rounding
/// apart leave slits far narrower than anything modelled, and single-precision rays slip through
/// them (lit-q3-dm4ish: one sample of 16 through a crack between brushes lit thin brush faces
/// that no photon reaches). A clear segment counts only if it stays clear when moved sideways by
/// this many model tolerances (Tolerance::planeOffset) in two directions across it; the same rule
/// as the portals', whose pieces thinner than the model tolerance are cracks, not openings.
inline constexpr double kCrackWidthInModelTolerances = 2.0;

/// Whether the clear segment from -> to passes only through a crack: one of its two copies moved
/// sideways (perpendicular to it and to each other) by kCrackWidthInModelTolerances model
/// tolerances is `blocked`.
bool throughCrack(const Vec3& from, const Vec3& to, const Tolerance& tol,
                  const std::function<bool(const Vec3& from, const Vec3& to)>& blocked);

/// What sampled visibility says when nothing else is known: Invisible when no sample is clear,
/// Visible when all are, else Partial, keeping the clear samples (the solver's taps).
VisibilityEstimate estimateFromSamples(SampledVisibility&& sampled);

}  // namespace gv
