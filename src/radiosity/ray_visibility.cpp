// `rays` visibility mode: jittered rays against the whole scene. HSA91 §3.
#include "radiosity/ray_visibility.h"

#include <algorithm>
#include <stdexcept>

#include "radiosity/polygon_sampling.h"

namespace gv {

RayVisibility::RayVisibility(const Scene& scene, const EmbreeScene& rays, int raysPerLink)
    : scene_(scene), rays_(rays), raysPerLink_(raysPerLink) {
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
  const SampleSegments samples = sampleSegments(a.polygon, b.polygon, raysPerLink_, rng);
  const double fraction = unblockedFraction(
      a.polygon, b.polygon, samples,
      [&](const Vec3& p, const Vec3& q) { return rays_.occluded(p, q, a.patch, b.patch); });
  VisibilityEstimate e;
  e.raysCast = samples.from.size();
  e.fraction = fraction;
  e.status = fraction == 0
                 ? VisibilityStatus::Invisible
                 : (fraction == 1 ? VisibilityStatus::Visible : VisibilityStatus::Partial);
  return e;
}

}  // namespace gv
