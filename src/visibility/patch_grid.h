// A loose multi-level grid over patch bounding boxes: the blocker-list stage (paper §5) asks it
// for the patches whose boxes meet conv(S, R)'s box instead of scanning every patch S or R saw.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/vec3.h"
#include "visibility/hull_overlap.h"

namespace gv {

/// Patch boxes in a hierarchy of uniform grids, level L with cells 2^L times the size of level
/// 0's (about `cellsPerPatch` x (patch count) cells shaped after the scene's box). A patch is
/// stored once, at the finest level whose cell is at least as large as its box, in the cell of
/// its box's low corner (so its box lies within that cell and the next one up along each axis:
/// a "loose" grid). Queries therefore see every patch once, without de-duplication.
class PatchGrid {
 public:
  explicit PatchGrid(const std::vector<Aabb>& boxes, double cellsPerPatch = 2.0);

  /// Appends to `out` (unsorted, no repeats) exactly the patches whose boxes meet `box` grown
  /// by `slack` on every side (touching counts as meeting; empty boxes meet nothing). The
  /// comparisons are PairHull's box test, so that a caller may skip its own.
  void gather(const Aabb& box, double slack, std::vector<uint32_t>& out) const;
  /// The same patches as gather(), written to out[0, count) (in the same order); returns the
  /// count. `out` must have room for patchCount() ids (a patch is written at most once, but
  /// every candidate's slot is written before its box test decides whether it stays).
  /// With `hull`, the patches of a grid cell whose bounds the hull separates (PairHull::
  /// separatesBox), and those whose own box it separates (keepUnseparated), are left out: only
  /// patches that cannot meet the hull are.
  size_t gatherInto(const Aabb& box, double slack, uint32_t* out,
                    const PairHull* hull = nullptr) const;
  /// Patches stored (those with non-empty boxes).
  size_t patchCount() const { return ids_.size(); }

  /// Grid levels (for tests).
  size_t levelCount() const { return levels_.size(); }

 private:
  struct Level {
    double cellSize = 0;
    int dims[3] = {1, 1, 1};
    std::vector<uint32_t> start;  ///< per cell, its first entry (CSR), and one past the last
    /// Per cell, the union of its entries' boxes, when the level's non-empty cells hold
    /// kEntriesForCellBounds entries or more on average (else empty, and rows are scanned whole).
    std::vector<Aabb> bounds;
    size_t cell(int x, int y, int z) const { return (size_t(z) * dims[1] + y) * dims[0] + x; }
  };
  /// The cell coordinate along `axis` of level `l` holding coordinate t (clamped to the grid).
  int coordinate(const Level& l, int axis, double t) const;

  Vec3 origin_{};
  bool flat_[3] = {false, false, false};  ///< axes with a single layer of cells at every level
  std::vector<Level> levels_;
  std::vector<uint32_t> ids_;  ///< patch ids, level by level, cell by cell
  std::vector<Aabb> boxes_;    ///< the box of each entry of ids_ (read in order by queries)
};

}  // namespace gv
