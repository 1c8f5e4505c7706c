// The visibility interface of the hierarchical radiosity solver: which patch pairs get initial
// links, and the visibility of a link between two elements, refined from its parent link's state.
// The paper's blocker lists and linespace tubes (§5, §6) plug in here as one implementation; the
// ray-sampling oracles of HSA91 (`rays`) and Haines & Wallace's shafts (`shaft`) are others.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <string_view>
#include <vector>

#include "linespace/visibility_status.h"
#include "radiosity/element_tree.h"
#include "util/parallel_for.h"
#include "visibility/patch_cell_reach.h"

namespace gv {

// VisibilityStatus (the paper's three classes, §4.2, §6.2) is defined by the linespace module.

/// Opaque per-link state owned by a LinkVisibility (a tube: blocker list + linespace hull, a shaft
/// candidate list, ...). kNoTube for oracles that keep none and for "no parent" (initial links).
using TubeId = uint32_t;
inline constexpr TubeId kNoTube = std::numeric_limits<TubeId>::max();

/// One sampled segment between two elements that light passes: its ends and its share of the
/// link's kernel-weighted samples (the shares of a link's clear samples sum to its fraction).
struct ClearSample {
  Vec3 from, to;  ///< on the first and on the second element
  double weight = 0;
};

/// What an oracle says about the light path between two elements.
struct VisibilityEstimate {
  VisibilityStatus status = VisibilityStatus::Visible;
  /// Estimated fraction of the unoccluded form factor that is not blocked, in [0, 1]: 1 for
  /// Visible, 0 for Invisible. The solver multiplies the exact unoccluded form factor by it.
  double fraction = 1.0;
  TubeId tube = kNoTube;  ///< state handed back as `parentTube` when this link is refined
  uint64_t raysCast = 0;  ///< work done, for the statistics
  /// Partial links: the clear samples, i.e. where light passes. The solver gathers through them
  /// from the parts of the elements they end on rather than from the elements' means: the part
  /// of a source that a receiver sees is often not its average (the floor of the lit room, not
  /// of the corridor that the same floor patch also covers). Empty otherwise.
  std::vector<ClearSample> clearSamples;
};

/// One link whose visibility is wanted: estimate(*a, *b, parentTube, seed).
struct LinkQuery {
  const Element* a = nullptr;
  const Element* b = nullptr;
  TubeId parentTube = kNoTube;
  uint64_t seed = 0;
};

/// A visibility oracle for links. The solver calls, in order: forEachCandidatePair once, then
/// estimate (or estimateAll, for a batch) for every link it creates (initial links with
/// parentTube = the pair's tube from forEachCandidatePair; a refined link's children with the
/// parent's tube).
///
/// Where the paper's `blockers` mode plugs in: forEachCandidatePair enumerates the VisibilityGraph
/// (VISIBLE and PARTIAL pairs only, each with a tube holding its blocker list B(S, R));
/// estimate(a, b, parentTube) reclassifies the parent's blockers against the child pair (§6.2),
/// returns Visible with fraction 1 when none impinges (no rays), Invisible when one occludes
/// completely, else Partial with a fraction from rays tested against the child's blockers only.
class LinkVisibility {
 public:
  virtual ~LinkVisibility() = default;

  /// Short name for statistics ("rays", "shaft", "blockers").
  virtual std::string_view name() const = 0;

  /// Calls `visit(a, b, tube)` for every unordered patch pair a < b that may exchange light.
  /// Pairs not visited never get a link. The solver still drops pairs that cannot face.
  virtual void forEachCandidatePair(
      const std::function<void(uint32_t a, uint32_t b, TubeId tube)>& visit) = 0;

  /// Visibility between elements `a` and `b` (on different patches), refining `parentTube`.
  /// `seed` makes any sampling deterministic per link: equal inputs give equal answers.
  virtual VisibilityEstimate estimate(const Element& a, const Element& b, TubeId parentTube,
                                      uint64_t seed) = 0;

  /// estimate for every query, answer i for query i: the same answers, and the same state
  /// afterwards (tube ids, statistics), as estimate called on each in index order, whatever the
  /// number of threads. Implementations may evaluate the queries on oneTBB parallel loops (the
  /// caller's task arena bounds the threads) and then keep their state in index order; this
  /// default calls estimate one after another.
  virtual std::vector<VisibilityEstimate> estimateAll(std::span<const LinkQuery> queries) {
    std::vector<VisibilityEstimate> out;
    out.reserve(queries.size());
    for (const LinkQuery& q : queries) out.push_back(estimate(*q.a, *q.b, q.parentTube, q.seed));
    return out;
  }

  /// Clustering (patch_clusters.h) links far groups of patches through single sampled segments
  /// rather than through links per pair, and asks about them here. Oracles that cannot answer
  /// say false, and the solver then links every candidate pair.
  virtual bool answersSegments() const { return false; }
  /// Whether every pair of patches is a candidate (forEachCandidatePair visits all n(n-1)/2, and
  /// with tube kNoTube), so that the solver need not keep the candidates to look pairs up.
  virtual bool everyPairIsCandidate() const { return false; }
  /// When the candidates are exactly the pairs whose cells may see each other (all with tube
  /// kNoTube): those cells, so that the solver looks pairs up through them instead of listing
  /// them (hundreds of millions on a big building). Null otherwise.
  virtual const PatchCellReach* candidateCells() const { return nullptr; }
  /// Whether the segment from `from` on patch `a` to `to` on patch `b` (a candidate pair, with
  /// the tube forEachCandidatePair gave it) is blocked. Thread-safe. Only if answersSegments().
  virtual bool segmentBlocked(uint32_t /*a*/, const Vec3& /*from*/, uint32_t /*b*/,
                              const Vec3& /*to*/, TubeId /*pairTube*/) const {
    return true;
  }
};

/// estimateAll for oracles split into a read-only `evaluate(query)` (run in parallel) and a
/// `commit(evaluation&&)` that stores state (run in query order), so the answers, tube ids and
/// statistics are those of calling estimate in order.
template <class Evaluate, class Commit>
std::vector<VisibilityEstimate> evaluateThenCommit(std::span<const LinkQuery> queries,
                                                   Evaluate&& evaluate, Commit&& commit) {
  using Evaluation = decltype(evaluate(queries[0]));
  std::vector<Evaluation> evaluations(queries.size());
  parallelForEach(queries.size(), [&](size_t i) { evaluations[i] = evaluate(queries[i]); });
  std::vector<VisibilityEstimate> out;
  out.reserve(queries.size());
  for (Evaluation& e : evaluations) out.push_back(commit(std::move(e)));
  return out;
}

}  // namespace gv
