// A uniform grid over patch bounding boxes: the blocker-list stage (paper §5) asks it for the
// patches whose boxes may meet conv(S, R)'s box instead of scanning every patch S or R has seen.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/vec3.h"

namespace gv {

/// Buckets patch boxes in a uniform grid of about `cellsPerPatch` x (patch count) cells shaped
/// after the scene's box. A query returns a superset of the patches whose boxes meet the query
/// box: callers still test the boxes (and more) themselves.
class PatchGrid {
 public:
  explicit PatchGrid(const std::vector<Aabb>& boxes, double cellsPerPatch = 2.0);

  /// Per-thread state of queries: a stamp per patch, so that a patch listed in several grid
  /// cells is reported once.
  class Query {
   public:
    explicit Query(const PatchGrid& grid) : grid_(&grid), stamps_(grid.patchCount_, 0) {}
    /// Appends to `out` (unsorted, no repeats) every patch whose box may meet `box` grown by
    /// `slack` on every side.
    void gather(const Aabb& box, double slack, std::vector<uint32_t>& out);

   private:
    const PatchGrid* grid_;
    std::vector<uint32_t> stamps_;
    uint32_t stamp_ = 0;
  };

 private:
  /// The grid cell range [lo, hi] along each axis that meets [a, b].
  void cellRange(const Vec3& a, const Vec3& b, int lo[3], int hi[3]) const;

  size_t patchCount_ = 0;
  Vec3 origin_{};
  double inverseSize_[3] = {0, 0, 0};  ///< cells per unit length along each axis
  int dims_[3] = {1, 1, 1};
  std::vector<uint32_t> start_;  ///< per grid cell, its first entry in ids_ (CSR)
  std::vector<uint32_t> ids_;    ///< patch ids, bucket by bucket
};

}  // namespace gv
