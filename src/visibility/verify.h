// Independent verification of a visibility result by ray casting (Embree), per the contract of
// ../shared/DESIGN.md: shares nothing with propagation but the scene.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "visibility/visibility_graph.h"

namespace gv {

/// Rays and segments start this fraction of the scene's diagonal away from their patches: Embree
/// works in single precision (~1e-7 relative), and a patch overlapping the start point in its own
/// plane (a box resting on a floor) would otherwise be "met" at distance 0 — contact, not sight.
inline constexpr double kVerifyContactDistance = 1e-6;

/// Violations described in VerifyReport::examples (the rest are only counted).
inline constexpr size_t kVerifyExamples = 10;

struct VerifyOptions {
  uint64_t rays = 200000;     ///< random rays from random patch points, cosine-distributed
  uint64_t segments = 50000;  ///< random segments between listed pairs
  uint32_t seed = 1;
  /// Listed pairs sampled for the tightness figure (VerifyReport::excess): each gets
  /// kTightnessSegments segments; a pair none of which is free counts as excess.
  uint64_t tightnessPairs = 2000;
  /// Hits of the rays from patches closer than this fraction of the scene's diagonal to their
  /// start are contact, not sight (skipped). At least kVerifyContactDistance; up to the model
  /// tolerance (kRelativeModelEpsilon), the strictest reading of the contract's contact rule.
  double rayContact = kVerifyContactDistance;
  /// Pairs not listed, drawn uniformly (S and R uniform among the patches), each tried with up
  /// to kUnlistedSegments front-to-front segments: a free one is a missing pair. The rays find a
  /// missed pair in proportion to its solid angle; these find a small patch's as often as a
  /// large one's (on session 32's q3-oacmpdm3 result, whose 0.35-square-unit bevel patch 3130
  /// missed pairs, 10^6 rays found none and 10^7 draws of these 65). 0: off.
  uint64_t unlistedPairs = 0;
};
/// Segments tried per unlisted pair (VerifyOptions::unlistedPairs).
inline constexpr int kUnlistedSegments = 16;

/// Segments per sampled pair in the tightness figure (../shared/DESIGN.md: "none of 48").
inline constexpr int kTightnessSegments = 48;

struct VerifyReport {
  uint64_t rays = 0, raysHittingFront = 0;
  uint64_t missingPairs = 0;  ///< a ray from S met R's front first, (S, R) not listed
  uint64_t segments = 0, blockedSegments = 0;
  uint64_t blockedVisible = 0;   ///< a segment of a VISIBLE pair is blocked
  uint64_t missingBlockers = 0;  ///< the first patch met from S or R is not in the list
  /// Hits of a segment moved off S and R by kVerifyContactDistance that the segment between the
  /// sampled points of S and R itself does not cross (nearly coplanar, nearly touching patches):
  /// not segments of the contract, so not violations. Counted to show how often it happens.
  uint64_t offsetOnlyHits = 0;
  /// Unlisted first hits of the offset segment behind a listed blocker that the segment between
  /// the sampled points meets first, closer than kVerifyContactDistance to its end (the offset
  /// segment starts past it): the contract's first hit is that listed one, so not violations.
  uint64_t contactFirstHits = 0;
  /// Rays from S whose first hit R faces S from S's own plane (within the model tolerance: a
  /// wall's foot on a floor, both a little out of true): a gap below the scene's resolution, so
  /// not a sightline of the contract; counted, not violations.
  uint64_t contactRays = 0;
  uint64_t invalidPairs = 0;  ///< listed pairs with ids out of range
  /// Unlisted pairs drawn (VerifyOptions::unlistedPairs), of them those with a front-to-front
  /// segment (tried), and those with a free one: missing pairs, found by segments rather than
  /// by rays. Free means Embree meets nothing between the offset ends and a scan of every patch
  /// in double precision confirms it (a crossing within the length tolerance of a patch's edge
  /// counts as met; see unlistedThroughCracks for those within the contact distance).
  uint64_t unlistedDrawn = 0, unlistedTried = 0, missingUnlisted = 0;
  /// Unlisted pairs whose only free segments pass a patch's edge closer than
  /// kVerifyContactDistance (a crack where two faces meet, closed by the tolerance policy):
  /// counted to show them, not violations.
  uint64_t unlistedThroughCracks = 0;
  /// Tightness: listed pairs sampled (uniformly among the listed ones) and, of them, those for
  /// which none of kTightnessSegments front-to-front segments is free: listed beyond what rays
  /// see. excess / tightnessPairs at most 0.5 means the list is at most about twice the visible
  /// pairs (issue #17's target). Not a violation: the contract is conservative, not exact.
  uint64_t tightnessPairs = 0, excess = 0;
  std::vector<std::string> examples;  ///< the first few violations, described
  bool ok() const {
    return missingPairs + missingUnlisted + blockedVisible + missingBlockers + invalidPairs == 0;
  }
};

/// Checks `graph` on `scene` (patch ids = indices of scene.patches):
/// - rays from area-weighted random points of random patches, cosine-distributed about the
///   normal: when the first patch met is met on its front, the pair must be listed;
/// - segments between random points of listed pairs (front to front): blocked segments of VISIBLE
///   pairs are errors, and the first patch met from either end must be in the blocker list;
/// - the tightness figure (VerifyOptions::tightnessPairs);
/// - segments of unlisted pairs (VerifyOptions::unlistedPairs): a free one is a missing pair.
VerifyReport verifyVisibility(const Scene& scene, const VisibilityGraph& graph,
                              const VerifyOptions& options = {});

}  // namespace gv
