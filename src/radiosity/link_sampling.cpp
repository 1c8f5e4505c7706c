// Sampled link visibility (HSA91 §3 jittered rays, kernel-weighted). See link_sampling.h.
#include "radiosity/link_sampling.h"

#include <utility>

#include "radiosity/form_factor.h"

namespace gv {

std::optional<SampledVisibility> sampleLinkVisibility(
    const ConvexPolygon& a, const ConvexPolygon& b, int count, const Tolerance& tol,
    SplitMix64& rng, const std::function<bool(const Vec3& from, const Vec3& to)>& blocked) {
  const std::optional<ExchangingParts> parts = exchangingParts(a, b, tol);
  if (!parts) return std::nullopt;
  const std::vector<Vec3> from = stratifiedPoints(parts->a.vertices, count, rng);
  std::vector<Vec3> to = stratifiedPoints(parts->b.vertices, count, rng);
  for (size_t i = to.size(); i > 1; --i) std::swap(to[i - 1], to[rng.next() % i]);
  SampledVisibility v;
  double weightClear = 0, weightAll = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    const double w = kernelWeight(from[i], a.plane.normal, to[i], b.plane.normal);
    weightAll += w;
    if (!blocked(from[i], to[i])) {
      ++v.clear;
      weightClear += w;
      v.clearSamples.push_back({from[i], to[i], w});
    }
  }
  v.samples = from.size();
  if (weightAll > 0) {
    v.fraction = weightClear / weightAll;
    for (ClearSample& c : v.clearSamples) c.weight /= weightAll;
  } else {
    // No kernel weight at all (rounding at grazing angles): count the samples instead.
    v.fraction = v.samples ? static_cast<double>(v.clear) / static_cast<double>(v.samples) : 1.0;
    for (ClearSample& c : v.clearSamples) c.weight = 1.0 / static_cast<double>(v.samples);
  }
  return v;
}

VisibilityEstimate estimateFromSamples(SampledVisibility&& sampled) {
  VisibilityEstimate e;
  e.raysCast = sampled.samples;
  e.fraction = sampled.fraction;
  e.status = sampled.clear == 0 ? VisibilityStatus::Invisible
                                : (sampled.clear == sampled.samples ? VisibilityStatus::Visible
                                                                    : VisibilityStatus::Partial);
  if (e.status == VisibilityStatus::Partial) e.clearSamples = std::move(sampled.clearSamples);
  return e;
}

}  // namespace gv
