// Patch-to-patch visibility (paper §4.2): from every patch S, the cell search with S's piece in
// its cell prefixed to the sequence (a tighter start than the whole cell). In every reached cell
// each patch T is tested as the sequence's last "portal", crossed the way a sightline would
// cross it; T is then "seen" from S, and "seen from the front" when the sightline meets T's
// front. These seen lists are the input of the blocker lists (blocker_detection.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bsp/subdivision.h"
#include "scene/scene.h"
#include "visibility/cell_visibility.h"
#include "visibility/propagation.h"
#include "visibility/stabbing.h"
#include "visibility/visibility_graph.h"

namespace gv {

/// Seen flags of one source patch.
enum : uint8_t { kSeen = 1, kSeenFront = 2 };

/// A seen patch and its flags packed in 32 bits (patch << 2 | flags): these lists are the patch
/// searches' whole output, held for every source until the blocker stage, so their size counts.
constexpr uint32_t seenEntry(uint32_t patch, uint8_t flags) {
  return patch << 2 | flags;
}
constexpr uint32_t seenPatch(uint32_t entry) {
  return entry >> 2;
}
constexpr uint8_t seenFlags(uint32_t entry) {
  return static_cast<uint8_t>(entry & 3);
}
/// Patch ids must leave the two flag bits free.
constexpr size_t kMaxPatches = size_t{1} << 30;

/// What the search from one source patch saw.
struct PatchSearchResult {
  std::vector<uint32_t> seen;             ///< seenEntry(patch, flags), sorted by patch
  std::vector<uint32_t> sameCellVisible;  ///< patches proven VISIBLE by the shortcut
  StabbingStats stabbing;
  uint64_t facingRuleTests = 0;  ///< (S, T) tests in S's own cell, decided by testInSourceCell
  /// The search ran out of budget: the branches it had not explored then were answered with
  /// every piece they might reach.
  bool overBudget = false;
};

/// The cells each patch's front looks into, as the patch searches place its pieces (the BSP's
/// placement, plus the pieces across coplanar openings and thin walls; `outsideSlivers` as in
/// PropagationOptions), sorted, per patch: the pieces that face into their cell or lie inside it
/// (either side). A search from S starts in these cells only, and it sees T's front only through
/// T's pieces in them.
std::vector<std::vector<uint32_t>> frontCellsOfPatches(const Scene& scene, const Subdivision& sub,
                                                       bool outsideSlivers);

/// The patch searches from every patch of `scene` (its pieces placed in the cells of `sub`),
/// bounded by the cell-to-cell answer; result s is patch s's. Fills the patch fields of `st`
/// (not patchSeconds); `threads` as resolved by computeVisibility; options' patch budget,
/// progress and deadline apply.
std::vector<PatchSearchResult> searchPatches(const Scene& scene, const Subdivision& sub,
                                             const CellVisibility& cells, int threads,
                                             const PropagationOptions& options,
                                             VisibilityStats& st);

}  // namespace gv
