// Why removing dead regions loses nothing. A segment from the front of S to the front of R that
// meets no other patch runs from the cell S's front looks into to the cell R's front looks
// into, and everywhere between it crosses cell boundaries only through portals (a boundary's
// opaque part is a patch, which the segment would meet). So all the cells it passes lie in one
// portal-connected region, and that region holds a patch facing into it: S. A region without
// one is never entered by any such segment, nor seen as a blocker (a blocker is met first by such
// a segment from S or R, from within the same region). Its portals can go.
#include "visibility/live_cells.h"

namespace gv {

LiveCells findLiveCells(const Scene& scene, const Subdivision& sub) {
  const size_t n = sub.cells.size();
  constexpr uint32_t kUnset = UINT32_MAX;
  std::vector<uint32_t> region(n, kUnset);
  std::vector<uint8_t> regionLive;
  std::vector<uint32_t> stack;
  for (uint32_t start = 0; start < n; ++start) {
    if (region[start] != kUnset) continue;
    const auto id = static_cast<uint32_t>(regionLive.size());
    regionLive.push_back(0);
    region[start] = id;
    stack.assign(1, start);
    while (!stack.empty()) {
      const uint32_t c = stack.back();
      stack.pop_back();
      const Cell& cell = sub.cells[c];
      // The searches' facing rule (bsp/subdivision.h).
      if (!regionLive[id] && somePatchFacesInto(scene, cell)) regionLive[id] = 1;
      for (uint32_t pid : cell.portals) {
        const uint32_t next = sub.portals[pid].other(c);
        if (region[next] == kUnset) {
          region[next] = id;
          stack.push_back(next);
        }
      }
    }
  }
  LiveCells out;
  out.live.resize(n);
  for (size_t c = 0; c < n; ++c) {
    out.live[c] = regionLive[region[c]];
    if (!out.live[c]) ++out.deadCells;
  }
  for (const Portal& p : sub.portals)
    if (!out.live[p.back]) ++out.deadPortals;
  return out;
}

Subdivision withoutDeadPortals(const Subdivision& sub, const LiveCells& live) {
  Subdivision out;
  out.tree = sub.tree;
  out.stats = sub.stats;
  out.leafCell = sub.leafCell;
  constexpr uint32_t kDropped = UINT32_MAX;
  std::vector<uint32_t> renumber(sub.portals.size(), kDropped);
  for (size_t i = 0; i < sub.portals.size(); ++i) {
    const Portal& p = sub.portals[i];
    if (!live.live[p.back]) continue;
    renumber[i] = static_cast<uint32_t>(out.portals.size());
    out.portals.push_back(p);
  }
  auto remap = [&](std::vector<uint32_t>& ids) {
    std::vector<uint32_t> kept;
    for (uint32_t id : ids)
      if (renumber[id] != kDropped) kept.push_back(renumber[id]);
    ids = std::move(kept);  // renumbering keeps the order, so still sorted
  };
  out.cells = sub.cells;
  for (Cell& cell : out.cells) {
    remap(cell.portals);
    for (BoundaryFace& f : cell.faces) remap(f.portals);
  }
  out.stats.portals = out.portals.size();
  return out;
}

}  // namespace gv
