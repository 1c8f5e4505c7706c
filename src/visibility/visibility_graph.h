// The conservative visibility graph over patches: interacting pairs with their blocker lists,
// and the paper's §7.2–§7.3 figures. The output of propagation (paper §4.2, §5).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>
#include <vector>

#include "util/bulk_file.h"
#include "visibility/blocker_lists.h"
#include "visibility/stabbing.h"

namespace gv {

/// Status of a patch pair (paper §5): INVISIBLE pairs are simply not listed.
enum class PairStatus { Invisible, Partial, Visible };

/// An interaction I(S, R) with its blocker list B(S, R), S < R. An empty list means VISIBLE:
/// no other patch meets conv(S, R). Otherwise PARTIAL: every patch that some segment from S's
/// front to R's front meets first, seen from S or from R, is in `blockers` (sorted).
struct Interaction {
  uint32_t s = 0, r = 0;
  std::vector<uint32_t> blockers;
  PairStatus status() const { return blockers.empty() ? PairStatus::Visible : PairStatus::Partial; }
};

/// Stabbing successes and failures by portal-sequence length (the paper's Fig. 13).
struct SequenceHistogram {
  std::vector<uint64_t> successes, failures;  ///< index = sequence length in portals
  void add(size_t length, bool success);
  SequenceHistogram& operator+=(const SequenceHistogram& o);
};

/// The figures of §7.2 and §7.3 for one run.
struct VisibilityStats {
  size_t patches = 0, cells = 0, portals = 0;
  /// Cells in regions no patch faces into, and the portals among them (live_cells.h): left out
  /// of every search.
  size_t deadCells = 0, deadPortals = 0;
  /// The BSP's cells and portals, before dead regions and merging (visibility/convex_merge.h);
  /// `cells` counts the merged ones.
  size_t cellsBeforeMerge = 0, portalsBeforeMerge = 0;
  /// Portals of the merged cells before coplanar pieces of one opening were joined
  /// (visibility/portal_join.h); `portals` counts the joined ones.
  size_t portalsBeforeJoin = 0;
  uint64_t cellPairsVisible = 0;  ///< ordered (source, reached) cell pairs, source included
  /// Searches stopped by their budget and answered conservatively (PropagationOptions::
  /// cellSequenceBudget, patchSequenceBudget): directed portals of the cell search, source patches.
  uint64_t cellSearchesOverBudget = 0, patchSearchesOverBudget = 0;
  /// The stabbing tests each patch search could run (0: no limit), as patchSequenceBudgetFor
  /// resolved the option.
  uint64_t patchBudget = 0;
  uint64_t cellStabbingTests = 0;  ///< portal-sequence tests of the cell-to-cell search
  /// Plane tests of the cell search's target checks, and of its answers to branches left
  /// unexplored over the budget (CellPvsResult::targetTests, overBudgetTests).
  uint64_t cellTargetTests = 0, cellOverBudgetTests = 0;
  uint64_t patchStabbingTests = 0;  ///< tests of the patch searches (portals and targets)
  /// Of those, target tests in the source's own cell decided by the two-polygon facing rule
  /// (no portal between: exact without the stabbing kernel; not in patchStabbing).
  uint64_t patchFacingRuleTests = 0;
  /// Patches a source patch's search saw (either facing), mean over sources: the candidates of
  /// its blocker lists.
  double meanPatchesSeen = 0;
  uint64_t unresolvedStabbing = 0;            ///< tests answered "maybe" (counted as visible)
  StabbingStats cellStabbing, patchStabbing;  ///< how the tests were decided, per search level
  double meanSequenceLength = 0;              ///< over the cell-level tests, in portals
  SequenceHistogram cellHistogram;            ///< Fig. 13
  uint64_t pairsVisible = 0, pairsPartial = 0;
  uint64_t sameCellShortcuts = 0;  ///< pairs declared VISIBLE by the same-empty-cell rule
  /// Pairs the searches kept that one of their blockers hides whole (single_occluder.h):
  /// dropped, so INVISIBLE.
  uint64_t pairsHiddenByOne = 0;
  /// Pairs the searches kept that blockers lying in one plane hide together (a wall of several
  /// patches: geometry/coplanar_cover.h): dropped, so INVISIBLE.
  uint64_t pairsHiddenByWall = 0;
  /// Pieces of patches placed in a cell across a one-sided wall they end against (patch_search.cpp:
  /// rays may cross such a wall within the contact tolerance of their start).
  uint64_t thinWallSlivers = 0;
  /// Of those, the ones in the level's outside (a merged cell's leaves), searched only for the
  /// fragments: the parts of fronts that look beyond the air (Scene::beyondAirBounds) cut from
  /// their pieces, which are searched only for those slivers (patch_search.cpp).
  uint64_t beyondAirSlivers = 0;
  uint64_t beyondAirFragments = 0;
  /// Pieces of patches placed in a cell across an opening that lies along the patch and overlaps
  /// it (patch_search.cpp: a patch the BSP moved onto a tilted plane, its front looking out
  /// through that opening).
  uint64_t acrossPortalPieces = 0;
  /// Pieces of patches placed across a sealed slab thinner than the tolerance in front of them
  /// (patch_search.cpp: the slab's faces are too thin to be portals, so the patch's front saw
  /// nothing).
  uint64_t acrossThinSlabPieces = 0;
  /// Pairs of nearly coplanar patches facing each other that the searches had not seen both
  /// ways, added for the blocker stage (visibility/coplanar_grazes.h).
  uint64_t coplanarGrazePairs = 0;
  double meanBlockersPerPartial = 0;
  double meanShaftCullPerPartial = 0;  ///< patches meeting conv(S, R), over `shaftSamples` pairs
  uint64_t shaftSamples = 0;
  double seconds = 0, cellSeconds = 0, patchSeconds = 0, blockerSeconds = 0;
  int threads = 1;
};

struct VisibilityGraph {
  std::vector<Interaction> interactions;  ///< sorted by (s, r)
  VisibilityStats stats;
};

/// Writes `visibility.txt` in the paper's format (DESIGN.md contract): `S R n b1 ... bn`.
void writeVisibilityTxt(const VisibilityGraph& graph, const std::string& path);

/// visibility.txt written as it is produced: the header when constructed, one line per add() in
/// the order given (the contract's (s, r) order is the caller's), the rest on close(). Lets
/// `globalvis vis` write the blocker lists without holding them all (PropagationOptions::
/// interactionSink). Written through BulkFile (direct I/O where possible: these files reach
/// gigabytes). Errors (open, write) throw InputError(path, 0, ...).
class VisibilityTxtWriter {
 public:
  explicit VisibilityTxtWriter(const std::string& path);
  ~VisibilityTxtWriter();
  VisibilityTxtWriter(const VisibilityTxtWriter&) = delete;
  VisibilityTxtWriter& operator=(const VisibilityTxtWriter&) = delete;
  /// One line: `s r n b1 ... bn`.
  void add(uint32_t s, uint32_t r, std::span<const uint32_t> blockers);
  void add(const Interaction& in) { add(in.s, in.r, in.blockers); }
  /// A line per pair of `lists`, in their order.
  void add(const BlockerLists& lists);
  /// Flushes and closes the file; throws if any write failed. Idempotent.
  void close();

 private:
  /// Ids below this (7 digits at most, so the count fits in the packed word's top byte) get
  /// their digits from packed_.
  static constexpr uint64_t kPackedIds = 10'000'000;
  void put(uint64_t v, char after);
  BulkFile file_;
  std::vector<uint64_t> packed_;  ///< per id: its digits, first in the lowest byte; count << 56
};
/// The statistics as JSON (§7.2–7.3 figures, the paper's own values alongside).
nlohmann::json visibilityStatsJson(const VisibilityStats& stats);
/// Reads a visibility.txt back (for `verify`); throws InputError on malformed lines.
VisibilityGraph readVisibilityTxt(const std::string& path);

}  // namespace gv
