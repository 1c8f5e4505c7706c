// Visibility propagation (paper §4): depth-first searches over portal sequences of the spatial
// subdivision, pruned by the stabbing test, giving cell-to-cell (§4.1, cell_visibility.h) and
// patch-to-patch visibility (§4.2, patch_search.h); then blocker lists (§5,
// blocker_detection.h). Output: the conservative VisibilityGraph.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <optional>

#include "bsp/subdivision.h"
#include "scene/scene.h"
#include "util/timing.h"
#include "visibility/blocker_lists.h"
#include "visibility/live_cells.h"
#include "visibility/portal_join.h"
#include "visibility/search_deadline.h"
#include "visibility/visibility_graph.h"

namespace gv {

/// Defaults of PropagationOptions' search budgets and the cell search's target checks. Chosen
/// on the real levels once the level's outside became one cell (convex_merge.h; measured
/// 2026-12-03, docs/BENCHMARKS.md): with target checks at 100 the cell search nearly always ends
/// before 5,000 sequences (doom-fd2-map03: 76 of 10,224 directed portals stop), and its tight
/// answer makes the patch searches cheap to bound: at 1,000 tests instead of 5,000 they list
/// 4.07 % of doom-fd2-map03's pairs instead of 3.76 %, in 2.4 s instead of 5.8 s. (Before the
/// merge, target checks cost more than they saved on the thin BSP cells of sector levels, and the
/// budgets were 500 and 5,000.)
inline constexpr uint64_t kDefaultCellSequenceBudget = 5000;
/// The patch searches' default budget follows the scene: each source may run
/// max(kMinPatchSequenceBudget, kPatchTestsInAll / patches) tests, so that the searches together
/// run about kPatchTestsInAll tests (a few seconds on two cores) past the minimum. On the Quake
/// maps and sector levels most searches reach any budget (retrojam1: 3,832 of 4,529 sources at
/// 1,000) and answer the rest of their branches with everything they might reach; a level with
/// fewer patches can afford longer searches, and their exact answers shorten the lists (measured
/// 2026-12-04, docs/BENCHMARKS.md: q3-dm4ish 12.7 % fewer pairs at 6,825 tests instead of 1,000,
/// lqdm13 2.7 % at 9,646, for up to 0.8 s more).
inline constexpr uint64_t kMinPatchSequenceBudget = 1000;
inline constexpr uint64_t kPatchTestsInAll = 12'000'000;
/// PropagationOptions::patchSequenceBudget's default: the budget above, from the patch count.
inline constexpr uint64_t kAutoPatchSequenceBudget = UINT64_MAX;
/// The per-source budget of the patch searches for option `budget` (kAutoPatchSequenceBudget:
/// from the patch count; 0: no limit; else itself).
inline uint64_t patchSequenceBudgetFor(uint64_t budget, size_t patches) {
  if (budget != kAutoPatchSequenceBudget) return budget;
  return std::max<uint64_t>(kMinPatchSequenceBudget,
                            kPatchTestsInAll / std::max<uint64_t>(patches, 1));
}
inline constexpr double kDefaultCellTargetChecks = 100;

struct PropagationOptions {
  /// Threads for the per-source searches (1 = serial). The output does not depend on it.
  int threads = 0;  ///< 0: all hardware threads
  /// Pairs sampled for the shaft-cull baseline statistic (patches meeting conv(S, R) among all
  /// patches: a brute-force scan per pair, so sampled on big scenes).
  size_t shaftSamples = 2000;
  /// Called with (done, total) source patches now and then, from one thread at a time.
  std::function<void(size_t, size_t)> progress;
  /// Called with (done, total) of the cell-to-cell search (§4.1, before the patch searches) now
  /// and then, from one thread at a time: source cells, or directed portals when the leaf-PVS
  /// search runs it; ends with done == total.
  std::function<void(size_t, size_t)> cellProgress;
  /// Called with (done, total) source patches of the blocker-list phase (§5, after the patch
  /// searches) now and then, from one thread at a time, rising.
  std::function<void(size_t, size_t)> blockerProgress;
  /// When set, the interactions are handed to it instead of kept in VisibilityGraph::
  /// interactions (which stays empty; the statistics are the same): all of them, in (s, r)
  /// order, a few sources' at a time, from one thread at a time while later sources are being
  /// worked on. Only the lists in flight are then held: `globalvis vis` writes visibility.txt
  /// this way, since on big scenes the blocker lists outgrow memory.
  std::function<void(const BlockerLists&)> interactionSink;
  /// The searches give up (computeVisibility throws PropagationDeadlineExceeded) once the clock
  /// passes this: a time budget that also holds inside one long search (`globalvis bench`).
  Clock::time_point deadline = Clock::time_point::max();
  /// What one search may test (0: no limit): portal sequences per directed portal of the cell
  /// search, stabbing tests per source patch of the patch searches. Past it, the branches the
  /// search has not explored yet are answered without exploring them, with everything a line
  /// through their first portal may reach (that portal tested, then its separating planes with
  /// the source), and the explored ones keep their answers: conservative either way (more
  /// listed, never less). They
  /// bound the time of the searches that fan out combinatorially on real levels. Counted in
  /// VisibilityStats::cellSearchesOverBudget / patchSearchesOverBudget. The patch searches'
  /// default follows the patch count (patchSequenceBudgetFor; VisibilityStats::patchBudget).
  uint64_t cellSequenceBudget = kDefaultCellSequenceBudget;
  uint64_t patchSequenceBudget = kAutoPatchSequenceBudget;
  /// Over its budget a patch search answers a branch it has not explored with only the pieces
  /// a line through the branch's portals may meet (not wholly behind one of the sequence's
  /// separating planes); off, with every piece of every cell the branch might reach, and the
  /// blocker stage alone drops the pairs hidden behind a blocker. Conservative either way; off
  /// only to test the blocker stage on such pairs, or to measure what it saves.
  bool patchBudgetAnswerByPlanes = true;
  /// The cell search's target checks (CellPvsOptions::targetCheckRatio; 0: none).
  double cellTargetChecks = kDefaultCellTargetChecks;
  /// Merge cells before searching (visibility/convex_merge.h: neighbours whose union is convex,
  /// and the blind cells no patch faces into): conservative; off only to measure what it saves.
  bool mergeConvexCells = true;
  /// Also search the thin-wall slivers (patch_search.cpp) in the leaves of merged cells, the
  /// level's outside, for everything: rays that leave a patch within the model tolerance of a
  /// one-sided wall it ends at, cross it (the contact rule does not count that hit) and go on
  /// through the outside and in through an opening. By default those slivers look only for the
  /// parts of fronts that look out of the air (Scene::beyondAirBounds), what such a ray meets
  /// first in a closed level; this option lists 2.4-4.5 times the pairs on the sector levels
  /// (docs/BENCHMARKS.md), whose rooms all end at one-sided walls with the outside behind.
  bool outsideSlivers = false;
};

/// The subdivision the searches walk, made from the one the BSP built: the portals of regions
/// no patch faces into dropped (live_cells.h), then, when `mergeCells`, convex unions of cells
/// merged and the pieces of one opening joined (convex_merge.h, portal_join.h). Conservative:
/// no sightline between patches is lost.
struct SearchSubdivision {
  const Subdivision* input = nullptr;
  std::optional<Subdivision> changed;  ///< unset when nothing changed the input
  LiveCells live;
  bool merged = false;  ///< cells merged and portal pieces joined (`joined` says how)
  PortalJoinStats joined;
  const Subdivision& get() const { return changed ? *changed : *input; }
};
/// `input` must outlive the result.
SearchSubdivision prepareSearchSubdivision(const Scene& scene, const Subdivision& input,
                                           bool mergeCells);
/// Fills the subdivision fields of `st`: patches, cells and portals (before and after the merge
/// and the join), the dead regions, and the threads.
void recordSubdivisionStats(const SearchSubdivision& prepared, size_t patches, int threads,
                            VisibilityStats& st);
/// PropagationOptions::threads resolved (0: all hardware threads).
int resolvedThreads(const PropagationOptions& options);

/// The conservative visibility graph of `scene` over its subdivision:
/// - a pair (S, R) is listed whenever some segment from the front of S to the front of R meets no
///   other patch (never missed: every search step is pruned only by a proven-empty stabbing test);
/// - its blockers are the patches seen from S or from R (by the same searches, either facing)
///   that meet conv(S, R); an empty list (VISIBLE) is therefore exact.
VisibilityGraph computeVisibility(const Scene& scene, const Subdivision& subdivision,
                                  const PropagationOptions& options = {});

}  // namespace gv
