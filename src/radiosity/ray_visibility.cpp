// `rays` visibility mode: jittered rays against the whole scene. HSA91 §3.
#include "radiosity/ray_visibility.h"

#include <algorithm>
#include <stdexcept>

#include "radiosity/form_factor.h"
#include "radiosity/polygon_sampling.h"

namespace gv {

RayVisibility::RayVisibility(const Scene& scene, const EmbreeScene& rays, int raysPerLink)
    : scene_(scene),
      rays_(rays),
      raysPerLink_(raysPerLink),
      tol_(scene.tolerance()),
      endOffset_(kRayEndOffset * scene.bounds().diagonal()) {
  if (raysPerLink < 1) throw std::invalid_argument("rays per link must be at least 1");
}

void RayVisibility::forEachCandidatePair(
    const std::function<void(uint32_t, uint32_t, TubeId)>& visit) {
  const auto n = static_cast<uint32_t>(scene_.patches.size());
  for (uint32_t a = 0; a < n; ++a)
    for (uint32_t b = a + 1; b < n; ++b) visit(a, b, kNoTube);
}

VisibilityEstimate RayVisibility::estimate(const Element& a, const Element& b, TubeId,
                                           uint64_t seed) {
  SplitMix64 rng(seed);
  // Sample only the parts that exchange light (what the form factor integrates over).
  const std::optional<ExchangingParts> parts = exchangingParts(a.polygon, b.polygon, tol_);
  if (!parts) return {VisibilityStatus::Invisible, 0.0, kNoTube, 0};
  const std::vector<Vec3> from = stratifiedPoints(parts->a.vertices, raysPerLink_, rng);
  std::vector<Vec3> to = stratifiedPoints(parts->b.vertices, raysPerLink_, rng);
  // Pair the strata of a with a random permutation of b's so that the rays do not all run
  // parallel (stratum i to stratum i would sample only "translated" directions).
  for (size_t i = to.size(); i > 1; --i) std::swap(to[i - 1], to[rng.next() % i]);
  int clear = 0;
  double weightClear = 0, weightAll = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    const double w = kernelWeight(from[i], a.polygon.plane.normal, to[i], b.polygon.plane.normal);
    weightAll += w;
    const Vec3 d = to[i] - from[i];
    const double len = length(d);
    const double pull = len > 0 ? std::min(0.01, endOffset_ / len) : 0.0;
    if (!rays_.occluded(from[i] + d * pull, to[i] - d * pull, a.patch, b.patch)) {
      ++clear;
      weightClear += w;
    }
  }
  VisibilityEstimate e;
  e.raysCast = from.size();
  e.fraction = weightAll > 0 ? weightClear / weightAll
                             : static_cast<double>(clear) / static_cast<double>(from.size());
  e.status = clear == 0 ? VisibilityStatus::Invisible
                        : (clear == static_cast<int>(from.size()) ? VisibilityStatus::Visible
                                                                  : VisibilityStatus::Partial);
  return e;
}

}  // namespace gv
