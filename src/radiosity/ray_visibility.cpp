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
  const std::vector<Vec3> from = stratifiedPoints(a.polygon.vertices, raysPerLink_, rng);
  std::vector<Vec3> to = stratifiedPoints(b.polygon.vertices, raysPerLink_, rng);
  // Pair the strata of a with a random permutation of b's so that the rays do not all run
  // parallel (stratum i to stratum i would sample only "translated" directions).
  for (size_t i = to.size(); i > 1; --i) std::swap(to[i - 1], to[rng.next() % i]);
  int clear = 0;
  for (size_t i = 0; i < from.size(); ++i)
    if (!rays_.occluded(from[i], to[i], a.patch, b.patch)) ++clear;
  VisibilityEstimate e;
  e.raysCast = from.size();
  e.fraction = static_cast<double>(clear) / static_cast<double>(from.size());
  e.status = clear == 0 ? VisibilityStatus::Invisible
                        : (clear == static_cast<int>(from.size()) ? VisibilityStatus::Visible
                                                                  : VisibilityStatus::Partial);
  return e;
}

}  // namespace gv
