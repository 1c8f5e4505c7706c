// `rays` visibility mode: jittered rays against the whole scene. HSA91 §3.
#include "radiosity/ray_visibility.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "radiosity/form_factor.h"
#include "radiosity/link_sampling.h"
#include "util/parallel_for.h"

namespace gv {

RayVisibility::RayVisibility(const Scene& scene, const EmbreeScene& rays, int raysPerLink,
                             const PatchCellReach* cells)
    : scene_(scene),
      rays_(rays),
      raysPerLink_(raysPerLink),
      cells_(cells),
      tol_(scene.tolerance()),
      endOffset_(kRayEndOffset * scene.bounds().diagonal()) {
  if (raysPerLink < 1) throw std::invalid_argument("rays per link must be at least 1");
}

void RayVisibility::forEachCandidatePair(
    const std::function<void(uint32_t, uint32_t, TubeId)>& visit) {
  if (cells_) {
    cells_->forEachPair([&](uint32_t a, uint32_t b) { visit(a, b, kNoTube); });
    return;
  }
  const auto n = static_cast<uint32_t>(scene_.patches.size());
  for (uint32_t a = 0; a < n; ++a)
    for (uint32_t b = a + 1; b < n; ++b) visit(a, b, kNoTube);
}

VisibilityEstimate RayVisibility::estimate(const Element& a, const Element& b, TubeId,
                                           uint64_t seed) {
  SplitMix64 rng(seed);
  std::optional<SampledVisibility> v = sampleLinkVisibility(
      a.polygon, b.polygon, raysPerLink_, tol_, rng, [&](const Vec3& p, const Vec3& q) {
        return segmentBlocked(a.patch, p, b.patch, q, kNoTube);
      });
  if (!v) return {VisibilityStatus::Invisible, 0.0, kNoTube, 0, {}};
  return estimateFromSamples(std::move(*v));
}

bool RayVisibility::segmentBlocked(uint32_t a, const Vec3& from, uint32_t b, const Vec3& to,
                                   TubeId) const {
  const Vec3 d = to - from;
  const double len = length(d);
  const double pull = len > 0 ? std::min(0.01, endOffset_ / len) : 0.0;
  return rays_.occluded(from + d * pull, to - d * pull, a, b);
}

std::vector<VisibilityEstimate> RayVisibility::estimateAll(std::span<const LinkQuery> queries) {
  std::vector<VisibilityEstimate> out(queries.size());
  parallelForEach(queries.size(), [&](size_t i) {
    const LinkQuery& q = queries[i];
    out[i] = estimate(*q.a, *q.b, q.parentTube, q.seed);
  });
  return out;
}

}  // namespace gv
