// `blockers` visibility mode: visibility-graph links, tubes reclassified on refinement, rays
// against blocker lists. Paper §6.2, §6.3, §7.4.
#include "radiosity/blocker_visibility.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "linespace/contact_blockers.h"
#include "linespace/segment_blocking.h"
#include "radiosity/link_sampling.h"
#include "util/check.h"
#include "util/parallel_for.h"

namespace gv {
namespace {

constexpr TubeId kVisibleTube = 0;

nlohmann::json levelJson(const LevelStats& l) {
  const OutcomeCounts& o = l.blockers;
  return {{"tubes", l.tubes},
          {"visible", l.visible},
          {"partial", l.partial},
          {"invisible", l.invisible},
          {"inherited_visible", l.inheritedVisible},
          {"blocker_tests", o.total()},
          {"occludes", o.occludes},
          {"impinges", o.impinges},
          {"disjoint", o.disjoint},
          {"disjoint_by_planes", o.byPlanes},
          {"punt", o.punt},
          {"straddling", o.straddling},
          {"punts_tested", o.puntsTested},
          {"punts_removed_by_stabbing", o.puntsRemoved},
          {"invisible_by_coplanar_blockers", o.coplanarCovers}};
}

}  // namespace

BlockerVisibility::BlockerVisibility(const Scene& scene, const VisibilityGraph& graph,
                                     int raysPerLink, TubeOptions options)
    : scene_(scene),
      tol_(scene.tolerance()),
      table_(scene),
      raysPerLink_(raysPerLink),
      options_(options),
      graph_(graph) {
  if (raysPerLink < 1) throw std::invalid_argument("rays per link must be at least 1");
  tubes_.push_back({});  // kVisibleTube
}

TubeId BlockerVisibility::addTube(const std::vector<uint32_t>& blockers) {
  const TubeRecord rec{static_cast<uint32_t>(blockers_.size()),
                       static_cast<uint32_t>(blockers.size())};
  blockers_.insert(blockers_.end(), blockers.begin(), blockers.end());
  tubes_.push_back(rec);
  return static_cast<TubeId>(tubes_.size() - 1);
}

void BlockerVisibility::forEachCandidatePair(
    const std::function<void(uint32_t, uint32_t, TubeId)>& visit) {
  // Each pair's blockers: the graph's list plus the patches resting on S or R (contact covers,
  // which propagation's "seen from S or R" lists miss; contact_blockers.h).
  const std::vector<std::vector<uint32_t>> contacts = contactBlockers(scene_);
  std::vector<uint32_t> list;
  for (const Interaction& in : graph_.interactions) {
    if (in.s >= scene_.patches.size() || in.r >= scene_.patches.size())
      throw std::invalid_argument("visibility graph does not belong to this scene");
    list = in.blockers;
    for (const uint32_t end : {in.s, in.r})
      for (const uint32_t c : contacts[end])
        if (c != in.s && c != in.r) list.push_back(c);
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    visit(in.s, in.r, list.empty() ? kVisibleTube : addTube(list));
  }
}

BlockerVisibility::Evaluation BlockerVisibility::evaluate(const Element& a, const Element& b,
                                                          TubeId parentTube, uint64_t seed) const {
  CHECK_MSG(parentTube < tubes_.size(), "blockers mode: a link without a tube from this oracle");
  Evaluation out;
  out.level = a.depth + b.depth;
  VisibilityEstimate& e = out.estimate;
  if (parentTube == kVisibleTube) {
    out.inherited = true;
    e.tube = kVisibleTube;
    return out;
  }
  const TubeRecord parent = tubes_[parentTube];
  const std::span<const uint32_t> list(blockers_.data() + parent.first, parent.count);
  TubeVerdict v = classifyTube(Tube(a.polygon, b.polygon), list, table_, tol_, options_);
  out.counts = v.counts;
  switch (v.status) {
    case VisibilityStatus::Invisible:
      out.proof = {a.patch, b.patch, a.depth, b.depth, v.proof};
      e.status = VisibilityStatus::Invisible;
      e.fraction = 0;
      return out;
    case VisibilityStatus::Visible:
      e.tube = kVisibleTube;
      return out;
    case VisibilityStatus::Partial:
      break;
  }
  // The sampling of `rays` mode (link_sampling.h), tested against the kept blockers only.
  SplitMix64 rng(seed);
  std::optional<SampledVisibility> sampled = sampleLinkVisibility(
      a.polygon, b.polygon, raysPerLink_, tol_, rng, [&](const Vec3& p, const Vec3& q) {
        return gv::segmentBlocked(p, q, v.blockers, table_, tol_.length());
      });
  // No part of one faces the other: the unoccluded form factor is 0 and so is the transfer,
  // whatever the fraction; the link stays PARTIAL as the classification said.
  e.status = VisibilityStatus::Partial;
  e.raysCast = sampled ? sampled->samples : 0;
  e.fraction = sampled ? sampled->fraction : 0.0;
  if (sampled) e.clearSamples = std::move(sampled->clearSamples);
  out.blockers = std::move(v.blockers);
  return out;
}

VisibilityEstimate BlockerVisibility::commit(Evaluation&& evaluation) {
  LevelStats& level = stats_.level(evaluation.level);
  VisibilityEstimate e = std::move(evaluation.estimate);
  if (evaluation.inherited) {
    ++level.inheritedVisible;
    ++level.visible;
    return e;
  }
  ++level.tubes;
  level.blockers += evaluation.counts;
  switch (e.status) {
    case VisibilityStatus::Invisible:
      ++level.invisible;
      proofs_.push_back(evaluation.proof);
      break;
    case VisibilityStatus::Visible:
      ++level.visible;
      break;
    case VisibilityStatus::Partial:
      ++level.partial;
      e.tube = addTube(evaluation.blockers);
      break;
  }
  return e;
}

bool BlockerVisibility::segmentBlocked(uint32_t, const Vec3& from, uint32_t, const Vec3& to,
                                       TubeId pairTube) const {
  CHECK_MSG(pairTube < tubes_.size(), "blockers mode: a segment without a tube from this oracle");
  if (pairTube == kVisibleTube) return false;
  const TubeRecord t = tubes_[pairTube];
  return gv::segmentBlocked(from, to, std::span(blockers_.data() + t.first, t.count), table_,
                            tol_.length());
}

VisibilityEstimate BlockerVisibility::estimate(const Element& a, const Element& b,
                                               TubeId parentTube, uint64_t seed) {
  return commit(evaluate(a, b, parentTube, seed));
}

std::vector<VisibilityEstimate> BlockerVisibility::estimateAll(std::span<const LinkQuery> queries) {
  return evaluateThenCommit(
      queries, [&](const LinkQuery& q) { return evaluate(*q.a, *q.b, q.parentTube, q.seed); },
      [&](Evaluation&& e) { return commit(std::move(e)); });
}

nlohmann::json BlockerVisibility::statsJson() const {
  nlohmann::json levels = nlohmann::json::array();
  for (size_t l = 0; l < stats_.levels.size(); ++l) {
    nlohmann::json j = levelJson(stats_.levels[l]);
    j["level"] = l;
    levels.push_back(j);
  }
  return {{"levels", levels},
          {"total", levelJson(stats_.total())},
          {"tubes_stored", tubes_.size()},
          {"blocker_ids_stored", blockers_.size()},
          {"invisible_proofs", proofs_.size()}};
}

}  // namespace gv
