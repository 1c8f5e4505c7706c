// The PVS of a portal graph by depth-first search over portal sequences with the stabbing test
// (paper §4, §4.1). See cell_pvs.h for the method and its guarantees.
#include "visibility/cell_pvs.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <memory>
#include <span>
#include <thread>

#include "geometry/ball.h"
#include "geometry/ball_tree.h"
#include "geometry/tolerance.h"
#include "util/timing.h"
#include "visibility/cell_set.h"
#include "visibility/portal_clipping.h"
#include "visibility/stabbing.h"

namespace gv {
namespace {

// A search uses the results of the searches ranked this many places or more before it (and the
// flood sets otherwise). Fixed, so the output does not depend on the number of threads; large
// enough that a thread seldom waits for a long search of another.
constexpr size_t kResultLag = 16;

// A portal crossed in one direction: 2i is portal i from back to front (its winding), 2i+1
// the way back (reversed winding), so that the winding is always counter-clockwise seen from the
// cell entered (the stabber's convention).
struct DirectedPortal {
  Winding winding;
  int from = 0, to = 0;
  Vec3 normal;                          // unit, direction of travel (zero if degenerate)
  double minOffset = 0, maxOffset = 0;  // the slab of normal·x its vertices span
};

// What a target check (Searcher::mayEnter) reads of one cell: a ball holding all its portals
// (rejecting them at once), then each portal's ball and points, stored cell by cell in one
// array each. A check visits many cells in turn; read through `portals` and each winding's own
// allocation, the load of each portal's record was the hottest instruction of the checks on
// doom-fd2-map10 (a cache miss per portal).
struct TargetCell {
  Ball ball;
  uint32_t exitBegin = 0, exitEnd = 0;  // its exits in Graph::targetExits, outgoing's order
  // With more than kExitTreeAbove exits (merged cells: on doom-fd2-map20 a check that found
  // none of a cell's exits crossable had tested 21 on average), a ball hierarchy over them
  // (items: indices among its exits) in Graph::exitTrees, else kNoTree.
  uint32_t tree = UINT32_MAX;
};
constexpr uint32_t kNoTree = UINT32_MAX;
constexpr size_t kExitTreeAbove = 8;
struct TargetExit {
  Ball ball;
  uint32_t pointBegin = 0, pointCount = 0;  // its points in Graph::targetPoints
};

struct Graph {
  std::vector<DirectedPortal> portals;
  std::vector<std::vector<int>> outgoing;  // per cell, directed portals leaving it
  std::vector<TargetCell> targetCells;     // per cell (see TargetCell)
  std::vector<TargetExit> targetExits;
  std::vector<Vec3> targetPoints;
  std::vector<BallTree> exitTrees;
  Tolerance tol;

  std::span<const Vec3> pointsOf(const TargetExit& e) const {
    return {targetPoints.data() + e.pointBegin, e.pointCount};
  }
};

Graph buildGraph(const PortalGraph& graph) {
  Graph g;
  g.outgoing.resize(graph.cellCount);
  Aabb box;
  for (const GraphPortal& p : graph.portals)
    for (const Vec3& v : p.winding) box.add(v);
  g.tol = Tolerance::forBounds(box);
  g.portals.reserve(2 * graph.portals.size());
  for (const GraphPortal& p : graph.portals) {
    for (int dir = 0; dir < 2; ++dir) {
      DirectedPortal d;
      d.winding = p.winding;
      d.from = static_cast<int>(dir == 0 ? p.back : p.front);
      d.to = static_cast<int>(dir == 0 ? p.front : p.back);
      if (dir == 1) std::reverse(d.winding.begin(), d.winding.end());
      const Vec3 n = newellNormal(d.winding);
      d.normal = length(n) > 0 ? normalize(n) : Vec3{};
      d.minOffset = INFINITY, d.maxOffset = -INFINITY;
      for (const Vec3& v : d.winding) {
        d.minOffset = std::min(d.minOffset, dot(d.normal, v));
        d.maxOffset = std::max(d.maxOffset, dot(d.normal, v));
      }
      g.outgoing[d.from].push_back(static_cast<int>(g.portals.size()));
      g.portals.push_back(std::move(d));
    }
  }
  // A cell's ball: about the mean of its portals' centres, out to the farthest portal ball.
  // (The portals into a cell are the reverses of its exits: the same points.)
  g.targetCells.resize(graph.cellCount);
  g.targetExits.reserve(g.portals.size());
  std::vector<Ball> balls;
  for (size_t c = 0; c < graph.cellCount; ++c) {
    TargetCell& t = g.targetCells[c];
    balls.clear();
    t.exitBegin = static_cast<uint32_t>(g.targetExits.size());
    for (int pi : g.outgoing[c]) {
      const DirectedPortal& d = g.portals[pi];
      balls.push_back(ballAround(d.winding, g.tol));
      g.targetExits.push_back({balls.back(), static_cast<uint32_t>(g.targetPoints.size()),
                               static_cast<uint32_t>(d.winding.size())});
      g.targetPoints.insert(g.targetPoints.end(), d.winding.begin(), d.winding.end());
    }
    t.exitEnd = static_cast<uint32_t>(g.targetExits.size());
    t.ball = ballAroundBalls(balls, g.tol);
    if (balls.size() > kExitTreeAbove) {
      t.tree = static_cast<uint32_t>(g.exitTrees.size());
      g.exitTrees.emplace_back(balls, g.tol);
    }
  }
  return g;
}

// May a stabbing line cross r after q? After crossing q's plane forward the line stays in front
// of it, and before crossing r's plane forward it is behind that: so r needs a point not behind
// q's slab and q a point not in front of r's slab (with the length tolerance as slack). A
// degenerate portal (zero normal) passes everything.
bool mayFollow(const DirectedPortal& q, const DirectedPortal& r, double slack) {
  double rFront = -INFINITY;
  for (const Vec3& v : r.winding) rFront = std::max(rFront, dot(q.normal, v));
  if (rFront < q.minOffset - slack) return false;
  double qBack = INFINITY;
  for (const Vec3& v : q.winding) qBack = std::min(qBack, dot(r.normal, v));
  return qBack <= r.maxOffset + slack;
}

// The cells a line through directed portal q may reach: flood from the cell it enters through
// portals that may follow q (paper §4's adjacency graph, pruned by q's plane as `vis` does).
// visibility/might_see.h floods the same way over a Subdivision for the per-cell fallback of
// computeVisibility, and both stay: they differ in slack (the length tolerance here, the plane
// offset there), in precision (slabs of normal·x from the origin here, distances from a portal
// vertex there) and in never re-entering the source cell here. Any of those changes the sets,
// and the sets reach the output (the search order, and the answer of a search over budget), so
// one flood for both would change `pvs` or `vis` output.
void floodFrom(const Graph& g, int qi, CellSet& out, std::vector<int>& stack) {
  const DirectedPortal& q = g.portals[qi];
  out.clear();
  out.insert(q.to);
  stack.assign(1, q.to);
  const double slack = g.tol.length();
  while (!stack.empty()) {
    const int x = stack.back();
    stack.pop_back();
    for (int ri : g.outgoing[x]) {
      const DirectedPortal& r = g.portals[ri];
      if (r.to == q.from || out.contains(r.to)) continue;
      if (!mayFollow(q, r, slack)) continue;
      out.insert(r.to);
      stack.push_back(r.to);
    }
  }
}

// The results a search of rank k may use: those of the searches ranked below this.
size_t usableBound(size_t k) {
  return k > kResultLag ? k - kResultLag : 0;
}

// The order of the searches (directed portals). `vis`'s order is increasing might-see size, so
// that the small searches' results narrow the big ones'. `groupCells`: a cell's portals are kept
// together (ordered by the largest might-see size among them, then by cell), so that cells are
// settled early, but no portal is put later than the place twice its own size would give it.
std::vector<int> searchOrder(const Graph& g, const std::vector<size_t>& floodSize,
                             bool groupCells) {
  const size_t np = g.portals.size();
  std::vector<int> order(np);
  for (size_t i = 0; i < np; ++i) order[i] = static_cast<int>(i);
  if (!groupCells) {
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return floodSize[a] < floodSize[b]; });
    return order;
  }
  std::vector<size_t> key(np);
  for (const std::vector<int>& out : g.outgoing) {
    size_t largest = 0;
    for (int pi : out) largest = std::max(largest, floodSize[pi]);
    for (int pi : out) key[pi] = std::min(largest, 2 * floodSize[pi]);
  }
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    if (key[a] != key[b]) return key[a] < key[b];
    if (g.portals[a].from != g.portals[b].from) return g.portals[a].from < g.portals[b].from;
    return floodSize[a] < floodSize[b];
  });
  return order;
}

// The inputs every search reads: the flood, and the finished searches' results. A search of
// rank k (its place in the search order) reads the result of a directed portal of rank below
// k - kResultLag, and the flood of any other: which results it may use depends only on k, never on
// thread timing, so the output is the same for any number of threads.
struct SearchInputs {
  const Graph& g;
  const std::vector<CellSet>& flood;
  // Per directed portal once its search is done: a superset of the cells sightlines through it
  // reach (what it found, and the settled cells it might have reached).
  const std::vector<CellSet>& portalVis;
  const std::vector<size_t>& rank;  // per directed portal, its place in the search order
  // Per cell, the rank from which on all its portals' results are usable (a search whose
  // results bound is at least this settles the cell); empty with CellPvsOptions::bothSides.
  const std::vector<size_t>& cellDoneAt;
};

// One thread's search state.
struct Searcher {
  Searcher(const SearchInputs& in, size_t cells, const StabbingOptions& options,
           uint64_t sequenceBudget, double targetCheckRatio, bool targetCheckWholeBranch)
      : g(in.g),
        inputs(in),
        maxSequences(sequenceBudget),
        targetRatio(targetCheckRatio),
        wholeBranch(targetCheckWholeBranch),
        stabber(in.g.tol, options),
        visible(cells),
        found(cells),
        settled(cells),
        enterableIn(cells, 0),
        onPath(cells, 0),
        lastCrossed(cells, 0) {}

  const Graph& g;
  const SearchInputs& inputs;
  const uint64_t maxSequences;    // per search; 0: no limit (CellPvsOptions::maxSequencesPerSearch)
  uint64_t budgetEnd = 0;         // the search stops once `sequences` passes this
  bool overBudget = false;        // the current search ran out of budget (see visitExit)
  const double targetRatio;       // CellPvsOptions::targetCheckRatio
  const bool wholeBranch;         // CellPvsOptions::targetCheckWholeBranch
  uint64_t searchStart = 0;       // `sequences` when the current search began
  uint64_t targetTests = 0;       // tests made by target checks, all searches of this thread
  uint64_t targetTestsStart = 0;  // `targetTests` when the current search began
  uint64_t targetCellsDropped = 0;
  uint64_t overBudgetTests = 0;  // mayEnter's tests answering branches over the budget
  uint64_t searchesOverBudget = 0;
  // Results of directed portals ranked below this are used (see SearchInputs).
  size_t usableRanks = 0;
  PortalSequenceStabber stabber;
  // The cells found (the search's result), the cells settled before it began (their own
  // searches are all done and decided the pair), and their union: what the pruning counts as
  // seen. A settled cell is still passed through, only nothing is looked for on its account.
  CellSet visible, found, settled;
  // Per depth, the number of the current visit of recurse there; per cell, the visit on which
  // a target check last found it enterable (branchMayFindUnseen).
  std::vector<uint64_t> visitAt;
  std::vector<uint64_t> enterableIn;
  uint64_t visits = 0;
  std::vector<char> onPath;
  // Per cell, the index (in its exits) of the portal its last target check found crossable.
  std::vector<uint32_t> lastCrossed;
  std::vector<CellSet> frames;               // might-see set per depth
  std::vector<int> path;                     // the cells before the current one, source first
  std::vector<std::vector<int>> laterExits;  // per depth, the portals recurse visits second
  uint64_t sequences = 0;
  std::vector<uint64_t> successes, failures;  // stabbing tests by sequence length (Fig. 13)

  // The cells a line through directed portal `pi` may reach: the flood, or (once that portal's
  // own search is finished and usable) its search result, which is smaller and still conservative
  // (the rest of any sequence through it is a sequence starting with it).
  const CellSet& might(int pi) const {
    return inputs.rank[pi] < usableRanks ? inputs.portalVis[pi] : inputs.flood[pi];
  }

  void count(size_t length, bool success) {
    std::vector<uint64_t>& v = success ? successes : failures;
    if (v.size() <= length) v.resize(length + 1, 0);
    ++v[length];
  }

  CellSet& frame(size_t depth) {
    while (frames.size() <= depth) frames.emplace_back(visible.capacity());
    return frames[depth];
  }

  // The cells reached by stabbable portal sequences starting with directed portal `pi`, using
  // the results of the searches ranked below `usable`.
  void searchFrom(int pi, size_t usable) {
    usableRanks = usable;
    const DirectedPortal& p = g.portals[pi];
    settled.clear();
    for (size_t c = 0; c < inputs.cellDoneAt.size(); ++c)
      if (inputs.cellDoneAt[c] <= usable) settled.insert(c);
    found.clear();
    found.insert(p.to);
    visible = settled;
    visible.insert(p.to);
    stabber.clear();
    stabber.push(p.winding);  // one portal is always stabbed (never Blocked)
    ++sequences;
    count(1, true);
    onPath[p.from] = onPath[p.to] = 1;
    // Sightlines are symmetric: a line from cell A = p.from into a cell Y, reversed, leaves Y
    // through one of Y's portals and reaches A. So a cell none of whose portals' might-see sets
    // holds A is not entered (nor anything behind it).
    CellSet& start = frame(1);
    start = might(pi);
    const size_t from = static_cast<size_t>(p.from);
    start.forEach([&](size_t y) {
      for (int qi : g.outgoing[y])
        if (might(qi).contains(from)) return;
      start.erase(y);
    });
    path.assign(1, p.from);
    overBudget = false;
    searchStart = sequences;
    targetTestsStart = targetTests;
    // Per search, so that what a search tests never depends on the searches before it on this
    // thread (the throttle counts tests): the output is the same on any number of threads.
    std::fill(lastCrossed.begin(), lastCrossed.end(), 0);
    budgetEnd = maxSequences ? sequences + maxSequences : UINT64_MAX;
    recurse(p.to, 1);
    onPath[p.from] = onPath[p.to] = 0;
    searchesOverBudget += overBudget;
  }

  bool reachesAll(const CellSet& set) const {
    for (int c : path)
      if (!set.contains(static_cast<size_t>(c))) return false;
    return true;
  }

  // The portals of `cell` into cells not yet visible first, then the others: the cells a search
  // reaches do not depend on this order (each push's answer depends on its path alone, and a
  // branch is pruned only when everything it might reach is already visible), but reaching new
  // cells early lets more later branches be pruned.
  void recurse(int cell, size_t depth) {
    if (visitAt.size() <= depth) visitAt.resize(depth + 1);
    visitAt[depth] = ++visits;
    // (`laterExits` grows in the calls below: it is indexed anew each time.)
    while (laterExits.size() <= depth) laterExits.emplace_back();
    laterExits[depth].clear();
    for (int ri : g.outgoing[cell]) {
      if (!visible.contains(g.portals[ri].to)) {
        if (!visitExit(cell, depth, ri)) return;
      } else {
        laterExits[depth].push_back(ri);
      }
    }
    for (size_t k = 0; k < laterExits[depth].size(); ++k)
      if (!visitExit(cell, depth, laterExits[depth][k])) return;
  }

  // Target checks (CellPvsOptions::targetCheckRatio), made before the branch through the exit
  // into `to` of the cell at `depth` is explored: its unseen cells (`frames[depth + 1]`) are
  // tested (mayEnter), and those no line of the current sequence may enter are dropped from
  // this depth's frame too, so that the cell's other branches skip them. False when none is
  // left: the branch is not explored. Unless `wholeBranch`, testing stops at the first cell a
  // line may enter. A cell found enterable is not tested again on this visit of the cell.
  // (Before, every unseen cell some exit might reach was tested on entering a cell: on
  // doom-fd2-map20, 170 M tests for 15 M cells dropped.) Within the allowance (tests made
  // against sequences pushed), which depends only on the search's own counts: deterministic.
  bool branchMayFindUnseen(size_t depth, int to) {
    if (double(sequences - searchStart) * targetRatio < double(targetTests - targetTestsStart))
      return true;
    CellSet& branch = frames[depth + 1];
    const uint64_t visit = visitAt[depth];
    auto enterable = [&](size_t y) {
      if (onPath[y] || enterableIn[y] == visit) return true;
      if (mayEnter(y, targetTests)) {
        enterableIn[y] = visit;
        return true;
      }
      frames[depth].erase(y);
      branch.erase(y);
      ++targetCellsDropped;
      return false;
    };
    if (wholeBranch) {
      bool any = false;
      branch.anyNotIn(visible, [&](size_t y) {
        any |= enterable(y);
        return false;
      });
      return any;
    }
    // The cell behind the exit first: when a line may enter it, the branch is explored.
    const size_t next = static_cast<size_t>(to);
    if (branch.contains(next) && !visible.contains(next) && enterable(next)) return true;
    return branch.anyNotIn(visible, enterable);
  }

  // May a line of the current portal sequence (the stabber's) enter cell y? False only when
  // every portal into y lies wholly behind one of the sequence's planes (its first portal's, its
  // last portal's, or a separating plane of the two): no line through the sequence reaches y.
  // `tests` counts the plane tests' calls.
  bool mayEnter(size_t y, uint64_t& tests) {
    // All of y's portals at once when one plane has the ball of them behind it; the planes
    // with that ball wholly in front are then skipped for its portals, which lie inside it.
    ++tests;
    const LaterPlanes planes{stabber.laterPlanes()};
    uint64_t inBall = planes.all();
    const TargetCell& cell = g.targetCells[y];
    if (!planes.keep(cell.ball.center, cell.ball.radius, {}, inBall)) return false;
    // The portals into y are the reverses of its exits: the same points. The one that let
    // y through last time first: it usually does again, deeper on the same path.
    const TargetExit* exits = g.targetExits.data() + cell.exitBegin;
    const size_t n = cell.exitEnd - cell.exitBegin, first = lastCrossed[y] < n ? lastCrossed[y] : 0;
    auto crossable = [&](size_t i, uint64_t mask) {
      ++tests;
      const TargetExit& q = exits[i];
      if (!planes.keep(q.ball.center, q.ball.radius, g.pointsOf(q), mask)) return false;
      lastCrossed[y] = static_cast<uint32_t>(i);
      return true;
    };
    if (cell.tree == kNoTree) {
      for (size_t k = 0, i = first; k < n; ++k, i = i + 1 == n ? 0 : i + 1)
        if (crossable(i, inBall)) return true;
      return false;
    }
    // Many exits: the rest down their ball tree, whose groups are rejected a ball at a time.
    if (crossable(first, inBall)) return true;
    return g.exitTrees[cell.tree].findKept(
        inBall,
        [&](const Ball& b, BallTree::ItemRange, uint64_t& mask) {
          ++tests;
          return planes.keep(b.center, b.radius, {}, mask);
        },
        [&](uint32_t i, uint64_t mask) { return i != first && crossable(i, mask); });
  }

  // The answer for a branch the budget leaves unexplored (the sequence to `cell`, then r into
  // r.to): every cell a line through that sequence and r may reach. The portal r is pushed (one
  // more stabbing test: a blocked r answers nothing), then the branch's might-see set is cut to
  // the cells a line of the longer sequence may enter (mayEnter: its separating planes). Without
  // the push, a branch out of the source's own cell (no separating plane yet) answered with the
  // whole flood of r: on doom-fd2-map10 a budget of 1,000 instead of 5,000 gave 4.6 times the
  // cell pairs. False when the cell's own sequence proved blocked (as visitExit).
  bool answerOverBudget(size_t depth, int ri, bool& stop) {
    const DirectedPortal& r = g.portals[ri];
    CellSet& answer = frames[depth + 1];  // the branch's might-see set, with something unseen
    ++sequences;
    const bool stabbed = stabber.push(r.winding, false) != StabbingResult::Blocked;
    if (!stabbed && stabber.isTopBlocked()) {
      --successes[depth];
      count(depth, false);
      stop = true;
      return false;
    }
    count(depth + 1, stabbed);
    if (!stabbed) return false;
    answer.subtract(visible);
    answer.forEach([&](size_t y) {
      if (onPath[y] || mayEnter(y, overBudgetTests)) return;
      answer.erase(y);
    });
    stabber.pop();
    answer.insert(static_cast<size_t>(r.to));
    return true;
  }

  // One step of recurse: the branch through portal `ri` of `cell`; false when the cell's own
  // sequence proved blocked (nothing more can be pushed on it).
  bool visitExit(int cell, size_t depth, int ri) {
    const DirectedPortal& r = g.portals[ri];
    if (onPath[r.to]) return true;  // a line meets a convex cell in one segment
    frame(depth + 1);               // allocate first: references into `frames` are taken below
    if (!frames[depth].contains(r.to)) return true;
    // The reversed line leaves r.to through r's reverse portal (index ri ^ 1) and passes
    // through every earlier cell of the path.
    if (!reachesAll(might(ri ^ 1))) return true;
    // Nothing this branch might reach is unseen: it cannot change the answer.
    if (!frames[depth + 1].assignIntersectionHasNew(frames[depth], might(ri), visible)) return true;
    if (depth >= 2 && targetRatio > 0 && !branchMayFindUnseen(depth, r.to)) return true;
    if (sequences >= budgetEnd) {
      // Over budget (CellPvsOptions::maxSequencesPerSearch): the branch is answered without
      // exploring it, with every cell a line through it may reach (answerOverBudget) — no
      // stabbable sequence through it reaches any other — and the branches explored before
      // keep their answers.
      overBudget = true;
      bool stop = false;
      if (answerOverBudget(depth, ri, stop)) {
        found.unite(frames[depth + 1]);
        visible.unite(frames[depth + 1]);
      }
      return !stop;
    }
    ++sequences;
    // Entering a cell already seen, the push matters only for what lies behind it: its LP may
    // wait until a deeper portal needs it.
    const bool stabbed = stabber.push(r.winding, visible.contains(r.to)) != StabbingResult::Blocked;
    if (!stabbed && stabber.isTopBlocked()) {
      // This cell's own sequence (length `depth`) was blocked after all: no push on it goes
      // through. Its count moves from success to failure; the sequence r began is not counted.
      --successes[depth];
      count(depth, false);
      return false;
    }
    count(depth + 1, stabbed);
    if (!stabbed) return true;
    if (!visible.contains(r.to)) found.insert(r.to);
    visible.insert(r.to);
    onPath[r.to] = 1;
    path.push_back(cell);
    recurse(r.to, depth + 1);
    path.pop_back();
    onPath[r.to] = 0;
    stabber.pop();
    return true;
  }
};

// Step 1: the might-see flood of every directed portal, and the mean might-see set of a cell
// (the union over its portals, plus itself) for the statistics.
std::vector<CellSet> floodAll(const Graph& g, size_t cells, bool parallel, double& meanMightSee) {
  std::vector<CellSet> flood(g.portals.size(), CellSet(cells));
  auto floodRange = [&](size_t begin, size_t end) {
    std::vector<int> stack;
    for (size_t i = begin; i < end; ++i) floodFrom(g, static_cast<int>(i), flood[i], stack);
  };
  if (parallel) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, g.portals.size(), 16),
                      [&](const tbb::blocked_range<size_t>& r) { floodRange(r.begin(), r.end()); });
  } else {
    floodRange(0, g.portals.size());
  }
  double sum = 0;
  CellSet u(cells);
  for (size_t c = 0; c < cells; ++c) {
    u.clear();
    u.insert(c);
    for (int pi : g.outgoing[c]) u.unite(flood[pi]);
    sum += static_cast<double>(u.count());
  }
  meanMightSee = cells ? sum / static_cast<double>(cells) : 0;
  return flood;
}

// The order of the searches and what it settles (SearchInputs).
struct SearchPlan {
  std::vector<int> order;    // directed portals by rank
  std::vector<size_t> rank;  // per directed portal, its place in `order`
  // A cell is settled for the searches that may use all its portals' results (cellDoneAt: the
  // rank from which on; empty with bothSides); lastUsable: the latest results bound among the
  // searches of its portals.
  std::vector<size_t> cellDoneAt, lastUsable;
};

SearchPlan planSearches(const Graph& g, const std::vector<CellSet>& flood, size_t cells,
                        bool bothSides) {
  SearchPlan plan;
  const size_t np = g.portals.size();
  std::vector<size_t> floodSize(np);
  for (size_t i = 0; i < np; ++i) floodSize[i] = flood[i].count();
  plan.order = searchOrder(g, floodSize, !bothSides);
  plan.rank.resize(np);
  for (size_t k = 0; k < np; ++k) plan.rank[plan.order[k]] = k;
  plan.lastUsable.assign(cells, 0);
  if (!bothSides) {
    plan.cellDoneAt.assign(cells, SIZE_MAX);  // a cell without portals is never settled
    for (size_t c = 0; c < cells; ++c) {
      for (int pi : g.outgoing[c]) {
        const size_t after = plan.rank[pi] + 1;
        size_t& doneAt = plan.cellDoneAt[c];
        doneAt = doneAt == SIZE_MAX ? after : std::max(doneAt, after);
        plan.lastUsable[c] = std::max(plan.lastUsable[c], usableBound(plan.rank[pi]));
      }
    }
  }
  return plan;
}

// Step 2: every directed portal's search, in rank order, each using the finished results of the
// searches ranked kResultLag or more before it (SearchInputs). Threads take the next rank from a
// shared counter and wait (rarely: only when one search outlasts kResultLag of the others) until
// the results it may use are done; no barrier between groups of searches, so threads idle only
// for such waits. Fills portalVis (and portalFound without bothSides) and the statistics.
void runSearches(const Graph& g, const std::vector<CellSet>& flood, const SearchPlan& plan,
                 size_t cells, const CellPvsOptions& options, std::vector<CellSet>& portalVis,
                 std::vector<CellSet>& portalFound, CellPvsResult& result) {
  const size_t np = g.portals.size();
  const SearchInputs inputs{g, flood, portalVis, plan.rank, plan.cellDoneAt};
  const size_t threads =
      options.parallel ? static_cast<size_t>(std::max(1, tbb::this_task_arena::max_concurrency()))
                       : 1;
  std::vector<Searcher> searchers;
  searchers.reserve(threads);
  for (size_t t = 0; t < threads; ++t)
    searchers.emplace_back(inputs, cells, options.stabbing, options.maxSequencesPerSearch,
                           options.targetCheckRatio, options.targetCheckWholeBranch);
  std::atomic<size_t> next{0}, finished{0};
  std::atomic<bool> stop{false};
  size_t reported = 0;  // the last count given to options.progress (from the calling thread)
  std::unique_ptr<std::atomic<bool>[]> done(new std::atomic<bool>[np]);
  for (size_t k = 0; k < np; ++k) done[k].store(false, std::memory_order_relaxed);
  // One worker: searches ranks in increasing order until none is left. Every rank below the one
  // it waits for has been taken by a running worker, and the lowest unfinished rank never waits,
  // so the waiting always ends.
  auto work = [&](Searcher& s, bool callingThread) {
    size_t ready = 0;  // ranks below this are known done
    for (;;) {
      if (stop.load(std::memory_order_relaxed)) return;
      const size_t k = next.fetch_add(1, std::memory_order_relaxed);
      if (k >= np) return;
      const size_t usable = usableBound(k);
      while (ready < usable) {
        if (done[ready].load(std::memory_order_acquire)) {
          ++ready;
        } else {
          if (stop.load(std::memory_order_relaxed)) return;
          std::this_thread::yield();
        }
      }
      const int pi = plan.order[k];
      s.searchFrom(pi, usable);
      if (options.bothSides) {
        portalVis[pi] = s.found;
      } else {
        portalFound[pi] = s.found;
        // For the later searches' pruning, the settled cells it might have reached count too.
        portalVis[pi].assignIntersection(s.frames[1], s.settled);
        portalVis[pi].unite(s.found);
      }
      done[k].store(true, std::memory_order_release);
      const size_t n = finished.fetch_add(1, std::memory_order_relaxed) + 1;
      if (callingThread && options.progress) options.progress(reported = n, np);
    }
  };
  if (threads == 1) {
    work(searchers[0], true);
  } else {
    tbb::task_group helpers;
    for (size_t t = 1; t < threads; ++t) {
      helpers.run([&, t] {
        try {
          work(searchers[t], false);
        } catch (...) {
          stop.store(true);  // no one waits for the rank this worker left unfinished
          throw;
        }
      });
    }
    try {
      work(searchers[0], true);
    } catch (...) {
      stop.store(true);
      helpers.wait();
      throw;
    }
    helpers.wait();
  }
  if (options.progress && reported < np) options.progress(np, np);
  for (const Searcher& s : searchers) {
    result.stabbing += s.stabber.stats();
    result.sequencesSearched += s.sequences;
    result.searchesOverBudget += s.searchesOverBudget;
    result.targetTests += s.targetTests;
    result.targetCellsDropped += s.targetCellsDropped;
    result.overBudgetTests += s.overBudgetTests;
    for (auto [from, to] : {std::pair{&s.successes, &result.successesByLength},
                            std::pair{&s.failures, &result.failuresByLength}}) {
      if (to->size() < from->size()) to->resize(from->size(), 0);
      for (size_t k = 0; k < from->size(); ++k) (*to)[k] += (*from)[k];
    }
  }
}

// Step 3: symmetrise: keep a pair only if each side's (conservative) search found the other; a
// pair one side settled (b settled in a search of a's: then every search of b's came earlier,
// with a not settled) stands on the other side's answer. Both cannot hold: each needs the other
// cell's last portal searched more than kResultLag places earlier. `seen`: per cell, itself and
// what its portals found.
void symmetrise(const std::vector<CellSet>& seen, const SearchPlan& plan, CellPvsResult& result) {
  const size_t cells = seen.size();
  auto settledIn = [&](size_t a, size_t b) {
    return !plan.cellDoneAt.empty() && plan.cellDoneAt[b] <= plan.lastUsable[a];
  };
  result.visibleCells.assign(cells, {});
  for (size_t a = 0; a < cells; ++a) {
    for (size_t b = 0; b < cells; ++b) {
      bool keep;
      if (settledIn(a, b)) {
        keep = seen[b].contains(a);
        ++result.settledPairs;
      } else if (settledIn(b, a)) {
        keep = seen[a].contains(b);
        ++result.settledPairs;
      } else {
        keep = seen[a].contains(b) && seen[b].contains(a);
      }
      if (keep) {
        result.visibleCells[a].push_back(static_cast<uint32_t>(b));
      } else if (seen[a].contains(b)) {
        ++result.oneSidedPairsDropped;
      }
    }
  }
}

}  // namespace

CellPvsResult computeCellPvs(const PortalGraph& graph, const CellPvsOptions& options) {
  CellPvsResult result;
  result.cellCount = graph.cellCount;
  result.portalCount = graph.portals.size();
  const size_t cells = graph.cellCount;
  const Graph g = buildGraph(graph);

  const auto t0 = Clock::now();
  const std::vector<CellSet> flood = floodAll(g, cells, options.parallel, result.meanCellsMightSee);
  result.floodSeconds = secondsSince(t0);

  const auto t1 = Clock::now();
  const size_t np = g.portals.size();
  const SearchPlan plan = planSearches(g, flood, cells, options.bothSides);
  // What each search found; without settled cells that is portalVis itself (not kept twice:
  // `vis` runs this on cell graphs whose sets take hundreds of MiB).
  std::vector<CellSet> portalVis(np, CellSet(cells));
  std::vector<CellSet> portalFound(options.bothSides ? 0 : np, CellSet(cells));
  runSearches(g, flood, plan, cells, options, portalVis, portalFound, result);
  const std::vector<CellSet>& found = options.bothSides ? portalVis : portalFound;
  // A cell sees itself and what its portals found.
  std::vector<CellSet> seen(cells, CellSet(cells));
  for (size_t c = 0; c < cells; ++c) {
    seen[c].insert(c);
    for (int pi : g.outgoing[c]) seen[c].unite(found[pi]);
  }
  result.searchSeconds = secondsSince(t1);

  symmetrise(seen, plan, result);
  result.portalFlow = std::move(portalVis);
  return result;
}

}  // namespace gv
