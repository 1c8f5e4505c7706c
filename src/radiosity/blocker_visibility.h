// The paper's `blockers` visibility mode (§6, §7.4): initial links only for the VISIBLE and
// PARTIAL pairs of the visibility graph; each PARTIAL link carries a linespace tube whose blockers
// are reclassified on every subdivision; partial visibility from rays tested against the tube's
// blockers only (no ray casting against the scene).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <vector>

#include "linespace/blocker_geometry.h"
#include "linespace/tube.h"
#include "linespace/tube_classification.h"
#include "radiosity/link_visibility.h"
#include "scene/scene.h"
#include "visibility/visibility_graph.h"

namespace gv {

/// An INVISIBLE child interaction and the blocker that proves it (kept for viewers: paper §6,
/// "the culprit blocker(s) can be retained as proof").
struct InvisibleProof {
  uint32_t patchA = 0, patchB = 0;  ///< the patches of the two elements
  uint32_t depthA = 0, depthB = 0;  ///< the elements' depths in their quadtrees
  uint32_t blocker = 0;             ///< the patch that occludes every segment between them
};

/// `blockers` mode. Visible links never cast rays; Invisible children are dropped (the solver
/// drops links whose estimate is Invisible); Partial links get a fraction from N stratified
/// jittered segments (the sampling of `rays` mode) tested against the link's own blockers.
class BlockerVisibility final : public LinkVisibility {
 public:
  /// `scene` and `graph` (computeVisibility of that scene) must outlive this. `raysPerLink` >= 1.
  BlockerVisibility(const Scene& scene, const VisibilityGraph& graph, int raysPerLink,
                    TubeOptions options = defaultOptions());

  /// The tube options `blockers` mode uses: straddling blockers split, PUNTs not sent to the
  /// stabbing LP (on the default office it removed 2 % of the PUNTs for 3x the run time:
  /// docs/BENCHMARKS.md).
  static TubeOptions defaultOptions() {
    TubeOptions o;
    o.resolvePunts = false;
    return o;
  }

  std::string_view name() const override { return "blockers"; }
  /// The graph's interactions (VISIBLE and PARTIAL pairs); INVISIBLE pairs never get a link.
  void forEachCandidatePair(const std::function<void(uint32_t, uint32_t, TubeId)>& visit) override;
  /// Reclassifies the parent tube's blockers against (a, b) (§6.2): VISIBLE parents give Visible
  /// with no work; an occluding blocker gives Invisible; no impinging blocker gives Visible;
  /// otherwise Partial with a new tube holding the blockers kept.
  VisibilityEstimate estimate(const Element& a, const Element& b, TubeId parentTube,
                              uint64_t seed) override;
  /// The classifications and rays in parallel; tubes, proofs and statistics kept in query order.
  std::vector<VisibilityEstimate> estimateAll(std::span<const LinkQuery> queries) override;
  bool answersSegments() const override { return true; }
  /// A VISIBLE pair's segments are clear; a PARTIAL pair's are tested against its blocker list
  /// (every first hit is in it, so the answer is the scene's).
  bool segmentBlocked(uint32_t a, const Vec3& from, uint32_t b, const Vec3& to,
                      TubeId pairTube) const override;

  /// Blocker outcomes and tube statuses per refinement level (a.depth + b.depth).
  const LinespaceStats& stats() const { return stats_; }
  const std::vector<InvisibleProof>& proofs() const { return proofs_; }
  /// The statistics as JSON (per level and totals).
  nlohmann::json statsJson() const;

 private:
  struct TubeRecord {
    uint32_t first = 0, count = 0;  ///< blockers_[first .. first + count)
  };
  /// What estimate finds before it keeps anything: reads the stored tubes only, so any number of
  /// evaluations may run at once between the commits.
  struct Evaluation {
    VisibilityEstimate estimate;
    size_t level = 0;                ///< a.depth + b.depth
    bool inherited = false;          ///< a VISIBLE parent: nothing classified
    OutcomeCounts counts;            ///< the classification's outcomes
    InvisibleProof proof;            ///< Invisible: kept in proofs()
    std::vector<uint32_t> blockers;  ///< Partial: kept as the link's tube
  };
  Evaluation evaluate(const Element& a, const Element& b, TubeId parentTube, uint64_t seed) const;
  /// Keeps an evaluation's tube, proof and statistics; returns its estimate.
  VisibilityEstimate commit(Evaluation&& evaluation);
  TubeId addTube(const std::vector<uint32_t>& blockers);

  const Scene& scene_;
  Tolerance tol_;
  BlockerTable table_;
  int raysPerLink_;
  TubeOptions options_;
  std::vector<TubeRecord> tubes_;  ///< tube 0: the shared VISIBLE tube (no blockers)
  std::vector<uint32_t> blockers_;
  const VisibilityGraph& graph_;
  LinespaceStats stats_;
  std::vector<InvisibleProof> proofs_;
};

}  // namespace gv
