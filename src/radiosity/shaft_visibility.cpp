// `shaft` visibility: candidate lists from convex-hull culling, rays against the list only.
// Haines & Wallace 1991 as the paper's §6.3 baseline; hull test of paper §5.
#include "radiosity/shaft_visibility.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "radiosity/form_factor.h"
#include "radiosity/link_sampling.h"
#include "util/parallel_for.h"
#include "visibility/hull_overlap.h"

namespace gv {

bool segmentCrossesPolygon(const Vec3& from, const Vec3& to, const ConvexPolygon& p, double eps) {
  const double df = p.plane.distance(from), dt = p.plane.distance(to);
  if (!((df > 0 && dt < 0) || (df < 0 && dt > 0))) return false;
  const double t = df / (df - dt);
  const Vec3 x = from + (to - from) * t;
  const Vec3& n = p.plane.normal;
  const std::vector<Vec3>& v = p.vertices;
  for (size_t i = 0; i < v.size(); ++i) {
    const Vec3 edge = v[(i + 1) % v.size()] - v[i];
    // Signed distance of x from edge i's line within the plane, positive inside (CCW about n).
    const double inside = dot(cross(edge, x - v[i]), n) / length(edge);
    if (inside < -eps) return false;
  }
  return true;
}

ShaftVisibility::ShaftVisibility(const Scene& scene, int raysPerLink)
    : scene_(scene), raysPerLink_(raysPerLink), tol_(scene.tolerance()), eps_(tol_.length()) {
  if (raysPerLink < 1) throw std::invalid_argument("rays per link must be at least 1");
  tubes_.emplace_back();  // tube 0: nothing can block
}

void ShaftVisibility::forEachCandidatePair(
    const std::function<void(uint32_t, uint32_t, TubeId)>& visit) {
  const auto n = static_cast<uint32_t>(scene_.patches.size());
  for (uint32_t a = 0; a < n; ++a)
    for (uint32_t b = a + 1; b < n; ++b) visit(a, b, kNoTube);
}

TubeId ShaftVisibility::store(std::vector<uint32_t> list) {
  ++lists_;
  listEntries_ += list.size();
  if (list.empty()) return 0;
  tubes_.push_back(std::move(list));
  return static_cast<TubeId>(tubes_.size() - 1);
}

ShaftVisibility::Evaluation ShaftVisibility::evaluate(const Element& a, const Element& b,
                                                      TubeId parentTube, uint64_t seed) const {
  const Tolerance& tol = tol_;
  Evaluation out;
  std::vector<uint32_t>& list = out.list;
  auto consider = [&](uint32_t p) {
    if (p == a.patch || p == b.patch) return;
    ++out.hullTests;
    if (meetsConvexHull(scene_.patches[p].polygon, a.polygon, b.polygon, tol)) list.push_back(p);
  };
  if (parentTube == kNoTube) {
    for (uint32_t p = 0; p < scene_.patches.size(); ++p) consider(p);
  } else {
    // The child's hull lies inside the parent's, so only the parent's candidates can meet it.
    // (No store runs during evaluations, so the parent's list stays where it is.)
    for (uint32_t p : tubes_.at(parentTube)) consider(p);
  }
  if (list.empty()) {
    out.keep = true;
    return out;  // Visible, fraction 1, no rays
  }
  SplitMix64 rng(seed);
  std::optional<SampledVisibility> v = sampleLinkVisibility(
      a.polygon, b.polygon, raysPerLink_, tol_, rng, [&](const Vec3& p, const Vec3& q) {
        return std::any_of(list.begin(), list.end(), [&](uint32_t c) {
          return segmentCrossesPolygon(p, q, scene_.patches[c].polygon, eps_);
        });
      });
  if (!v) {
    out.estimate = {VisibilityStatus::Invisible, 0.0, kNoTube, 0, {}};
    return out;
  }
  out.estimate = estimateFromSamples(std::move(*v));
  out.keep = true;
  return out;
}

VisibilityEstimate ShaftVisibility::commit(Evaluation&& evaluation) {
  hullTests_ += evaluation.hullTests;
  VisibilityEstimate e = std::move(evaluation.estimate);
  if (evaluation.keep) e.tube = store(std::move(evaluation.list));
  return e;
}

VisibilityEstimate ShaftVisibility::estimate(const Element& a, const Element& b, TubeId parentTube,
                                             uint64_t seed) {
  return commit(evaluate(a, b, parentTube, seed));
}

std::vector<VisibilityEstimate> ShaftVisibility::estimateAll(std::span<const LinkQuery> queries) {
  return evaluateThenCommit(
      queries, [&](const LinkQuery& q) { return evaluate(*q.a, *q.b, q.parentTube, q.seed); },
      [&](Evaluation&& e) { return commit(std::move(e)); });
}

}  // namespace gv
