// HSA91's original visibility: every pair of patches that can face each other gets an initial
// link, and a link's visibility is the fraction of N jittered rays between its two elements that
// reach, tested against the whole scene (Embree). The baseline the paper's blocker lists beat.
#pragma once

#include "radiosity/link_visibility.h"
#include "raycast/embree_scene.h"
#include "scene/scene.h"

namespace gv {

/// Embree works in single precision: a segment that starts or ends on a patch can "hit" another
/// patch coplanar with that one (two faces back to back, an end cap flush with a wall) at t ~ 0
/// or 1. Segment ends are pulled in by this fraction of the scene's diagonal (~16 float ulps
/// relative to the scene), and photon rays start this far along. Coplanar patches cannot block
/// a segment leaving their plane, so nothing real is lost.
inline constexpr double kRayEndOffset = 1e-6;

/// `radiosity`'s rays mode (and `bench`'s radiosity, which runs what it runs) culls by cells
/// only from this many patches on. Below it every pair is cheap to link, while the cell stage
/// can cost more than the whole solve: the furnished room (384 patches, furniture cutting its
/// air into 170 cells and 520 portals) spent 0.6 s there against 0.3 s for all of `--quality
/// draft`; the default office (423) gains little (its cells see 97 % of its pairs).
inline constexpr size_t kMinPatchesForCellCulling = 1000;

/// `rays` mode. Visible when all rays reach, Invisible when none does (HSA91 then drops the link;
/// a light path narrower than the ray spacing can be missed: the sampling error the paper's
/// conservative blocker lists remove), Partial otherwise.
///
/// With cells (PatchCellReach), only the pairs whose cells may see each other are candidates: no
/// link and no cluster sample between rooms that cannot see each other (the rays would all be
/// blocked there anyway, so the solution is the same up to sampling, at a fraction of the rays).
class RayVisibility final : public LinkVisibility {
 public:
  /// `scene`, `rays` (the shared BVH) and `cells` (if given) must outlive this. `raysPerLink`
  /// >= 1.
  RayVisibility(const Scene& scene, const EmbreeScene& rays, int raysPerLink,
                const PatchCellReach* cells = nullptr);

  std::string_view name() const override { return "rays"; }
  /// All pairs a < b of the scene's patches (n(n-1)/2), or those whose cells may see each other.
  void forEachCandidatePair(const std::function<void(uint32_t, uint32_t, TubeId)>& visit) override;
  /// raysPerLink segments between stratified points of the parts of a and b that exchange light
  /// (exchangingParts) (paired by a random
  /// permutation), each tested with EmbreeScene::occluded ignoring the two patches themselves.
  VisibilityEstimate estimate(const Element& a, const Element& b, TubeId parentTube,
                              uint64_t seed) override;
  /// The queries in parallel: estimate keeps no state and EmbreeScene::occluded is thread-safe.
  std::vector<VisibilityEstimate> estimateAll(std::span<const LinkQuery> queries) override;
  bool answersSegments() const override { return true; }
  bool everyPairIsCandidate() const override { return !cells_ || !cells_->known(); }
  const PatchCellReach* candidateCells() const override {
    return cells_ && cells_->known() ? cells_ : nullptr;
  }
  /// EmbreeScene::occluded ignoring a and b, the ends pulled in as for a link's rays.
  bool segmentBlocked(uint32_t a, const Vec3& from, uint32_t b, const Vec3& to,
                      TubeId pairTube) const override;

 private:
  const Scene& scene_;
  const EmbreeScene& rays_;
  int raysPerLink_;
  const PatchCellReach* cells_;
  Tolerance tol_;
  double endOffset_;  ///< kRayEndOffset times the scene's diagonal
};

}  // namespace gv
