// Loose multi-level grid of patch boxes for the blocker candidates of paper §5 (patch_grid.h).
#include "visibility/patch_grid.h"

#include <algorithm>
#include <cmath>

namespace gv {
namespace {

/// Axes shorter than this fraction of the scene's longest one get a single layer of cells (a flat
/// scene is not cut into slivers along its thin axis).
constexpr double kFlatAxisFraction = 1e-3;

/// Cells per axis at level 0 never exceed this (keeps indices in int and the grid small on odd
/// inputs: one huge outlier box makes the level-0 cells coarser, never more numerous).
constexpr int kMaxDim = 1024;

/// Levels whose non-empty cells hold at least this many entries on average keep per-cell
/// bounds, which let queries skip or take whole cells; sparser levels are scanned row by row
/// (a bounds test per cell would cost about what it saves).
constexpr double kEntriesForCellBounds = 4.0;

/// Relative margin on the query's low side for rounding in (t − origin) / cellSize.
constexpr double kCellRounding = 1e-9;

}  // namespace

PatchGrid::PatchGrid(const std::vector<Aabb>& boxes, double cellsPerPatch) {
  Aabb all;
  for (const Aabb& b : boxes)
    if (!b.empty()) all.add(b);
  Vec3 e{};
  if (!all.empty()) {
    origin_ = all.lo;
    e = all.extent();
  }
  const double ext[3] = {e.x, e.y, e.z};
  const double longest = std::max({ext[0], ext[1], ext[2]});
  const double target = std::max(1.0, cellsPerPatch * double(boxes.size()));
  double volume = 1;
  int axes = 0;
  for (int a = 0; a < 3; ++a) {
    flat_[a] = !(ext[a] > kFlatAxisFraction * longest);
    if (!flat_[a]) volume *= ext[a], ++axes;
  }
  // Level 0: cell edge h with about `target` cells over the axes that are not flat.
  double h = axes > 0 ? std::pow(volume / target, 1.0 / axes) : 1.0;
  if (axes > 0) h = std::max(h, longest / kMaxDim);
  if (!(h > 0)) h = 1.0;
  for (;;) {
    Level l;
    l.cellSize = h;
    bool single = true;
    for (int a = 0; a < 3; ++a) {
      l.dims[a] = flat_[a] ? 1 : std::max(1, static_cast<int>(std::ceil(ext[a] / h)));
      single = single && l.dims[a] == 1;
    }
    levels_.push_back(l);
    if (single) break;
    h *= 2;
  }
  // Each patch once: the finest level whose cell is as large as its box, at its low corner.
  std::vector<std::pair<uint32_t, size_t>> where;  // (level, cell) per stored patch
  std::vector<uint32_t> stored;
  for (uint32_t p = 0; p < boxes.size(); ++p) {
    const Aabb& b = boxes[p];
    if (b.empty()) continue;  // meets nothing
    const Vec3 be = b.extent();
    const double bext[3] = {be.x, be.y, be.z};
    double size = 0;
    for (int a = 0; a < 3; ++a)
      if (!flat_[a]) size = std::max(size, bext[a]);
    uint32_t level = 0;
    while (level + 1 < levels_.size() && levels_[level].cellSize < size) ++level;
    const Level& l = levels_[level];
    const double lo[3] = {b.lo.x, b.lo.y, b.lo.z};
    int c[3];
    for (int a = 0; a < 3; ++a) c[a] = coordinate(l, a, lo[a]);
    where.emplace_back(level, l.cell(c[0], c[1], c[2]));
    stored.push_back(p);
  }
  // Counting sort into each level's buckets, levels one after another in ids_.
  std::vector<size_t> levelBase(levels_.size() + 1, 0);
  for (size_t k = 0; k < levels_.size(); ++k) {
    const Level& l = levels_[k];
    levelBase[k + 1] = levelBase[k] + size_t(l.dims[0]) * l.dims[1] * l.dims[2];
  }
  std::vector<uint32_t> count(levelBase.back() + 1, 0);
  for (const auto& [level, cell] : where) ++count[levelBase[level] + cell + 1];
  for (size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
  for (size_t k = 0; k < levels_.size(); ++k)
    levels_[k].start.assign(count.begin() + levelBase[k], count.begin() + levelBase[k + 1] + 1);
  ids_.resize(stored.size());
  boxes_.resize(stored.size());
  for (size_t i = 0; i < stored.size(); ++i) {
    const uint32_t slot = count[levelBase[where[i].first] + where[i].second]++;
    ids_[slot] = stored[i];
    boxes_[slot] = boxes[stored[i]];
  }
  for (Level& l : levels_) {
    const size_t cells = l.start.size() - 1;
    size_t used = 0;
    for (size_t c = 0; c < cells; ++c) used += l.start[c + 1] > l.start[c];
    if (used == 0 ||
        double(l.start.back() - l.start.front()) < kEntriesForCellBounds * double(used))
      continue;
    l.bounds.resize(cells);
    for (size_t c = 0; c < cells; ++c)
      for (uint32_t i = l.start[c]; i < l.start[c + 1]; ++i) l.bounds[c].add(boxes_[i]);
  }
}

int PatchGrid::coordinate(const Level& l, int axis, double t) const {
  if (flat_[axis]) return 0;
  const double o = axis == 0 ? origin_.x : axis == 1 ? origin_.y : origin_.z;
  const double c = std::floor((t - o) / l.cellSize);
  return static_cast<int>(std::clamp(c, 0.0, double(l.dims[axis] - 1)));
}

void PatchGrid::gather(const Aabb& box, double slack, std::vector<uint32_t>& out) const {
  const size_t before = out.size();
  out.resize(before + ids_.size());
  out.resize(before + gatherInto(box, slack, out.data() + before));
}

size_t PatchGrid::gatherInto(const Aabb& box, double slack, uint32_t* out,
                             const PairHull* hull) const {
  if (box.empty()) return 0;
  const Aabb& a = box;
  const double e = slack;
  const double lo[3] = {box.lo.x - slack, box.lo.y - slack, box.lo.z - slack};
  const double hi[3] = {box.hi.x + slack, box.hi.y + slack, box.hi.z + slack};
  size_t count = 0;
  for (const Level& l : levels_) {
    if (l.start.front() == l.start.back()) continue;  // no patch at this level
    // A box stored in cell i starts in it and is at most one cell long: it lies in cells i and
    // i + 1, so the cells from the one holding lo − (a cell) are enough; the extra 1e-9 of a
    // cell covers rounding in the cell coordinates (floor is monotone, so `last` needs none).
    int first[3], last[3];
    for (int k = 0; k < 3; ++k) {
      first[k] = coordinate(l, k, lo[k] - l.cellSize * (1 + kCellRounding));
      last[k] = coordinate(l, k, hi[k]);
    }
    // Entries [begin, end) scanned with each entry written and the count advanced on a hit
    // (hits are unpredictable): no branch. The comparisons are PairHull's box test.
    auto scan = [&](uint32_t begin, uint32_t end) {
      for (uint32_t i = begin; i < end; ++i) {
        const Aabb& b = boxes_[i];
        const bool hit = (a.lo.x <= b.hi.x + e) & (b.lo.x <= a.hi.x + e) & (a.lo.y <= b.hi.y + e) &
                         (b.lo.y <= a.hi.y + e) & (a.lo.z <= b.hi.z + e) & (b.lo.z <= a.hi.z + e);
        out[count] = i;
        count += hit;
      }
    };
    for (int z = first[2]; z <= last[2]; ++z)
      for (int y = first[1]; y <= last[1]; ++y) {
        const size_t firstCell = l.cell(first[0], y, z), lastCell = l.cell(last[0], y, z);
        if (l.bounds.empty()) {
          // Cells x = first..last of one row are consecutive buckets: one run of entries.
          scan(l.start[firstCell], l.start[lastCell + 1]);
          continue;
        }
        for (size_t c = firstCell; c <= lastCell; ++c) {
          const uint32_t begin = l.start[c], end = l.start[c + 1];
          if (begin == end) continue;
          // Every entry's box b lies in the cell's bounds cb. If the box test fails for cb
          // along an axis (a.lo > cb.hi + e, say), it fails for every b (b.hi <= cb.hi, and
          // rounding b.hi + e is monotone): skip the cell. If cb lies within `a` (no slack),
          // every b passes (a.lo <= b.lo <= b.hi <= b.hi + e and b.lo <= b.hi <= a.hi <=
          // a.hi + e, for e >= 0 and boxes not empty, as stored ones are): take them all.
          const Aabb& cb = l.bounds[c];
          const bool meets = (a.lo.x <= cb.hi.x + e) & (cb.lo.x <= a.hi.x + e) &
                             (a.lo.y <= cb.hi.y + e) & (cb.lo.y <= a.hi.y + e) &
                             (a.lo.z <= cb.hi.z + e) & (cb.lo.z <= a.hi.z + e);
          if (!meets) continue;
          if (hull && hull->separatesBox(cb)) continue;
          const bool within = e >= 0 && a.lo.x <= cb.lo.x && cb.hi.x <= a.hi.x &&
                              a.lo.y <= cb.lo.y && cb.hi.y <= a.hi.y && a.lo.z <= cb.lo.z &&
                              cb.hi.z <= a.hi.z;
          if (within) {
            for (uint32_t i = begin; i < end; ++i) out[count++] = i;
          } else {
            scan(begin, end);
          }
        }
      }
  }
  // With a hull, an entry whose box one of its side planes separates holds no patch that can
  // meet it (on a long diagonal pair most of the hull's box is outside the hull): the entries'
  // own boxes are tested here, plane by plane, instead of the patches' vertices later.
  if (hull) count = hull->keepUnseparated(out, count, boxes_);
  for (size_t k = 0; k < count; ++k) out[k] = ids_[out[k]];
  return count;
}

}  // namespace gv
