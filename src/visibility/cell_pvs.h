// The potentially visible set of a portal graph: for every cell, the cells some sightline through
// the portals can reach (paper §4.1: depth-first search over portal sequences with the
// stabbing-line test, src/visibility/stabbing.h). Conservative, symmetric and deterministic. Run
// on Quake portal files by `globalvis pvs` (quake/prt_portal_graph.h converts them) and on the BSP
// cells by the cell-to-cell stage of `vis` (visibility/cell_visibility.h).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "geometry/portal_graph.h"
#include "visibility/cell_set.h"
#include "visibility/stabbing.h"

namespace gv {

/// Edge clearance a PVS sightline needs (StabbingOptions::blockedBelow): its Plücker side with
/// every portal edge over the edge's length, in units of the map's diagonal, for the line scaled
/// to cross the first portal at unit speed along its normal (about the line's distance from the
/// edge's line times the sine of their angle). Lines that only touch portal edges are not kept.
/// The E1M1 test of the pairs this drops
/// (DISABLED_E1M1OpenPortalsDropNoRayVisiblePair: rays kept 1e-6 of the diagonal inside every
/// portal) passes with 1e-9 and fails with 1e-6 (grazing crossings have a smaller clearance than
/// their distance in the portal's plane) and 1e-4. E1M1: 165.4 -> 163.3 mean leafs visible.
/// Like the LP's grazing-slope box, a measure-tiny set of lines is given up: sightlines passing
/// within ~1e-9 of the diagonal of an edge.
inline constexpr double kPvsEdgeClearance = 1e-9;

/// The stabber's defaults without the witness-line search: the PVS needs only "blocked or not",
/// and witness lines (a third of the search time on E1M1) never change what is pruned. With the
/// LP deferred for cells already visible (`deferLp`: the same cells reached, a quarter fewer LP
/// solves on E1M1), and open portals (kPvsEdgeClearance).
inline StabbingOptions pvsStabbingOptions() {
  StabbingOptions o;
  o.seekWitness = false;
  o.deferLp = true;
  o.blockedBelow = kPvsEdgeClearance;
  return o;
}

struct CellPvsOptions {
  StabbingOptions stabbing = pvsStabbingOptions();
  /// Run the searches on the threads of the current oneTBB arena; the result is identical to the
  /// serial run (and to a run on any number of threads).
  bool parallel = true;
  /// Called after each search the calling thread finishes, with (directed portals searched,
  /// total), strictly increasing, from the calling thread; it may throw to stop the searches.
  std::function<void(size_t, size_t)> progress;
  /// Find every cell pair from both cells' searches and keep it only if both found it: the
  /// tightest PVS, and slower. Off (the default): a search does not look for the cells whose
  /// own searches are all finished (their answer for the pair stands); see computeCellPvs.
  bool bothSides = false;
  /// Portal sequences one search may push (0: no limit). Past it the search stops testing:
  /// each branch it has not explored yet is answered with every cell it might reach (its
  /// might-see set narrowed along the path), while the branches explored keep their answers:
  /// conservative, looser, bounded. On real levels some portals' sequences fan out
  /// combinatorially (thin cells under long sightlines); one such search could run for minutes.
  uint64_t maxSequencesPerSearch = 0;
  /// Target checks (`vis`'s -targetchecks): a search entering a cell may first drop from its
  /// might-see set the cells into which no line of the current portal sequence can pass
  /// (PortalSequenceStabber::mayCrossLater on each portal into them), so that branches left
  /// with nothing new to find are pruned. Spent while the tests made stay below this multiple
  /// of the sequences the search has pushed (0: never; at 100 they practically never stop).
  /// Only cells no sightline of the sequence reaches are dropped, so every cell a sightline
  /// reaches is still found; the PVS can get smaller, since the separating planes are exact
  /// for two portals where the Plücker LP is a relaxation (E1M1: 164.09 -> 164.03 leafs).
  /// The checks are made for a branch about to be explored, on its unseen cells only.
  double targetCheckRatio = 100;
  /// Whether a branch's target checks test all its unseen cells (dropping every one no line
  /// may enter, so that the deeper branches skip them too) or stop at the first that a line may
  /// enter (the branch is explored either way). Stopping is faster (e3m4.prt 8 %, E1M1 12 %,
  /// the PVS within 0.01 %); testing all keeps more branches pruned below, which matters where
  /// searches run out of a budget (maxSequencesPerSearch): on doom-fd2-map10 stopping made
  /// 16 % more searches overrun theirs and 2.6 % more patch pairs, testing all none.
  bool targetCheckWholeBranch = false;
};

struct CellPvsResult {
  /// For each cell of the graph, the cells it may see, ascending, itself included.
  std::vector<std::vector<uint32_t>> visibleCells;
  size_t cellCount = 0, portalCount = 0;
  /// Cell pairs (ordered) found from one side only and dropped by symmetrisation.
  uint64_t oneSidedPairsDropped = 0;
  /// Cell pairs (ordered, either answer) decided by one side's searches alone, because the
  /// other side's searches came later and did not look for it (not with `bothSides`).
  uint64_t settledPairs = 0;
  /// Mean over cells of the cells the might-see flood allows (before stabbing), for comparison.
  double meanCellsMightSee = 0;
  StabbingStats stabbing;
  uint64_t sequencesSearched = 0;  ///< portal sequences pushed by the searches
  /// Directed-portal searches that ran out of CellPvsOptions::maxSequencesPerSearch.
  uint64_t searchesOverBudget = 0;
  /// Tests made by target checks (CellPvsOptions::targetCheckRatio; a cell's ball of portals,
  /// then its portals), and the might-see entries they dropped.
  uint64_t targetTests = 0, targetCellsDropped = 0;
  /// Plane tests made answering the branches a search left unexplored over its budget (the
  /// cells a line through the branch's first portal may enter).
  uint64_t overBudgetTests = 0;
  /// Stabbing tests by sequence length in portals (the paper's Fig. 13), index = length.
  std::vector<uint64_t> successesByLength, failuresByLength;
  /// Per directed portal (2i: portal i from back into front; 2i+1: the way back), the
  /// cells reached by the stabbable sequences it starts (before symmetrisation; without
  /// `bothSides`, with the settled cells its search might have reached added): a superset of
  /// where any sightline continuing through it can go.
  std::vector<CellSet> portalFlow;
  double floodSeconds = 0, searchSeconds = 0;
};

/// Computes the PVS. A cell sees itself and every cell reached by a portal sequence that admits a
/// stabbing line (through open portals with the default options: see kPvsEdgeClearance). Method:
///  1. might-see flood per directed portal (cheap plane tests, `vis -fast`-like);
///  2. from each directed portal, depth-first search over the portal sequences it starts (at each
///     cell, the portals into cells not yet visible first: the same cells are reached in any
///     order, and reaching new ones early prunes more of the rest), pruned
///     when the stabbing test proves a sequence blocked, when the entered cell is already on the
///     path (a line meets a convex cell once), or when nothing the sequence might still reach is
///     unseen (might-see sets narrowed by the results of the portals searched at least 16 places
///     earlier: the same for any number of threads),
///     or when the entered cell cannot see the path back (sightlines are symmetric: the reverse
///     portal's might-see set misses a cell of the path, or every might-see set of the entered
///     cell's portals misses the source);
///     a cell sees itself and what its portals see. Order: increasing might-see size with
///     `bothSides` (`vis`'s order); by default a cell's portals are searched together (ordered by
///     the largest might-see size among them, but no portal later than twice its own size), and
///     a search counts the cells whose portals were all searched (at least 16 places earlier)
///     as already seen: their searches decided the pair (conservatively), so sequences still go
///     through them but nothing is pruned-for or kept alive on their account. On the shared
///     maps this costs 0.1-0.6 % more leafs visible and saves 3-31 % of the time;
///  3. symmetrisation: a pair is kept only if found from both sides (each side's search is
///     conservative and true visibility is symmetric, so the intersection still contains it),
///     or, for a pair settled in step 2, if the side that searched for it found it.
CellPvsResult computeCellPvs(const PortalGraph& graph, const CellPvsOptions& options = {});

}  // namespace gv
