// Uniform grid of patch boxes for the blocker candidates of paper §5 (see patch_grid.h).
#include "visibility/patch_grid.h"

#include <algorithm>
#include <cmath>

namespace gv {
namespace {

/// Axes shorter than this fraction of the scene's longest one get a single layer of cells (a flat
/// scene is not cut into slivers along its thin axis).
constexpr double kFlatAxisFraction = 1e-3;

/// A patch whose box covers more grid cells than this is kept in one list that every query
/// returns, so a few huge patches (a ground plane) cannot fill the grid with copies of themselves.
constexpr size_t kMaxCellsPerPatch = 512;

/// Cells per axis never exceed this (keeps indices in int and the grid small on odd inputs).
constexpr int kMaxDim = 4096;

}  // namespace

PatchGrid::PatchGrid(const std::vector<Aabb>& boxes, double cellsPerPatch)
    : patchCount_(boxes.size()) {
  Aabb all;
  for (const Aabb& b : boxes)
    if (!b.empty()) all.add(b);
  if (all.empty()) {
    for (uint32_t p = 0; p < boxes.size(); ++p) ids_.push_back(p);
    start_ = {0, 0, static_cast<uint32_t>(ids_.size())};  // cell 0 empty, the global list after
    return;
  }
  origin_ = all.lo;
  const Vec3 e = all.extent();
  const double ext[3] = {e.x, e.y, e.z};
  const double longest = std::max({ext[0], ext[1], ext[2]});
  // Cell edge h with about cellsPerPatch * n cells over the axes that are not flat.
  const double target = std::max(1.0, cellsPerPatch * double(boxes.size()));
  double volume = 1;
  int axes = 0;
  for (double x : ext)
    if (x > kFlatAxisFraction * longest) volume *= x, ++axes;
  const double h = axes > 0 ? std::pow(volume / target, 1.0 / axes) : 1.0;
  for (int a = 0; a < 3; ++a) {
    const bool flat = !(ext[a] > kFlatAxisFraction * longest) || !(h > 0);
    dims_[a] = flat ? 1 : std::clamp(static_cast<int>(std::ceil(ext[a] / h)), 1, kMaxDim);
    inverseSize_[a] = ext[a] > 0 ? dims_[a] / ext[a] : 0;
  }
  const size_t cells = size_t(dims_[0]) * size_t(dims_[1]) * size_t(dims_[2]);
  // Counting sort into buckets; the last bucket (index `cells`) is the global list.
  std::vector<uint32_t> count(cells + 1, 0);
  auto forCells = [&](const Aabb& b, auto f) {
    int lo[3], hi[3];
    cellRange(b.lo, b.hi, lo, hi);
    const size_t covered =
        size_t(hi[0] - lo[0] + 1) * size_t(hi[1] - lo[1] + 1) * size_t(hi[2] - lo[2] + 1);
    if (covered > kMaxCellsPerPatch) {
      f(cells);
      return;
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x) f((size_t(z) * dims_[1] + y) * dims_[0] + x);
  };
  for (const Aabb& b : boxes)
    if (b.empty()) {
      ++count[cells];
    } else {
      forCells(b, [&](size_t c) { ++count[c]; });
    }
  start_.assign(cells + 2, 0);
  for (size_t c = 0; c <= cells; ++c) start_[c + 1] = start_[c] + count[c];
  ids_.resize(start_.back());
  std::vector<uint32_t> fill(start_.begin(), start_.end() - 1);
  for (uint32_t p = 0; p < boxes.size(); ++p)
    if (boxes[p].empty()) {
      ids_[fill[cells]++] = p;
    } else {
      forCells(boxes[p], [&](size_t c) { ids_[fill[c]++] = p; });
    }
}

void PatchGrid::cellRange(const Vec3& a, const Vec3& b, int lo[3], int hi[3]) const {
  const double pa[3] = {a.x - origin_.x, a.y - origin_.y, a.z - origin_.z};
  const double pb[3] = {b.x - origin_.x, b.y - origin_.y, b.z - origin_.z};
  for (int k = 0; k < 3; ++k) {
    // Clamping keeps boxes beyond the grid (a query box grown by its slack) on the border cells.
    auto cell = [&](double t) {
      const double c = std::floor(t * inverseSize_[k]);
      return static_cast<int>(std::clamp(c, 0.0, double(dims_[k] - 1)));
    };
    lo[k] = cell(pa[k]);
    hi[k] = cell(pb[k]);
  }
}

void PatchGrid::Query::gather(const Aabb& box, double slack, std::vector<uint32_t>& out) {
  const PatchGrid& g = *grid_;
  if (++stamp_ == 0) {  // wrapped: old stamps could collide
    std::fill(stamps_.begin(), stamps_.end(), 0);
    stamp_ = 1;
  }
  auto take = [&](size_t bucket) {
    for (uint32_t i = g.start_[bucket]; i < g.start_[bucket + 1]; ++i) {
      const uint32_t p = g.ids_[i];
      if (stamps_[p] != stamp_) {
        stamps_[p] = stamp_;
        out.push_back(p);
      }
    }
  };
  const size_t cells = g.start_.size() - 2;
  take(cells);  // the global list
  if (box.empty() || cells == 0) return;
  const Vec3 s{slack, slack, slack};
  int lo[3], hi[3];
  g.cellRange(box.lo - s, box.hi + s, lo, hi);
  for (int z = lo[2]; z <= hi[2]; ++z)
    for (int y = lo[1]; y <= hi[1]; ++y)
      for (int x = lo[0]; x <= hi[0]; ++x) take((size_t(z) * g.dims_[1] + y) * g.dims_[0] + x);
}

}  // namespace gv
