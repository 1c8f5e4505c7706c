// Leaf PVS of a Quake portal file by depth-first search over portal sequences with the stabbing
// test (paper §4, §4.1). See leaf_pvs.h for the method and its guarantees.
#include "quake/leaf_pvs.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <mutex>

#include "geometry/tolerance.h"
#include "util/timing.h"
#include "visibility/cell_set.h"
#include "visibility/portal_clipping.h"

namespace gv {
namespace {

// A portal crossed in one direction: 2i is portal i from clusterA to clusterB (file winding), 2i+1
// the way back (reversed winding), so that the winding is always counter-clockwise seen from the
// cell entered (the stabber's convention).
struct DirectedPortal {
  Winding winding;
  int from = 0, to = 0;
  Vec3 normal;                          // unit, direction of travel (zero if degenerate)
  double minOffset = 0, maxOffset = 0;  // the slab of normal·x its vertices span
};

struct Graph {
  std::vector<DirectedPortal> portals;
  std::vector<std::vector<int>> outgoing;  // per cell, directed portals leaving it
  Tolerance tol;
};

Graph buildGraph(const PrtFile& prt) {
  Graph g;
  g.outgoing.resize(prt.clusterCount);
  Aabb box;
  for (const PrtPortal& p : prt.portals)
    for (const Vec3& v : p.winding) box.add(v);
  g.tol = Tolerance::forBounds(box);
  g.portals.reserve(2 * prt.portals.size());
  for (const PrtPortal& p : prt.portals) {
    for (int dir = 0; dir < 2; ++dir) {
      DirectedPortal d;
      d.winding = p.winding;
      d.from = dir == 0 ? p.clusterA : p.clusterB;
      d.to = dir == 0 ? p.clusterB : p.clusterA;
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

// One thread's search state.
struct Searcher {
  Searcher(const Graph& graph, const std::vector<const CellSet*>& mightSee,
           const std::vector<CellSet>& reachOf, size_t cells, const StabbingOptions& options)
      : g(graph),
        might(mightSee),
        reach(reachOf),
        stabber(graph.tol, options),
        visible(cells),
        onPath(cells, 0) {}

  const Graph& g;
  // Per directed portal, the cells a line through it may reach: the flood, or (once that portal's
  // own search is finished) its search result, which is smaller and still conservative (the rest
  // of any sequence through it is a sequence starting with it).
  const std::vector<const CellSet*>& might;
  // Per cell, the cells a line leaving it may reach: the union of its portals' `might` sets.
  const std::vector<CellSet>& reach;
  PortalSequenceStabber stabber;
  CellSet visible;
  std::vector<char> onPath;
  std::vector<CellSet> frames;  // might-see set per depth
  std::vector<int> path;        // the cells before the current one, source first
  uint64_t sequences = 0;
  std::vector<uint64_t> successes, failures;  // stabbing tests by sequence length (Fig. 13)

  void count(size_t length, bool success) {
    std::vector<uint64_t>& v = success ? successes : failures;
    if (v.size() <= length) v.resize(length + 1, 0);
    ++v[length];
  }

  CellSet& frame(size_t depth) {
    while (frames.size() <= depth) frames.emplace_back(visible.capacity());
    return frames[depth];
  }

  // The cells reached by stabbable portal sequences starting with directed portal `pi`.
  void searchFrom(int pi) {
    const DirectedPortal& p = g.portals[pi];
    visible.clear();
    visible.insert(p.to);
    stabber.clear();
    stabber.push(p.winding);  // one portal is always stabbed (never Blocked)
    ++sequences;
    count(1, true);
    onPath[p.from] = onPath[p.to] = 1;
    // Sightlines are symmetric: a line from cell A = p.from into a cell Y, reversed, leaves Y and
    // reaches A. So a cell whose `reach` excludes A is not entered (nor anything behind it).
    CellSet& start = frame(1);
    start = *might[pi];
    for (size_t y = 0; y < reach.size(); ++y)
      if (start.contains(y) && !reach[y].contains(static_cast<size_t>(p.from))) start.erase(y);
    path.assign(1, p.from);
    recurse(p.to, 1);
    onPath[p.from] = onPath[p.to] = 0;
  }

  bool reachesAll(const CellSet& set) const {
    for (int c : path)
      if (!set.contains(static_cast<size_t>(c))) return false;
    return true;
  }

  void recurse(int cell, size_t depth) {
    for (int ri : g.outgoing[cell]) {
      const DirectedPortal& r = g.portals[ri];
      if (onPath[r.to]) continue;  // a line meets a convex cell in one segment
      frame(depth + 1);            // allocate first: references into `frames` are taken below
      if (!frames[depth].contains(r.to)) continue;
      // The reversed line leaves r.to through r's reverse portal (index ri ^ 1) and passes
      // through every earlier cell of the path.
      if (!reachesAll(*might[ri ^ 1])) continue;
      // Nothing this branch might reach is unseen: it cannot change the answer.
      if (!frames[depth + 1].assignIntersectionHasNew(frames[depth], *might[ri], visible)) continue;
      ++sequences;
      // Entering a cell already seen, the push matters only for what lies behind it: its LP may
      // wait until a deeper portal needs it.
      const bool stabbed =
          stabber.push(r.winding, visible.contains(r.to)) != StabbingResult::Blocked;
      if (!stabbed && stabber.isTopBlocked()) {
        // This cell's own sequence (length `depth`) was blocked after all: no push on it goes
        // through. Its count moves from success to failure; the sequence r began is not counted.
        --successes[depth];
        count(depth, false);
        return;
      }
      count(depth + 1, stabbed);
      if (!stabbed) continue;
      visible.insert(r.to);
      onPath[r.to] = 1;
      path.push_back(cell);
      recurse(r.to, depth + 1);
      path.pop_back();
      onPath[r.to] = 0;
      stabber.pop();
    }
  }
};

}  // namespace

LeafPvsResult computeLeafPvs(const PrtFile& prt, const LeafPvsOptions& options) {
  LeafPvsResult result;
  result.leafCount = prt.leafCount;
  result.clusterCount = prt.clusterCount;
  result.portalCount = prt.portals.size();
  const size_t cells = prt.clusterCount;
  const Graph g = buildGraph(prt);

  // 1. Might-see flood per directed portal.
  const auto t0 = Clock::now();
  std::vector<CellSet> flood(g.portals.size(), CellSet(cells));
  auto floodRange = [&](size_t begin, size_t end) {
    std::vector<int> stack;
    for (size_t i = begin; i < end; ++i) floodFrom(g, static_cast<int>(i), flood[i], stack);
  };
  if (options.parallel) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, g.portals.size(), 16),
                      [&](const tbb::blocked_range<size_t>& r) { floodRange(r.begin(), r.end()); });
  } else {
    floodRange(0, g.portals.size());
  }
  {
    // Might-see per cell: the union over its portals (plus itself), for the statistics.
    double sum = 0;
    CellSet u(cells);
    for (size_t c = 0; c < cells; ++c) {
      u.clear();
      u.insert(c);
      for (int pi : g.outgoing[c]) u.unite(flood[pi]);
      sum += static_cast<double>(u.count());
    }
    result.meanClustersMightSee = cells ? sum / static_cast<double>(cells) : 0;
  }
  result.floodSeconds = secondsSince(t0);

  // 2. Depth-first search from every directed portal, in waves of increasing might-see size
  //    (`vis`'s order): a search uses the finished results of earlier waves as its might-see
  //    sets. Which results a search may use depends only on the wave, never on thread timing,
  //    so the output is the same for any number of threads.
  const auto t1 = Clock::now();
  const size_t np = g.portals.size();
  std::vector<int> order(np);
  std::vector<size_t> floodSize(np);
  for (size_t i = 0; i < np; ++i) order[i] = static_cast<int>(i), floodSize[i] = flood[i].count();
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return floodSize[a] < floodSize[b]; });
  std::vector<CellSet> portalVis(np, CellSet(cells));
  std::vector<const CellSet*> might(np);
  for (size_t i = 0; i < np; ++i) might[i] = &flood[i];
  std::vector<CellSet> reach(cells, CellSet(cells));
  auto updateReach = [&](size_t c) {
    reach[c].clear();
    reach[c].insert(c);
    for (int pi : g.outgoing[c]) reach[c].unite(*might[pi]);
  };
  for (size_t c = 0; c < cells; ++c) updateReach(c);
  tbb::enumerable_thread_specific<Searcher> searchers(
      [&] { return Searcher(g, might, reach, cells, options.stabbing); });
  const size_t wave = 8;
  for (size_t w0 = 0; w0 < np; w0 += wave) {
    const size_t w1 = std::min(np, w0 + wave);
    auto searchRange = [&](size_t begin, size_t end) {
      Searcher& s = searchers.local();
      for (size_t k = begin; k < end; ++k) {
        const int pi = order[k];
        s.searchFrom(pi);
        portalVis[pi] = s.visible;
      }
    };
    if (options.parallel) {
      tbb::parallel_for(
          tbb::blocked_range<size_t>(w0, w1, 1),
          [&](const tbb::blocked_range<size_t>& r) { searchRange(r.begin(), r.end()); });
    } else {
      searchRange(w0, w1);
    }
    for (size_t k = w0; k < w1; ++k) might[order[k]] = &portalVis[order[k]];
    for (size_t k = w0; k < w1; ++k) updateReach(static_cast<size_t>(g.portals[order[k]].from));
    if (options.progress) options.progress(w1, np);
  }
  for (const Searcher& s : searchers) {
    result.stabbing += s.stabber.stats();
    result.sequencesSearched += s.sequences;
    for (auto [from, to] : {std::pair{&s.successes, &result.successesByLength},
                            std::pair{&s.failures, &result.failuresByLength}}) {
      if (to->size() < from->size()) to->resize(from->size(), 0);
      for (size_t k = 0; k < from->size(); ++k) (*to)[k] += (*from)[k];
    }
  }
  // A cell sees itself and what its portals see.
  std::vector<CellSet> seen(cells, CellSet(cells));
  for (size_t c = 0; c < cells; ++c) {
    seen[c].insert(c);
    for (int pi : g.outgoing[c]) seen[c].unite(portalVis[pi]);
  }
  result.searchSeconds = secondsSince(t1);

  // 3. Symmetrise: keep a pair only if each side's (conservative) search found the other.
  std::vector<std::vector<int>> visibleCells(cells);
  for (size_t a = 0; a < cells; ++a) {
    for (size_t b = 0; b < cells; ++b) {
      if (!seen[a].contains(b)) continue;
      if (seen[b].contains(a)) {
        visibleCells[a].push_back(static_cast<int>(b));
      } else {
        ++result.oneSidedPairsDropped;
      }
    }
  }

  // 4. Expand clusters to leafs.
  std::vector<std::vector<uint32_t>> clusterRow(cells);
  for (size_t c = 0; c < cells; ++c) {
    for (int d : visibleCells[c])
      for (int leaf : prt.clusterLeafs[d]) clusterRow[c].push_back(static_cast<uint32_t>(leaf));
    std::sort(clusterRow[c].begin(), clusterRow[c].end());
  }
  result.visibleLeafs.resize(prt.leafCount);
  double total = 0;
  for (size_t l = 0; l < prt.leafCount; ++l) {
    result.visibleLeafs[l] = clusterRow[prt.leafCluster[l]];
    total += static_cast<double>(result.visibleLeafs[l].size());
  }
  result.meanLeafsVisible = prt.leafCount ? total / static_cast<double>(prt.leafCount) : 0;
  result.portalFlow = std::move(portalVis);
  return result;
}

}  // namespace gv
