// Sampled link visibility (HSA91 §3 jittered rays, kernel-weighted). See link_sampling.h.
#include "radiosity/link_sampling.h"

#include <algorithm>
#include <cmath>
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
  // Only a link both blocked and clear can owe its light to a crack (a wall with a crack in it);
  // testing every clear sample would double the rays of the links in plain view.
  if (v.clear > 0 && v.clear < v.samples) {
    std::erase_if(v.clearSamples, [&](const ClearSample& c) {
      if (!throughCrack(c.from, c.to, tol, blocked)) return false;
      --v.clear;
      weightClear -= c.weight;
      return true;
    });
    weightClear = std::max(0.0, weightClear);
  }
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

bool throughCrack(const Vec3& from, const Vec3& to, const Tolerance& tol,
                  const std::function<bool(const Vec3& from, const Vec3& to)>& blocked) {
  const Vec3 d = to - from;
  const double len = length(d);
  if (!(len > 0)) return false;
  const Vec3 axis = d * (1.0 / len);
  // Two unit directions perpendicular to the segment and to each other: a crack narrower than
  // the shift is left by at least one of them (each has a component across it of ≥ shift / √2).
  const auto [u, w] = perpendicularFrame(axis);
  const double shift = kCrackWidthInModelTolerances * tol.planeOffset();
  return blocked(from + u * shift, to + u * shift) || blocked(from + w * shift, to + w * shift);
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
