// Visibility propagation (paper §4.1–4.2) and blocker detection (§5).
//
// Cell level: from every cell, a depth-first search over portal sequences, each step kept only
// while the sequence admits a stabbing line; reached cells are the cells it may see.
// Patch level: from every patch S, the same search with S's piece in its cell prefixed to the
// sequence (a tighter start than the whole cell). In every reached cell each patch T is tested as
// the sequence's last "portal", crossed the way a sightline would cross it; T is then "seen" from
// S, and "seen from the front" when the sightline meets T's front. Pairs seen front to front
// from both ends interact. Their blockers are the patches seen from S or from T that meet
// conv(S, T): the first patch a segment from S meets lies in a cell the search reached through
// the portals that segment crossed, and the segment crosses that patch after those portals, so
// the search saw it (stabbing is never "no" when a line exists).
#include "visibility/propagation.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/concurrent_queue.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cmath>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <stdexcept>

#include "quake/leaf_pvs.h"
#include "util/timing.h"
#include "visibility/blocker_lists.h"
#include "visibility/facing_lines.h"
#include "visibility/hull_overlap.h"
#include "visibility/live_cells.h"
#include "visibility/might_see.h"
#include "visibility/patch_grid.h"

namespace gv {
namespace {

/// Blocker lists are built for this many entries of the sources' seen lists at a time (one
/// pipeline token; a source's pairs come from its entries): small enough that the chunks in
/// flight are little memory (at most this many pairs each), large enough to amortise the
/// hand-over.
constexpr uint64_t kSeenPerChunk = 1024;
/// Chunks in flight per thread: room for threads to work ahead of a slow chunk that holds up
/// the in-order hand-over.
constexpr size_t kChunksInFlightPerThread = 3;
/// Flags of the blocker stage's candidates: seen from the pair's S, from its T.
constexpr uint8_t kFromS = 1, kFromT = 2;
/// A membership flag costs about this fraction of a binary search in seen(T) (both per
/// candidate; flags need a pass over seen(T) to set and one to clear).
constexpr size_t kFlagsPerSearch = 4;

/// A chunk whose id array grew past this (16 MiB) gives it back after the hand-over instead of
/// keeping it for reuse.
constexpr size_t kKeptIdsPerChunk = size_t{1} << 22;

/// Above this many bits of per-directed-portal cell sets (2 x portals x cells; 2^32 bits =
/// 512 MiB) the leaf-PVS cell search is not used.
constexpr double kMaxPortalFlowBits = 4294967296.0;

/// A patch's piece inside (or on the boundary of) one cell, and which way its front looks.
struct CellPatch {
  uint32_t patch = 0;
  ConvexPolygon piece;
  bool facesIn = false;   ///< the front looks into the cell
  bool interior = false;  ///< lies inside the cell: sightlines may meet either side
  bool whole = false;     ///< the piece is the whole patch
};

/// The part of p within the cell, grown by the BSP's plane-merging tolerance so that pieces moved
/// onto merged planes are never lost (a larger piece only makes the search see more).
std::optional<ConvexPolygon> clipToCell(const ConvexPolygon& p, const ConvexPolyhedron& cell,
                                        const Tolerance& tol) {
  std::optional<ConvexPolygon> cur = p;
  const double slack = tol.planeOffset();
  for (const Plane& h : cell.halfspaces) {
    cur = clipToFront(*cur, Plane{-h.normal, -h.offset - slack}, tol);  // keep h.distance <= slack
    if (!cur) return std::nullopt;
  }
  return cur;
}

/// Some vertex of `b` strictly in front of `a`'s plane, and vice versa: only such pairs can
/// exchange light front to front.
bool canFace(const ConvexPolygon& a, const ConvexPolygon& b, double eps) {
  auto someInFront = [eps](const ConvexPolygon& of, const ConvexPolygon& plane) {
    for (const Vec3& v : of.vertices)
      if (plane.plane.distance(v) > eps) return true;
    return false;
  };
  return someInFront(b, a) && someInFront(a, b);
}

/// Seen flags of one source patch.
enum : uint8_t { kSeen = 1, kSeenFront = 2 };

/// The flags a search can give a patch through this piece of it.
uint8_t attainable(const CellPatch& cp) {
  return (cp.facesIn || cp.interior) ? (kSeen | kSeenFront) : kSeen;
}

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

struct PatchSearchResult {
  std::vector<uint32_t> seen;             ///< seenEntry(patch, flags), sorted by patch
  std::vector<uint32_t> sameCellVisible;  ///< patches proven VISIBLE by the shortcut
  StabbingStats stabbing;
  uint64_t facingRuleTests = 0;  ///< (S, T) tests in S's own cell, decided by testInSourceCell
  bool overBudget = false;       ///< the search gave up: `seen` is everything it might reach
};

using Placements = std::vector<std::vector<std::pair<uint32_t, size_t>>>;

/// Where a sightline may go after crossing a portal (a superset): the leaf-PVS flow of that
/// directed portal (the cells its stabbable sequences reach) when it was computed, else the
/// might-see flood.
struct PortalReach {
  const std::vector<CellSet>* flow = nullptr;  ///< leaf_pvs.h numbering: 2i = into portal i's front
  const MightSee* might = nullptr;
  const CellSet& through(uint32_t pid, bool forward) const {
    return flow ? (*flow)[2 * pid + (forward ? 0 : 1)] : might->through(pid, forward);
  }
};

/// Per-thread state of the patch-level search. Beyond the stabbing test it prunes a branch when
/// every cell the branch might still reach (MightSee) holds only patches already seen in every
/// way they can be seen: the search's only output is those flags, so nothing is lost.
/// Throws PropagationDeadlineExceeded once `deadline` has passed; reads the clock every 64 calls
/// (a search step costs far more than a clock read, but there are millions of them).
class DeadlineCheck {
 public:
  Clock::time_point deadline = Clock::time_point::max();
  void operator()() {
    if (deadline == Clock::time_point::max() || ++calls_ % 64 != 0) return;
    if (Clock::now() > deadline) throw PropagationDeadlineExceeded();
  }

 private:
  uint32_t calls_ = 0;
};

class PatchSearch {
 public:
  DeadlineCheck checkDeadline;
  PatchSearch(const Subdivision& sub, const std::vector<std::vector<CellPatch>>& cellPatches,
              const Placements& placements, const PortalReach& might,
              const std::vector<CellSet>& cellReach, const Tolerance& tol)
      : sub_(sub),
        cellPatches_(cellPatches),
        placements_(placements),
        might_(might),
        cellReach_(cellReach),
        stabber_(tol),
        flags_(placements.size(), 0),
        onPath_(sub.cells.size(), 0),
        unsaturatedCount_(sub.cells.size(), 0),
        unsaturated_(sub.cells.size()),
        tol_(tol) {
    for (uint32_t c = 0; c < sub.cells.size(); ++c) {
      baseCount_.push_back(static_cast<uint32_t>(cellPatches[c].size()));
      if (!cellPatches[c].empty()) unsaturated_.insert(c);
    }
    unsaturatedCount_ = baseCount_;
  }

  PatchSearchResult run(uint32_t s) {
    PatchSearchResult result;
    stabber_.resetStats();
    facingRuleTests_ = 0;
    source_ = s;
    overBudget_ = false;
    // The source's own pieces are never targets: they count as saturated.
    for (auto [cell, k] : placements_[s]) decrement(cell);
    for (auto [cell, k] : placements_[s]) {
      const CellPatch& cp = cellPatches_[cell][k];
      if (!cp.facesIn && !cp.interior) continue;  // S's front does not look into this cell
      stabber_.clear();
      if (stabber_.push(cp.piece.vertices) == StabbingResult::Blocked) continue;  // degenerate
      sourcePiece_ = &cp.piece;
      const bool cellEmpty = sub_.cells[cell].interiorPatches.empty();
      if (cp.whole && cellEmpty) {
        for (const CellPatch& t : cellPatches_[cell])
          if (t.patch != s && t.whole && t.facesIn) result.sameCellVisible.push_back(t.patch);
      }
      // A sightline from S is one from S's cell: it reaches only cells the cell search reached.
      visit(cell, 0, cellReach_.empty() ? nullptr : &cellReach_[cell]);
      if (overBudget_) break;
    }
    if (overBudget_) {
      markEverythingReachable(s);
      result.overBudget = true;
    }
    for (uint32_t t : touched_) {
      result.seen.push_back(seenEntry(t, flags_[t]));
      flags_[t] = 0;
    }
    touched_.clear();
    for (uint32_t c : touchedCells_) {
      unsaturatedCount_[c] = baseCount_[c];
      if (baseCount_[c] > 0) unsaturated_.insert(c);
    }
    touchedCells_.clear();
    std::sort(result.seen.begin(), result.seen.end());
    std::sort(result.sameCellVisible.begin(), result.sameCellVisible.end());
    result.sameCellVisible.erase(
        std::unique(result.sameCellVisible.begin(), result.sameCellVisible.end()),
        result.sameCellVisible.end());
    result.stabbing = stabber_.stats();
    result.facingRuleTests = facingRuleTests_;
    return result;
  }

  /// Portal sequences (pushes of portals and targets) one run may test before it gives up and
  /// marks everything it might reach (0: no limit).
  void setBudget(uint64_t pushes) { budget_ = pushes ? pushes : UINT64_MAX; }

 private:
  /// The conservative answer of a search over budget: every piece in every cell S's cells may
  /// see (the cell search's sets; without them, the cells the flows of their portals reach), with
  /// every flag it could get there. The search itself marks only pieces in such cells: a sequence
  /// stabbed from S's piece is one stabbed from S's cell.
  void markEverythingReachable(uint32_t s) {
    CellSet cells(sub_.cells.size());
    for (auto [cell, k] : placements_[s]) {
      const CellPatch& cp = cellPatches_[cell][k];
      if (!cp.facesIn && !cp.interior) continue;
      if (!cellReach_.empty()) {
        cells.unite(cellReach_[cell]);
        continue;
      }
      cells.insert(cell);
      for (uint32_t pid : sub_.cells[cell].portals) {
        const Portal& p = sub_.portals[pid];
        cells.unite(might_.through(pid, p.front != cell));
      }
    }
    cells.forEach([&](size_t c) {
      for (const CellPatch& t : cellPatches_[c])
        if (t.patch != s) mark(t.patch, attainable(t));
    });
  }

  void decrement(uint32_t cell) {
    if (unsaturatedCount_[cell] == baseCount_[cell]) touchedCells_.push_back(cell);
    if (--unsaturatedCount_[cell] == 0) unsaturated_.erase(cell);
  }

  void mark(uint32_t t, uint8_t f) {
    const uint8_t before = flags_[t];
    const uint8_t after = before | f;
    if (after == before) return;
    if (before == 0) touched_.push_back(t);
    flags_[t] = after;
    for (auto [cell, k] : placements_[t]) {
      const uint8_t need = attainable(cellPatches_[cell][k]);
      if ((before & need) != need && (after & need) == need) decrement(cell);
    }
  }

  /// The sequence (S's piece, T's piece) inside one convex cell, decided exactly by
  /// facingLines (facing_lines.h) instead of the stabbing kernel.
  void testInSourceCell(const CellPatch& t) {
    const uint8_t have = flags_[t.patch];
    const bool wantFront = (t.facesIn || t.interior) && !(have & kSeenFront);
    const bool wantBack = (!t.facesIn || t.interior) && !(have & kSeen);
    if (!wantFront && !wantBack) return;
    const FacingLines lines = facingLines(*sourcePiece_, t.piece, tol_.length());
    if (wantFront) {
      ++facingRuleTests_;
      if (lines.throughFront) mark(t.patch, kSeen | kSeenFront);
    }
    if (wantBack && !(flags_[t.patch] & kSeen)) {
      ++facingRuleTests_;
      if (lines.throughBack) mark(t.patch, kSeen);
    }
  }

  /// Tests T crossed the way a sightline arriving from inside the cell crosses it.
  void testTarget(const CellPatch& t) {
    if (t.patch == source_) return;
    if (stabber_.depth() == 1) {
      testInSourceCell(t);
      return;
    }
    const uint8_t have = flags_[t.patch];
    // Front hit: the line crosses T from its front to its back (loop reversed = travel normal).
    if ((t.facesIn || t.interior) && !(have & kSeenFront)) {
      scratch_.assign(t.piece.vertices.rbegin(), t.piece.vertices.rend());
      if (stabber_.push(scratch_) != StabbingResult::Blocked) {
        mark(t.patch, kSeen | kSeenFront);
        stabber_.pop();
      }
    }
    if ((!t.facesIn || t.interior) && !(flags_[t.patch] & kSeen)) {
      if (stabber_.push(t.piece.vertices) != StabbingResult::Blocked) {
        mark(t.patch, kSeen);
        stabber_.pop();
      }
    }
  }

  /// `reach`: the cells this branch may still reach (null: all).
  void visit(uint32_t cell, size_t depth, const CellSet* reach) {
    checkDeadline();
    if (overBudget_ || stabber_.stats().tests >= budget_) {
      overBudget_ = true;  // unwinds the search; run() then answers conservatively
      return;
    }
    onPath_[cell] = 1;
    for (const CellPatch& t : cellPatches_[cell]) testTarget(t);
    if (stack_.size() <= depth) stack_.resize(depth + 1);
    for (uint32_t pid : sub_.cells[cell].portals) {
      const Portal& p = sub_.portals[pid];
      const uint32_t next = p.other(cell);
      if (onPath_[next]) continue;  // a line cannot enter a convex cell twice
      const bool forward = p.front == next;
      const CellSet& through = might_.through(pid, forward);
      CellSet& nextReach = stack_[depth];
      if (reach) nextReach.assignIntersection(*reach, through);
      const CellSet& r = reach ? nextReach : through;
      if (!r.intersects(unsaturated_)) continue;  // nothing new can be seen that way
      if (forward) {
        scratch_ = p.polygon.vertices;
      } else {
        scratch_.assign(p.polygon.vertices.rbegin(), p.polygon.vertices.rend());
      }
      if (stabber_.push(scratch_) == StabbingResult::Blocked) continue;
      visit(next, depth + 1, &r);
      stabber_.pop();
      if (overBudget_) break;
    }
    onPath_[cell] = 0;
  }

  const Subdivision& sub_;
  const std::vector<std::vector<CellPatch>>& cellPatches_;
  const Placements& placements_;
  const PortalReach& might_;
  const std::vector<CellSet>& cellReach_;  // per cell, the cells it may see (empty: unknown)
  PortalSequenceStabber stabber_;
  std::vector<uint8_t> flags_;
  std::vector<uint32_t> touched_, touchedCells_;
  std::vector<uint8_t> onPath_;
  std::vector<uint32_t> baseCount_, unsaturatedCount_;
  CellSet unsaturated_;
  std::deque<CellSet> stack_;  // deque: growing it keeps references to its elements valid
  std::vector<Vec3> scratch_;
  uint32_t source_ = 0;
  const ConvexPolygon* sourcePiece_ = nullptr;  // S's piece that starts the current sequence
  uint64_t facingRuleTests_ = 0;
  uint64_t budget_ = UINT64_MAX;  // stabbing tests per run (setBudget)
  bool overBudget_ = false;
  Tolerance tol_;
};

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

/// Sorts distinct ids in [0, 64 bits.size()): by std::sort when there are few, else by setting
/// their bits in `bits` (all clear on entry and on return) and reading them back in order, which
/// is cheaper once the ids are more than a sparse sample of the range.
void sortIds(std::span<uint32_t> ids, std::vector<uint64_t>& bits) {
  if (ids.size() < 64 || double(ids.size()) * std::log2(double(ids.size())) < double(bits.size())) {
    std::sort(ids.begin(), ids.end());
    return;
  }
  uint32_t lo = UINT32_MAX, hi = 0;
  for (uint32_t id : ids) {
    bits[id >> 6] |= uint64_t{1} << (id & 63);
    lo = std::min(lo, id);
    hi = std::max(hi, id);
  }
  size_t k = 0;
  for (size_t word = lo >> 6; word <= (hi >> 6); ++word) {
    for (uint64_t b = bits[word]; b; b &= b - 1)
      ids[k++] = static_cast<uint32_t>(word * 64 + size_t(std::countr_zero(b)));
    bits[word] = 0;
  }
}

/// Runs fn(worker, index) for index in [0, n) on at most `threads` oneTBB workers, each with its
/// own state from makeWorker(); each index exactly once. Results land per index, so the output
/// does not depend on the schedule.
template <typename MakeWorker, typename Fn>
void parallelFor(size_t n, int threads, MakeWorker makeWorker, Fn fn) {
  using Worker = decltype(makeWorker());
  tbb::enumerable_thread_specific<Worker> workers(makeWorker);
  tbb::task_arena arena(threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1),
                      [&](const tbb::blocked_range<size_t>& r) {
                        Worker& w = workers.local();
                        for (size_t i = r.begin(); i < r.end(); ++i) fn(w, i);
                      });
  });
}

}  // namespace

void SequenceHistogram::add(size_t length, bool success) {
  auto& v = success ? successes : failures;
  if (successes.size() <= length) successes.resize(length + 1, 0);
  if (failures.size() <= length) failures.resize(length + 1, 0);
  ++v[length];
}

SequenceHistogram& SequenceHistogram::operator+=(const SequenceHistogram& o) {
  successes.resize(std::max(successes.size(), o.successes.size()), 0);
  failures.resize(std::max(failures.size(), o.failures.size()), 0);
  for (size_t i = 0; i < o.successes.size(); ++i) successes[i] += o.successes[i];
  for (size_t i = 0; i < o.failures.size(); ++i) failures[i] += o.failures[i];
  return *this;
}

VisibilityGraph computeVisibility(const Scene& scene, const Subdivision& input,
                                  const PropagationOptions& options) {
  const auto start = Clock::now();
  // Regions no patch faces into (closed solids' insides) lose their portals first: the searches
  // would walk them for nothing (live_cells.cpp says why nothing is lost).
  const LiveCells live = findLiveCells(scene, input);
  std::optional<Subdivision> pruned;
  if (live.deadPortals > 0) pruned = withoutDeadPortals(input, live);
  const Subdivision& sub = pruned ? *pruned : input;
  const Tolerance tol = sub.tree.tol;
  const size_t n = scene.patches.size();
  const int threads =
      options.threads > 0 ? options.threads : tbb::this_task_arena::max_concurrency();
  VisibilityGraph graph;
  VisibilityStats& st = graph.stats;
  if (n >= kMaxPatches)
    throw std::length_error(
        fmt::format("visibility: {} patches, at most {} supported", n, kMaxPatches - 1));
  st.patches = n;
  st.cells = sub.cells.size();
  st.portals = input.portals.size();
  st.deadCells = live.deadCells;
  st.deadPortals = live.deadPortals;
  st.threads = threads;

  // Cell to cell (§4.1). Where the sets fit (portals × cells bits), the Quake-style search of
  // leaf_pvs.h over our cells: one search per directed portal, in waves that let finished
  // portals' results narrow later searches; its per-portal results (flows) then bound the patch
  // searches far more tightly than the might-see flood. Otherwise a search per cell, pruned by
  // the flood.
  std::vector<CellSet> cellReach;  // per cell, the cells it may see (symmetric), if known
  std::vector<CellSet> flow;
  std::optional<MightSee> flood;
  PortalReach reach;
  const double setBits = 2.0 * double(sub.portals.size()) * double(sub.cells.size());
  if (setBits <= kMaxPortalFlowBits) {
    PrtFile cellGraph;
    cellGraph.leafCount = cellGraph.clusterCount = sub.cells.size();
    cellGraph.leafCluster.resize(sub.cells.size());
    cellGraph.clusterLeafs.resize(sub.cells.size());
    for (size_t c = 0; c < sub.cells.size(); ++c) {
      cellGraph.leafCluster[c] = static_cast<int>(c);
      cellGraph.clusterLeafs[c] = {static_cast<int>(c)};
    }
    for (const Portal& p : sub.portals)  // the polygon's normal points from back into front
      cellGraph.portals.push_back(
          {p.polygon.vertices, static_cast<int>(p.back), static_cast<int>(p.front), 0});
    LeafPvsOptions pvsOptions;
    // Closed portals: the contract lists a pair if *any* segment between them is clear, grazing
    // ones included, so the cell search keeps lines that only touch portal edges (the leaf PVS
    // of `pvs` reads portals as open, kPvsEdgeClearance).
    pvsOptions.stabbing.blockedBelow = -kStabbingLpMargin;
    // The tightest cell visibility (it bounds every patch search; the cell search is a small
    // part of `vis`).
    pvsOptions.bothSides = true;
    pvsOptions.parallel = threads > 1;
    pvsOptions.maxSequencesPerSearch = options.cellSequenceBudget;
    // Between waves of the search: progress, and the deadline (a wave is short).
    pvsOptions.progress = [&](size_t done, size_t total) {
      if (options.deadline != Clock::time_point::max() && Clock::now() > options.deadline)
        throw PropagationDeadlineExceeded();
      if (options.cellProgress) options.cellProgress(done, total);
    };
    tbb::task_arena arena(threads);
    LeafPvsResult pvs;
    arena.execute([&] { pvs = computeLeafPvs(cellGraph, pvsOptions); });
    cellReach.resize(sub.cells.size(), CellSet(sub.cells.size()));
    for (size_t c = 0; c < sub.cells.size(); ++c)
      for (uint32_t d : pvs.visibleLeafs[c]) cellReach[c].insert(d);
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
    for (size_t c = 0; c < sub.cells.size(); ++c) st.cellPairsVisible += pvs.visibleLeafs[c].size();
    st.meanSequenceLength =
        st.cellStabbingTests ? double(lengthSum) / double(st.cellStabbingTests) : 0;
    st.cellStabbing = pvs.stabbing;
    st.cellSearchesOverBudget = pvs.searchesOverBudget;
    flow = std::move(pvs.portalFlow);
    reach.flow = &flow;
  } else {
    flood.emplace(sub, tol);
    reach.might = &*flood;
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
  st.cellSeconds = secondsSince(start);

  // Pieces of patches per cell, and where each patch lies.
  const auto patchStart = Clock::now();
  std::vector<std::vector<CellPatch>> cellPatches(sub.cells.size());
  Placements placements(n);
  for (uint32_t c = 0; c < sub.cells.size(); ++c) {
    const Cell& cell = sub.cells[c];
    const Vec3 inside = cell.shape.centroid();
    for (uint32_t p : cell.patches) {
      const ConvexPolygon& poly = scene.patches[p].polygon;
      auto piece = clipToCell(poly, cell.shape, tol);
      if (!piece) continue;
      CellPatch cp;
      cp.patch = p;
      cp.interior = std::binary_search(cell.interiorPatches.begin(), cell.interiorPatches.end(), p);
      cp.facesIn = poly.plane.distance(inside) > 0;
      cp.whole = piece->area() >= poly.area() * (1 - 1e-9);
      cp.piece = std::move(*piece);
      placements[p].emplace_back(c, cellPatches[c].size());
      cellPatches[c].push_back(std::move(cp));
    }
  }

  // Patch searches (§4.2).
  std::vector<PatchSearchResult> seen(n);
  std::atomic<size_t> done{0};
  std::mutex progressMutex;
  parallelFor(
      n, threads,
      [&] {
        PatchSearch w(sub, cellPatches, placements, reach, cellReach, tol);
        w.checkDeadline.deadline = options.deadline;
        w.setBudget(options.patchSequenceBudget);
        return w;
      },
      [&](PatchSearch& w, size_t s) {
        seen[s] = w.run(static_cast<uint32_t>(s));
        const size_t d = ++done;
        if (options.progress && (d % 64 == 0 || d == n)) {
          std::lock_guard lock(progressMutex);
          options.progress(d, n);
        }
      });
  StabbingStats stabbing;
  uint64_t seenEntries = 0;
  for (const PatchSearchResult& r : seen) {
    stabbing += r.stabbing;
    st.patchFacingRuleTests += r.facingRuleTests;
    seenEntries += r.seen.size();
    st.patchSearchesOverBudget += r.overBudget;
  }
  st.meanPatchesSeen = n ? double(seenEntries) / double(n) : 0;
  st.patchStabbingTests = stabbing.tests + st.patchFacingRuleTests;
  st.patchStabbing = stabbing;
  st.unresolvedStabbing = stabbing.unresolved + stabbing.lpNumericalFailures;
  st.patchSeconds = secondsSince(patchStart);

  // Interactions and blockers (§5).
  const auto blockerStart = Clock::now();
  auto flagsOf = [&](uint32_t s, uint32_t t) -> uint8_t {
    const auto& v = seen[s].seen;
    auto it = std::lower_bound(v.begin(), v.end(), seenEntry(t, 0));
    return (it != v.end() && seenPatch(*it) == t) ? seenFlags(*it) : 0;
  };
  auto isSameCellVisible = [&](uint32_t s, uint32_t t) {
    const auto& v = seen[s].sameCellVisible;
    return std::binary_search(v.begin(), v.end(), t);
  };
  std::vector<Aabb> patchBoxes(n);
  for (size_t p = 0; p < n; ++p) patchBoxes[p] = scene.patches[p].polygon.bounds();
  // Candidates come from a grid of patch boxes: only patches whose boxes meet conv(S, T)'s box
  // can meet conv(S, T), so the scan no longer walks all of seen(S) and seen(T) for every pair.
  const PatchGrid grid(patchBoxes);
  // The candidates' vertices in one array, patch by patch: candidates are tested in id order, so
  // the test walks this array forwards instead of chasing a vector per patch.
  std::vector<uint32_t> vertexStart(n + 1, 0);
  for (size_t p = 0; p < n; ++p)
    vertexStart[p + 1] = vertexStart[p] + uint32_t(scene.patches[p].polygon.vertices.size());
  std::vector<Vec3> vertices(vertexStart[n]);
  for (size_t p = 0; p < n; ++p)
    std::copy(scene.patches[p].polygon.vertices.begin(), scene.patches[p].polygon.vertices.end(),
              vertices.begin() + vertexStart[p]);
  // The candidates' plane normals in one array (a Patch is far larger than its normal).
  std::vector<Vec3> normals(n);
  std::vector<double> normalLengths(n);
  for (size_t p = 0; p < n; ++p) {
    normals[p] = scene.patches[p].polygon.plane.normal;
    normalLengths[p] = length(normals[p]);
  }
  struct BlockerWorker {
    std::vector<uint8_t> seen;       ///< per patch: kFromS (in seen(S)) | kFromT (in seen(T))
    std::vector<uint32_t> gathered;  ///< room for every patch: PatchGrid::gatherInto's output
    std::vector<uint64_t> bits;      ///< one per patch, all clear between calls of sortIds
  };
  // Work is counted in entries of the seen lists, all sources' lists one after another: source
  // s holds positions [seenStart[s], seenStart[s + 1]), and its pairs (s, t) come from them.
  std::vector<uint64_t> seenStart(n + 1, 0);
  for (size_t p = 0; p < n; ++p) seenStart[p + 1] = seenStart[p] + seen[p].seen.size();
  struct Chunk {
    uint64_t begin = 0, end = 0;  ///< positions [begin, end) of the seen lists
    size_t sourcesDone = 0;       ///< sources whose lists end by `end`
    BlockerLists lists;
    uint64_t visible = 0, partial = 0, sameCell = 0;
  };
  // The interactions (s, t), t > s, for entries [from, to) of seen(s), in t order, with their
  // blocker lists, appended to `chunk`.
  auto blockersOf = [&](BlockerWorker& w, uint32_t s, size_t from, size_t to, Chunk& chunk) {
    const ConvexPolygon& sp = scene.patches[s].polygon;
    for (uint32_t e : seen[s].seen) w.seen[seenPatch(e)] = kFromS;
    for (size_t k = from; k < to; ++k) {
      const uint32_t e = seen[s].seen[k];
      const uint32_t t = seenPatch(e);
      const uint8_t f = seenFlags(e);
      if (t <= s) continue;
      // Both searches are conservative and a sightline runs both ways, so a real pair is seen
      // front to front from each end: requiring both is exact pruning, not a guess.
      const bool front = (f & kSeenFront) && (flagsOf(t, s) & kSeenFront);
      const ConvexPolygon& tp = scene.patches[t].polygon;
      if (!front || !canFace(sp, tp, tol.length())) continue;
      BlockerLists& lists = chunk.lists;
      lists.addPair(s, t);  // its blockers are appended below, straight into the chunk
      if (isSameCellVisible(s, t) || isSameCellVisible(t, s)) {
        ++chunk.sameCell;
      } else {
        const PairHull hull(sp, tp, tol);
        Aabb box = patchBoxes[s];
        box.add(patchBoxes[t]);
        // The slack is PairHull's box tolerance: the grid does PairHull's box test.
        const std::span<uint32_t> candidates(
            w.gathered.data(), grid.gatherInto(box, tol.length(), w.gathered.data(), &hull));
        const auto& b = seen[t].seen;
        sortIds(candidates, w.bits);  // blockers come out sorted
        // Seen from T: by flags when there are many candidates to ask about (setting them
        // costs a pass over seen(T)), else by searches in the sorted seen(T).
        const bool flagT = candidates.size() * kFlagsPerSearch > b.size();
        if (flagT)
          for (uint32_t entry : b) w.seen[seenPatch(entry)] |= kFromT;
        auto fromT = b.begin();  // candidates rise: each search starts where the last ended
        for (uint32_t c : candidates) {
          if (c == s || c == t) continue;
          if (flagT) {
            if (!w.seen[c]) continue;
          } else if (!w.seen[c]) {
            fromT = std::lower_bound(fromT, b.end(), seenEntry(c, 0));
            if (fromT == b.end() || seenPatch(*fromT) != c) continue;
          }
          const std::span<const Vec3> cv(vertices.data() + vertexStart[c],
                                         vertices.data() + vertexStart[c + 1]);
          if (hull.meetsInBox(cv, normals[c], normalLengths[c])) lists.addBlocker(c);
        }
        if (flagT)
          for (uint32_t entry : b) w.seen[seenPatch(entry)] &= kFromS;
      }
      ++(lists.blockers(lists.size() - 1).empty() ? chunk.visible : chunk.partial);
    }
    for (uint32_t e : seen[s].seen) w.seen[seenPatch(e)] = 0;
  };
  // Chunks of kSeenPerChunk seen-list entries through a pipeline: worked on in parallel and
  // handed on (to the sink or into the graph) one at a time in order, so the output is (s, r)
  // sorted whatever the schedule, and with a sink only the chunks in flight are held: each is at
  // most kSeenPerChunk pairs, a source that saw many patches being cut into several. Chunks are
  // reused (no allocation once their arrays have grown), unless they grew past kKeptIdsPerChunk.
  tbb::enumerable_thread_specific<BlockerWorker> blockerWorkers([n, &grid] {
    return BlockerWorker{std::vector<uint8_t>(n, 0), std::vector<uint32_t>(grid.patchCount()),
                         std::vector<uint64_t>((n + 63) / 64, 0)};
  });
  std::vector<std::unique_ptr<Chunk>> chunks;  // every chunk made (touched by the first stage)
  tbb::concurrent_queue<Chunk*> freeChunks;    // handed back by the last stage
  std::vector<std::pair<uint32_t, uint32_t>> partialPairs;  // in order, for the shaft sample
  uint64_t blockerSum = 0;
  uint64_t nextPosition = 0;
  size_t sourcesReported = 0;
  {
    tbb::task_arena arena(threads);
    arena.execute([&] {
      tbb::parallel_pipeline(
          kChunksInFlightPerThread * size_t(threads),
          tbb::make_filter<void, Chunk*>(
              tbb::filter_mode::serial_in_order,
              [&](tbb::flow_control& fc) -> Chunk* {
                if (nextPosition >= seenStart[n]) {
                  fc.stop();
                  return nullptr;
                }
                Chunk* chunk = nullptr;
                if (!freeChunks.try_pop(chunk)) {
                  chunks.push_back(std::make_unique<Chunk>());
                  chunk = chunks.back().get();
                }
                chunk->begin = nextPosition;
                chunk->end = nextPosition = std::min(seenStart[n], nextPosition + kSeenPerChunk);
                // Sources s with seenStart[s + 1] <= end.
                chunk->sourcesDone =
                    size_t(std::upper_bound(seenStart.begin() + 1, seenStart.end(), chunk->end) -
                           (seenStart.begin() + 1));
                return chunk;
              }) &
              tbb::make_filter<Chunk*, Chunk*>(
                  tbb::filter_mode::parallel,
                  [&](Chunk* chunk) {
                    if (options.deadline != Clock::time_point::max() &&
                        Clock::now() > options.deadline)
                      throw PropagationDeadlineExceeded();
                    BlockerWorker& w = blockerWorkers.local();
                    // The first source with entries at or after `begin`, then on while its
                    // entries start before `end`.
                    size_t s =
                        size_t(std::upper_bound(seenStart.begin(), seenStart.end(), chunk->begin) -
                               seenStart.begin()) -
                        1;
                    for (; s < n && seenStart[s] < chunk->end; ++s) {
                      const uint64_t from = std::max(chunk->begin, seenStart[s]);
                      const uint64_t to = std::min(chunk->end, seenStart[s + 1]);
                      if (from < to)
                        blockersOf(w, static_cast<uint32_t>(s), size_t(from - seenStart[s]),
                                   size_t(to - seenStart[s]), *chunk);
                    }
                    return chunk;
                  }) &
              tbb::make_filter<Chunk*, void>(tbb::filter_mode::serial_in_order, [&](Chunk* chunk) {
                const BlockerLists& lists = chunk->lists;
                st.pairsVisible += chunk->visible;
                st.pairsPartial += chunk->partial;
                st.sameCellShortcuts += chunk->sameCell;
                blockerSum += lists.idCount();
                for (size_t k = 0; k < lists.size(); ++k)
                  if (!lists.blockers(k).empty()) partialPairs.emplace_back(lists.s(k), lists.r(k));
                if (options.interactionSink) {
                  options.interactionSink(lists);
                } else {
                  for (size_t k = 0; k < lists.size(); ++k) {
                    const auto ids = lists.blockers(k);
                    graph.interactions.push_back(
                        {lists.s(k), lists.r(k), std::vector<uint32_t>(ids.begin(), ids.end())});
                  }
                }
                if (options.blockerProgress && chunk->sourcesDone > sourcesReported)
                  options.blockerProgress(sourcesReported = chunk->sourcesDone, n);
                if (chunk->lists.idCapacity() > kKeptIdsPerChunk) chunk->lists = {};
                chunk->lists.clear();
                chunk->visible = chunk->partial = chunk->sameCell = 0;
                freeChunks.push(chunk);
              }));
    });
  }
  if (options.blockerProgress && sourcesReported < n) options.blockerProgress(n, n);
  st.meanBlockersPerPartial = st.pairsPartial ? double(blockerSum) / double(st.pairsPartial) : 0;
  st.blockerSeconds = secondsSince(blockerStart);

  // Shaft-culling baseline (Haines & Wallace): every patch meeting conv(S, R), on a sample.
  if (st.pairsPartial > 0 && options.shaftSamples > 0) {
    const uint64_t stride = std::max<uint64_t>(1, st.pairsPartial / options.shaftSamples);
    uint64_t k = 0, sum = 0;
    for (const auto& [ps, pr] : partialPairs) {
      if ((k++ % stride) != 0) continue;
      const PairHull hull(scene.patches[ps].polygon, scene.patches[pr].polygon, tol);
      for (uint32_t c = 0; c < n; ++c)
        if (c != ps && c != pr && hull.meets(scene.patches[c].polygon, patchBoxes[c])) ++sum;
      ++st.shaftSamples;
    }
    st.meanShaftCullPerPartial = double(sum) / double(st.shaftSamples);
  }
  st.seconds = secondsSince(start);
  return graph;
}

}  // namespace gv
