// `shaft` link visibility (Haines & Wallace, "Shaft culling for efficient ray-cast radiosity",
// 1991; the baseline of paper §6.3): per link, the patches meeting the convex hull of its two
// elements are the only possible occluders; visibility rays are tested against that candidate
// list alone, and a refined link's list is culled from its parent's.
#pragma once

#include <cstdint>
#include <vector>

#include "radiosity/link_visibility.h"
#include "scene/scene.h"

namespace gv {

/// True when the open segment from `from` to `to` (parameters in (0, 1)) crosses the convex
/// polygon `p` (two-sided; a crossing on its boundary counts, within `eps`). A segment lying in
/// the polygon's plane does not cross it.
bool segmentCrossesPolygon(const Vec3& from, const Vec3& to, const ConvexPolygon& p, double eps);

/// `shaft` mode. Every pair of patches is a candidate (as in `rays`). A link's candidate list
/// holds the patches other than its two that meet conv(a ∪ b) (meetsConvexHull, conservative):
/// empty → Visible with no rays (nothing can block); otherwise `raysPerLink` jittered segments
/// (the same sampling as RayVisibility) are tested against the list only: none clear →
/// Invisible, all clear → Visible, else Partial. Children cull their parent's list.
class ShaftVisibility final : public LinkVisibility {
 public:
  /// `scene` must outlive this. `raysPerLink` >= 1.
  ShaftVisibility(const Scene& scene, int raysPerLink);

  std::string_view name() const override { return "shaft"; }
  void forEachCandidatePair(const std::function<void(uint32_t, uint32_t, TubeId)>& visit) override;
  VisibilityEstimate estimate(const Element& a, const Element& b, TubeId parentTube,
                              uint64_t seed) override;
  /// The hull tests and rays in parallel, the candidate lists stored in query order.
  std::vector<VisibilityEstimate> estimateAll(std::span<const LinkQuery> queries) override;

  /// Candidates examined by hull tests so far, and the mean list length of the links made.
  uint64_t hullTests() const { return hullTests_; }
  double meanCandidates() const {
    return lists_ == 0 ? 0.0 : static_cast<double>(listEntries_) / static_cast<double>(lists_);
  }

 private:
  /// What estimate finds before it stores anything: reads the stored lists only, so any number
  /// of evaluations may run at once between the stores.
  struct Evaluation {
    VisibilityEstimate estimate;
    std::vector<uint32_t> list;  ///< the candidates, stored as the link's tube if `keep`
    bool keep = false;
    uint64_t hullTests = 0;
  };
  Evaluation evaluate(const Element& a, const Element& b, TubeId parentTube, uint64_t seed) const;
  /// Stores an evaluation's list and counts it; returns its estimate.
  VisibilityEstimate commit(Evaluation&& evaluation);
  TubeId store(std::vector<uint32_t> list);

  const Scene& scene_;
  int raysPerLink_;
  Tolerance tol_;
  double eps_;
  std::vector<std::vector<uint32_t>> tubes_;  ///< candidate lists; tube 0 is the empty list
  uint64_t hullTests_ = 0, lists_ = 0, listEntries_ = 0;
};

}  // namespace gv
