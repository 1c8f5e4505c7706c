// Patch pairs bounded by cell-to-cell visibility.
#include "visibility/patch_cell_reach.h"

#include <algorithm>
#include <numeric>

#include "util/timing.h"
#include "visibility/cell_visibility.h"
#include "visibility/patch_search.h"

namespace gv {

PatchCellReach::PatchCellReach(const Scene& scene, const Subdivision& input,
                               const PropagationOptions& options)
    : patches_(scene.patches.size()) {
  const auto start = Clock::now();
  const SearchSubdivision prepared =
      prepareSearchSubdivision(scene, input, options.mergeConvexCells);
  const Subdivision& sub = prepared.get();
  const int threads = resolvedThreads(options);
  recordSubdivisionStats(prepared, patches_, threads, stats_);
  CellVisibility cells = computeCellVisibility(sub, threads, options, stats_);
  stats_.seconds = stats_.cellSeconds = secondsSince(start);
  if (cells.cellReach.empty()) return;  // unknown: every pair may see
  reach_ = std::move(cells.cellReach);
  cellsOf_ = frontCellsOfPatches(scene, sub, options.outsideSlivers);
  patchesOf_.resize(sub.cells.size());
  for (uint32_t p = 0; p < cellsOf_.size(); ++p) {
    if (cellsOf_[p].empty()) unplaced_.push_back(p);
    for (uint32_t c : cellsOf_[p]) patchesOf_[c].push_back(p);
  }
  stats_.seconds = secondsSince(start);
}

bool PatchCellReach::maySee(uint32_t a, uint32_t b) const {
  if (!known() || cellsOf_[a].empty() || cellsOf_[b].empty()) return true;
  for (uint32_t c : cellsOf_[a])
    for (uint32_t d : cellsOf_[b])
      if (reach_[c].contains(d)) return true;
  return false;
}

namespace {

/// out := the union of the reach of `cells`.
void uniteReach(const std::vector<uint32_t>& cells, const std::vector<CellSet>& reach,
                CellSet& out) {
  out.clear();
  for (uint32_t c : cells) out.unite(reach[c]);
}

/// Calls partners(a, list) for every patch a with the patches b > a whose cells a's cells may
/// see, ascending (cells known).
template <class F>
void forEachPartnerList(size_t n, const std::vector<std::vector<uint32_t>>& cellsOf,
                        const std::vector<std::vector<uint32_t>>& patchesOf,
                        const std::vector<CellSet>& reach, const std::vector<uint32_t>& unplaced,
                        F&& partners) {
  // Per patch a: the union of its cells' reach, then the patches of those cells above a, each
  // once (a patch lies in several cells). Unplaced patches pair with everyone.
  std::vector<uint32_t> stamp(n, UINT32_MAX);
  std::vector<uint32_t> list;
  CellSet reached(reach.size());
  for (uint32_t a = 0; a < n; ++a) {
    list.clear();
    if (cellsOf[a].empty()) {
      for (uint32_t b = a + 1; b < n; ++b) list.push_back(b);
      partners(a, list);
      continue;
    }
    uniteReach(cellsOf[a], reach, reached);
    auto add = [&](uint32_t b) {
      if (b > a && stamp[b] != a) {
        stamp[b] = a;
        list.push_back(b);
      }
    };
    reached.forEach([&](size_t d) {
      for (uint32_t b : patchesOf[d]) add(b);
    });
    for (uint32_t b : unplaced) add(b);
    std::sort(list.begin(), list.end());
    partners(a, list);
  }
}

}  // namespace

void PatchCellReach::forEachPair(const std::function<void(uint32_t, uint32_t)>& visit) const {
  const auto n = static_cast<uint32_t>(patches_);
  if (!known()) {
    for (uint32_t a = 0; a < n; ++a)
      for (uint32_t b = a + 1; b < n; ++b) visit(a, b);
    return;
  }
  forEachPartnerList(patches_, cellsOf_, patchesOf_, reach_, unplaced_,
                     [&](uint32_t a, const std::vector<uint32_t>& list) {
                       for (uint32_t b : list) visit(a, b);
                     });
}

size_t PatchCellReach::countPairs() const {
  if (!known()) return patches_ < 2 ? 0 : patches_ * (patches_ - 1) / 2;
  size_t count = 0;
  forEachPartnerList(patches_, cellsOf_, patchesOf_, reach_, unplaced_,
                     [&](uint32_t, const std::vector<uint32_t>& list) { count += list.size(); });
  return count;
}

std::vector<double> PatchCellReach::powerInView(const std::vector<double>& power) const {
  const double total = std::accumulate(power.begin(), power.end(), 0.0);
  std::vector<double> out(patches_, total);
  if (!known()) return out;
  // Per cell, the power of the patches whose cells may see it, each patch counted once.
  std::vector<double> cellPower(reach_.size(), 0.0);
  CellSet reached(reach_.size());
  for (uint32_t p = 0; p < patches_; ++p) {
    if (!(power[p] > 0) || cellsOf_[p].empty()) continue;
    uniteReach(cellsOf_[p], reach_, reached);
    reached.forEach([&](size_t d) { cellPower[d] += power[p]; });
  }
  for (uint32_t p = 0; p < patches_; ++p) {
    if (cellsOf_[p].empty()) continue;
    double direct = 0, neighbour = 0;
    for (uint32_t c : cellsOf_[p]) {
      direct = std::max(direct, cellPower[c]);
      reach_[c].forEach([&](size_t d) { neighbour = std::max(neighbour, cellPower[d]); });
    }
    if (direct > 0) {
      out[p] = direct;
    } else if (neighbour > 0) {
      out[p] = neighbour;
    }
  }
  return out;
}

}  // namespace gv
