// Which pairs of patches may see each other at all, from the cells they lie in: the cell-to-cell
// stage of the visibility pipeline (paper §4.1) lifted to patches, without the patch searches
// and blocker lists after it. Cheap next to what it saves (the 100k office: 13-19 s with its BSP,
// for 92 % of the pairs never linked) and conservative: a sightline from S's front to R's front
// starts in a cell S's front looks into and ends in one R's front looks into, and the cell stage
// never leaves out a cell a sightline can reach. `rays` radiosity links only
// these pairs, so that no ray is cast between rooms that cannot see each other.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "bsp/subdivision.h"
#include "scene/scene.h"
#include "visibility/cell_set.h"
#include "visibility/propagation.h"
#include "visibility/visibility_graph.h"

namespace gv {

class PatchCellReach {
 public:
  /// Prepares `sub` (a subdivision of `scene`) as computeVisibility does, runs its cell stage
  /// (options' threads, cell budget, cell progress and deadline apply) and places the patches as
  /// the patch searches would.
  PatchCellReach(const Scene& scene, const Subdivision& sub, const PropagationOptions& options);

  /// False when the cell stage kept no per-cell sets (too many cells for cells² bits): every pair
  /// may then see.
  bool known() const { return !reach_.empty(); }
  /// Calls visit(a, b) once for every pair a < b where a cell of a reaches a cell of b (every
  /// pair when !known()). A patch placed in no cell is paired with every other.
  void forEachPair(const std::function<void(uint32_t a, uint32_t b)>& visit) const;
  /// Whether a cell of a reaches a cell of b (true when !known()).
  bool maySee(uint32_t a, uint32_t b) const;
  /// How many pairs forEachPair visits (it walks them all, without the calls).
  size_t countPairs() const;

  /// The cells the front of patch p looks into, sorted (empty: unplaced). Only when known().
  const std::vector<uint32_t>& cellsOf(uint32_t p) const { return cellsOf_[p]; }
  /// The cells cell c may see (c included; symmetric). Only when known().
  const CellSet& reach(uint32_t c) const { return reach_[c]; }
  size_t cellCount() const { return reach_.size(); }

  /// Per patch, how much of `power` (a value per patch, e.g. emitted power) lies on patches
  /// whose cells may see one of its cells: the largest such sum over its cells (a lower bound of
  /// the sum over all of them when it has several). Where that is 0 (no emitter in view: a room
  /// lit only through others), the largest sum of a cell it may see; where that is 0 too, or the
  /// cells are not known, or the patch is unplaced, the total.
  std::vector<double> powerInView(const std::vector<double>& power) const;

  /// The cell stage's figures (cells, portals, cell pairs, budgets; VisibilityStats' cell fields).
  const VisibilityStats& stats() const { return stats_; }
  /// Patches placed in no cell (paired with every other).
  size_t unplacedPatches() const { return unplaced_.size(); }

 private:
  size_t patches_ = 0;
  std::vector<std::vector<uint32_t>> cellsOf_;    ///< per patch, its cells, sorted
  std::vector<std::vector<uint32_t>> patchesOf_;  ///< per cell, its patches, ascending
  std::vector<CellSet> reach_;                    ///< per cell, the cells it may see
  std::vector<uint32_t> unplaced_;                ///< patches with no cell, ascending
  VisibilityStats stats_;
};

}  // namespace gv
