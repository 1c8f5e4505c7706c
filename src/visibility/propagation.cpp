// Visibility propagation (paper §4.1–4.2) and blocker detection (§5), stage by stage: regions no
// patch faces into are dropped, then cell-to-cell visibility (cell_visibility.h), the
// patch-to-patch searches it bounds (patch_search.h), and the blocker lists of the pairs those
// searches find (blocker_detection.h).
#include "visibility/propagation.h"

#include <fmt/format.h>
#include <tbb/task_arena.h>

#include <optional>
#include <stdexcept>
#include <utility>

#include "util/timing.h"
#include "visibility/blocker_detection.h"
#include "visibility/cell_visibility.h"
#include "visibility/convex_merge.h"
#include "visibility/coplanar_grazes.h"
#include "visibility/live_cells.h"
#include "visibility/patch_search.h"
#include "visibility/portal_join.h"

namespace gv {

SearchSubdivision prepareSearchSubdivision(const Scene& scene, const Subdivision& input,
                                           bool mergeCells) {
  SearchSubdivision out;
  out.input = &input;
  // Regions no patch faces into (closed solids' insides) lose their portals first: the searches
  // would walk them for nothing (live_cells.cpp says why nothing is lost).
  out.live = findLiveCells(scene, input);
  if (out.live.deadPortals > 0) out.changed = withoutDeadPortals(input, out.live);
  // Then the cells are merged (convex_merge.h): the level's outside becomes one cell, and open
  // space cut into slabs by far-away planes one cell per convex union.
  // Then the pieces of one opening between two merged cells become one portal (portal_join.h).
  if (mergeCells) {
    out.changed = mergeConvexCells(scene, out.changed ? std::move(*out.changed) : input);
    out.joined = joinCoplanarPortals(*out.changed);
    out.merged = true;
  }
  return out;
}

void recordSubdivisionStats(const SearchSubdivision& prepared, size_t patches, int threads,
                            VisibilityStats& st) {
  const Subdivision& sub = prepared.get();
  st.patches = patches;
  st.cells = sub.cells.size();
  st.portals = sub.portals.size();
  st.cellsBeforeMerge = prepared.input->cells.size();
  st.portalsBeforeMerge = prepared.input->portals.size();
  st.portalsBeforeJoin = prepared.merged ? prepared.joined.portalsBefore : sub.portals.size();
  st.deadCells = prepared.live.deadCells;
  st.deadPortals = prepared.live.deadPortals;
  st.threads = threads;
}

int resolvedThreads(const PropagationOptions& options) {
  return options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
}

VisibilityGraph computeVisibility(const Scene& scene, const Subdivision& input,
                                  const PropagationOptions& options) {
  const auto start = Clock::now();
  const SearchSubdivision prepared =
      prepareSearchSubdivision(scene, input, options.mergeConvexCells);
  const Subdivision& sub = prepared.get();
  const Tolerance tol = sub.tree.tol;
  const size_t n = scene.patches.size();
  const int threads = resolvedThreads(options);
  VisibilityGraph graph;
  VisibilityStats& st = graph.stats;
  if (n >= kMaxPatches)
    throw std::length_error(
        fmt::format("visibility: {} patches, at most {} supported", n, kMaxPatches - 1));
  recordSubdivisionStats(prepared, n, threads, st);

  const CellVisibility cells = computeCellVisibility(sub, threads, options, st);  // §4.1
  st.cellSeconds = secondsSince(start);

  const auto patchStart = Clock::now();
  std::vector<PatchSearchResult> seen =
      searchPatches(scene, sub, cells, threads, options, st);  // §4.2
  st.coplanarGrazePairs = addCoplanarGrazes(scene, sub.tree.planes, tol, seen);
  st.patchSeconds = secondsSince(patchStart);

  detectBlockers(scene, seen, tol, threads, options, graph);  // §5
  st.seconds = secondsSince(start);
  return graph;
}

}  // namespace gv
