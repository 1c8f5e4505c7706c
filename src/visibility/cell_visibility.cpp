// Cell-to-cell visibility (paper §4.1): the cell PVS over the subdivision, or, where its
// per-portal sets would not fit, a search from every cell pruned by the might-see flood; both
// keep only portal sequences that admit a stabbing line (see cell_visibility.h).
#include "visibility/cell_visibility.h"

#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <deque>
#include <mutex>

#include "geometry/portal_graph.h"
#include "util/parallel_for.h"
#include "util/timing.h"
#include "visibility/cell_pvs.h"
#include "visibility/search_deadline.h"
#include "visibility/stabbing.h"

namespace gv {
namespace {

/// Above this many bits of per-directed-portal cell sets (2 x portals x cells; 2^32 bits =
/// 512 MiB) the cell PVS is not used.
constexpr double kMaxPortalFlowBits = 4294967296.0;

/// Cell-to-cell search from one source cell: counts and the Fig. 13 histogram.
struct CellSearchResult {
  uint64_t reached = 0, tests = 0, lengthSum = 0;
  CellSet reachedSet;  ///< the cells reached, the source included
  SequenceHistogram histogram;
  StabbingStats stabbing;
};

/// The cell-level search, pruned like PatchSearch: a branch stops when every cell it might still
/// reach is already known to be visible from the source.
class CellSearch {
 public:
  DeadlineCheck checkDeadline;
  CellSearch(const Subdivision& sub, const PortalReach& might, const Tolerance& tol)
      : sub_(sub), might_(might), stabber_(tol), onPath_(sub.cells.size(), 0) {}

  CellSearchResult run(uint32_t source) {
    result_ = {};
    unreached_ = CellSet(sub_.cells.size(), true);
    stabber_.clear();
    unreached_.erase(source);
    result_.reached = 1;
    stabber_.resetStats();
    visit(source, 0, nullptr);
    result_.stabbing = stabber_.stats();
    result_.reachedSet = unreached_;
    result_.reachedSet.complement(sub_.cells.size());
    return result_;
  }

 private:
  void visit(uint32_t cell, size_t depth, const CellSet* reach) {
    checkDeadline();
    onPath_[cell] = 1;
    if (stack_.size() <= depth) stack_.resize(depth + 1);
    for (uint32_t pid : sub_.cells[cell].portals) {
      const Portal& p = sub_.portals[pid];
      const uint32_t next = p.other(cell);
      if (onPath_[next]) continue;
      const bool forward = p.front == next;
      const CellSet& through = might_.through(pid, forward);
      CellSet& nextReach = stack_[depth];
      if (reach) nextReach.assignIntersection(*reach, through);
      const CellSet& r = reach ? nextReach : through;
      if (!r.intersects(unreached_)) continue;
      if (forward) {
        scratch_ = p.polygon.vertices;
      } else {
        scratch_.assign(p.polygon.vertices.rbegin(), p.polygon.vertices.rend());
      }
      const StabbingResult res = stabber_.push(scratch_);
      const size_t length = stabber_.depth() + (res == StabbingResult::Blocked ? 1 : 0);
      ++result_.tests;
      result_.lengthSum += length;
      result_.histogram.add(length, res != StabbingResult::Blocked);
      if (res == StabbingResult::Blocked) continue;
      if (unreached_.contains(next)) {
        unreached_.erase(next);
        ++result_.reached;
      }
      visit(next, depth + 1, &r);
      stabber_.pop();
    }
    onPath_[cell] = 0;
  }

  const Subdivision& sub_;
  const PortalReach& might_;
  PortalSequenceStabber stabber_;
  std::vector<uint8_t> onPath_;
  CellSet unreached_;
  std::deque<CellSet> stack_;  // deque: growing it keeps references to its elements valid
  std::vector<Vec3> scratch_;
  CellSearchResult result_;
};

/// The subdivision as a portal graph: the polygon's normal points from back into front.
PortalGraph cellGraphOf(const Subdivision& sub) {
  PortalGraph graph;
  graph.cellCount = sub.cells.size();
  for (const Portal& p : sub.portals)
    graph.portals.push_back({p.polygon.vertices, p.back, p.front});
  return graph;
}

/// The cell PVS over the subdivision, with its statistics in `st`.
void cellPvsVisibility(const Subdivision& sub, int threads, const PropagationOptions& options,
                       VisibilityStats& st, CellVisibility& cv) {
  CellPvsOptions pvsOptions;
  // Closed portals: the contract lists a pair if *any* segment between them is clear, grazing
  // ones included, so the cell search keeps lines that only touch portal edges (the leaf PVS
  // of `pvs` reads portals as open, kPvsEdgeClearance).
  pvsOptions.stabbing.blockedBelow = -kStabbingLpMargin;
  // The tightest cell visibility: it bounds every patch search. (Measured 2026-12-03 on the
  // merged cells, one-sided instead: doom-fd2-map03 10.2 → 9.2 s but doom-fd1-e1m2 6.12 →
  // 6.89 % of pairs listed; q3-oa_dm2 no faster.)
  pvsOptions.bothSides = true;
  pvsOptions.parallel = threads > 1;
  pvsOptions.maxSequencesPerSearch = options.cellSequenceBudget;
  pvsOptions.targetCheckRatio = options.cellTargetChecks;
  // The searches here run under a budget: keep their pruning as strong as it can be.
  pvsOptions.targetCheckWholeBranch = true;
  // Between waves of the search: progress, and the deadline (a wave is short).
  pvsOptions.progress = [&](size_t done, size_t total) {
    if (options.deadline != Clock::time_point::max() && Clock::now() > options.deadline)
      throw PropagationDeadlineExceeded();
    if (options.cellProgress) options.cellProgress(done, total);
  };
  tbb::task_arena arena(threads);
  CellPvsResult pvs;
  arena.execute([&] { pvs = computeCellPvs(cellGraphOf(sub), pvsOptions); });
  cv.cellReach.resize(sub.cells.size(), CellSet(sub.cells.size()));
  for (size_t c = 0; c < sub.cells.size(); ++c)
    for (uint32_t d : pvs.visibleCells[c]) cv.cellReach[c].insert(d);
  // The search's own Fig. 13 counts, both vectors one length (as SequenceHistogram::add keeps).
  SequenceHistogram& h = st.cellHistogram;
  h.successes = std::move(pvs.successesByLength);
  h.failures = std::move(pvs.failuresByLength);
  const size_t lengths = std::max(h.successes.size(), h.failures.size());
  h.successes.resize(lengths, 0);
  h.failures.resize(lengths, 0);
  uint64_t lengthSum = 0;
  for (size_t k = 0; k < lengths; ++k) {
    lengthSum += k * (h.successes[k] + h.failures[k]);
    st.cellStabbingTests += h.successes[k] + h.failures[k];
  }
  for (size_t c = 0; c < sub.cells.size(); ++c) st.cellPairsVisible += pvs.visibleCells[c].size();
  st.meanSequenceLength =
      st.cellStabbingTests ? double(lengthSum) / double(st.cellStabbingTests) : 0;
  st.cellStabbing = pvs.stabbing;
  st.cellSearchesOverBudget = pvs.searchesOverBudget;
  st.cellTargetTests = pvs.targetTests;
  st.cellOverBudgetTests = pvs.overBudgetTests;
  cv.flow = std::move(pvs.portalFlow);
}

/// A search from every cell, pruned by the might-see flood, with its statistics in `st`.
void perCellVisibility(const Subdivision& sub, int threads, const PropagationOptions& options,
                       VisibilityStats& st, CellVisibility& cv) {
  const Tolerance tol = sub.tree.tol;
  cv.flood.emplace(sub, tol);
  const PortalReach reach = cv.reach();
  const std::optional<MightSee>& flood = cv.flood;
  std::vector<CellSet>& cellReach = cv.cellReach;
  std::vector<CellSearchResult> cellResults(sub.cells.size());
  std::atomic<size_t> cellsDone{0};
  std::mutex cellProgressMutex;
  size_t cellsReported = 0;
  parallelFor(
      sub.cells.size(), threads,
      [&] {
        CellSearch w(sub, reach, tol);
        w.checkDeadline.deadline = options.deadline;
        return w;
      },
      [&](CellSearch& w, size_t c) {
        cellResults[c] = w.run(static_cast<uint32_t>(c));
        const size_t d = ++cellsDone;
        if (options.cellProgress && (d % 16 == 0 || d == sub.cells.size())) {
          // Under the lock, the count now (not d): reports rise even when threads race.
          std::lock_guard lock(cellProgressMutex);
          const size_t now = cellsDone.load();
          if (now > cellsReported) options.cellProgress(cellsReported = now, sub.cells.size());
        }
      });
  uint64_t lengthSum = 0;
  for (const CellSearchResult& r : cellResults) {
    st.cellPairsVisible += r.reached;
    st.cellStabbingTests += r.tests;
    lengthSum += r.lengthSum;
    st.cellHistogram += r.histogram;
    st.cellStabbing += r.stabbing;
  }
  st.meanSequenceLength =
      st.cellStabbingTests ? double(lengthSum) / double(st.cellStabbingTests) : 0;
  // Cell visibility is symmetric and each search is conservative: a pair found from one side
  // only is not visible. The symmetric sets bound the patch searches (memory: cells² bits, so
  // only where the flood keeps its sets too).
  if (flood->enabled()) {
    cellReach.resize(sub.cells.size(), CellSet(sub.cells.size()));
    for (size_t c = 0; c < sub.cells.size(); ++c)
      cellResults[c].reachedSet.forEach([&](size_t d) {
        if (cellResults[d].reachedSet.contains(c)) cellReach[c].insert(d);
      });
  }
}

}  // namespace

CellVisibility computeCellVisibility(const Subdivision& sub, int threads,
                                     const PropagationOptions& options, VisibilityStats& st) {
  CellVisibility cv;
  const double setBits = 2.0 * double(sub.portals.size()) * double(sub.cells.size());
  if (setBits <= kMaxPortalFlowBits) {
    cellPvsVisibility(sub, threads, options, st, cv);
  } else {
    perCellVisibility(sub, threads, options, st, cv);
  }
  return cv;
}

}  // namespace gv
