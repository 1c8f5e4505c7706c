// Incremental stabbing-line test for portal sequences (paper §4.1): separating-plane clipping,
// then Teller's Plücker-space LP, then an exactly confirmed witness line. See stabbing.h.
#include "visibility/stabbing.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "visibility/separator_search.h"

namespace gv {
namespace {

// LP variables: the two direction components other than pivot_ (x0, x1), the moment (x2..x4),
// and the slack t (x5). The pivot component is fixed by d·normal = 1.
constexpr int kDim = 6;
constexpr int kT = 5;
// Relaxation of the LP's rows (in units of the unit-scaled rows) for a retry of a degenerate LP.
constexpr double kLpTieBreak = 1e-9;
// An edge rising out of its loop's plane by more than this per unit of length gets no LP row
// (appendRows). Rounding lifts an in-plane edge's end by about 1e-16 of the scene's size; only
// edges shorter than a thousand times their rise out of the plane are dropped: the corners a
// hair apart that off-plane input leaves.
constexpr double kMaxEdgeSlope = 1e-3;

// `newell` is the loop's Newell normal (computed once per push by the caller).
bool isDegenerate(std::span<const Vec3> loop, const Vec3& newell, const Tolerance& tol) {
  if (loop.size() < 3) return true;
  // Twice the area below length-tolerance x diameter: a sliver with no inside to cross.
  double diameter2 = 0;
  for (const Vec3& p : loop) diameter2 = std::max(diameter2, lengthSquared(p - loop[0]));
  const double limit = tol.length();
  return lengthSquared(newell) <= limit * limit * diameter2;
}

// The extreme offsets of a loop along n: portals from files are planar only up to their printed
// precision, so a portal's plane is taken as the slab its vertices span, and clips keep the whole
// slab (the crossing point can be anywhere in it).
double minDot(const Vec3& n, std::span<const Vec3> loop) {
  double m = INFINITY;
  for (const Vec3& p : loop) m = std::min(m, dot(n, p));
  return m;
}
double maxDot(const Vec3& n, std::span<const Vec3> loop) {
  double m = -INFINITY;
  for (const Vec3& p : loop) m = std::max(m, dot(n, p));
  return m;
}

Vec3 centroidOf(std::span<const Vec3> loop) {
  Vec3 c{};
  for (const Vec3& p : loop) c += p;
  return c / static_cast<double>(loop.size());
}

// clipToHalfspace (portal_clipping.h) in place, with the same arithmetic (so the same points),
// each vertex's distance computed once, and no copy when nothing is cut. `dist` and `scratch`
// are working memory.
void clipInPlace(Winding& w, const Vec3& unitNormal, double offset, double slack,
                 std::vector<double>& dist, Winding& scratch) {
  const size_t n = w.size();
  if (n == 0) return;
  const double limit = offset - slack;
  dist.resize(n);
  bool allIn = true, allOut = true;
  for (size_t i = 0; i < n; ++i) {
    dist[i] = dot(unitNormal, w[i]) - limit;
    allIn = allIn && dist[i] >= 0;
    allOut = allOut && !(dist[i] >= 0);
  }
  if (allIn) return;
  if (allOut) {
    w.clear();
    return;
  }
  scratch.clear();
  for (size_t i = 0; i < n; ++i) {
    const size_t j = i + 1 == n ? 0 : i + 1;
    const Vec3& p = w[i];
    const double dp = dist[i], dq = dist[j];
    if (dp >= 0) scratch.push_back(p);
    if ((dp >= 0) != (dq >= 0)) {
      const double t = dp / (dp - dq);
      scratch.push_back(p + (w[j] - p) * t);
    }
  }
  w.swap(scratch);
}

}  // namespace

StabbingStats& StabbingStats::operator+=(const StabbingStats& o) {
  tests += o.tests;
  blockedByClipping += o.blockedByClipping;
  blockedByLp += o.blockedByLp;
  stabbed += o.stabbed;
  unresolved += o.unresolved;
  lpNumericalFailures += o.lpNumericalFailures;
  degeneratePortals += o.degeneratePortals;
  lpSolves += o.lpSolves;
  simplexFallbacks += o.simplexFallbacks;
  lpShortcuts += o.lpShortcuts;
  lpDeferred += o.lpDeferred;
  deferredBlocked += o.deferredBlocked;
  return *this;
}

PortalSequenceStabber::PortalSequenceStabber(const Tolerance& tol, StabbingOptions options)
    : tol_(tol), options_(options) {
  levels_.reserve(64);
  rows_.reserve(512);
}

void PortalSequenceStabber::clear() {
  depth_ = 0;
  rows_.clear();
  witness_.reset();
}

void PortalSequenceStabber::pop() {
  if (depth_ == 0) throw std::logic_error("PortalSequenceStabber::pop on an empty sequence");
  --depth_;
  rows_.resize(depth_ == 0 ? 0 : levels_[depth_ - 1].constraintEnd);
}

// One LP row per edge a→b of the loop: side(π, e) >= t, i.e. -(d·m_e + m·d_e) + t <= 0, with
// d_pivot = (1 - sum_{j != pivot} n_j d_j) / n_pivot substituted, scaled to a unit row.
void PortalSequenceStabber::appendRows(std::span<const Vec3> loop, const Vec3& planeNormal) {
  const size_t n = loop.size();
  const int j0 = (pivot_ + 1) % 3, j1 = (pivot_ + 2) % 3;
  const double np = normal_[pivot_];
  for (size_t i = 0; i < n; ++i) {
    const Vec3 a = toLocal(loop[i]), b = toLocal(loop[(i + 1) % n]);
    const Vec3 de = b - a, me = cross(a, b);
    // A (near-)repeated vertex, e.g. two rounded copies of one clip point, is no edge: its
    // direction is rounding noise, and once normalised below it would cut away real lines (a
    // false "blocked", found by `globalvis verify` on the office). Lengths here are in units of
    // the scene size.
    const double length2 = lengthSquared(de);
    if (!(length2 > kRelativeLengthEpsilon * kRelativeLengthEpsilon)) continue;
    // Nor is an edge that leaves the loop's plane steeply: the rows say "crosses a convex
    // polygon" only for edges lying in its plane. Two copies of one corner a hair apart, one of
    // them a hair off the plane (within the importer's planarity tolerance), make such an edge,
    // and its row cuts away lines through the polygon's middle: q3-oacmpdm3's 45° bevel patch
    // 3130 has corners 1e-6 apart, one 7e-7 off its plane, and that row proved a real
    // sightline's sequence blocked (a missed pair). Dropping a row only enlarges the feasible
    // set, so skipping such edges stays conservative, as above; the rows of edges in the plane
    // (every edge of a BSP portal, but for rounding) are kept as they are.
    const double rise = dot(de, planeNormal);
    if (rise * rise > kMaxEdgeSlope * kMaxEdgeSlope * length2) continue;
    LpConstraint r;
    // d·m_e = sum_{j != p} d_j (me_j - n_j me_p / n_p) + me_p / n_p
    r.a[0] = -(me[j0] - normal_[j0] * me[pivot_] / np);
    r.a[1] = -(me[j1] - normal_[j1] * me[pivot_] / np);
    r.a[2] = -de.x;
    r.a[3] = -de.y;
    r.a[4] = -de.z;
    r.a[kT] = 1;
    r.b = me[pivot_] / np;
    // Scale by the edge's own Plücker size so that every row measures distance alike (t is then
    // "how far the line passes inside the edge", comparable across edges).
    const double edgeSize = std::sqrt(length2 + lengthSquared(me));
    double norm = 0;
    for (int j = 0; j < kT; ++j) {
      r.a[j] /= edgeSize;
      norm += r.a[j] * r.a[j];
    }
    r.b /= edgeSize;
    norm = std::sqrt(norm + 1.0);
    for (int j = 0; j < kDim; ++j) r.a[j] /= norm;
    r.b /= norm;
    rows_.push_back(r);
  }
}

namespace {

LpVector lpBoxLo() {
  LpVector lo{};
  for (int j = 0; j < kT; ++j) lo[j] = -kStabbingMaxGrazingSlope;
  // t's lower bound is below any achievable value (|side| <= |π| <= ~5 x the box), so the LP is
  // always feasible and t* measures how far the best line misses.
  lo[kT] = -8 * kStabbingMaxGrazingSlope;
  return lo;
}

LpVector lpBoxHi() {
  LpVector hi{};
  for (int j = 0; j <= kT; ++j) hi[j] = kStabbingMaxGrazingSlope;
  return hi;
}

double sizeOf(const LpVector& x) {
  double size = 1;
  for (int j = 0; j < kT; ++j) size = std::max(size, std::abs(x[j]));
  return size;
}

// Exact: the line crosses the loop forward, side >= 0 with every edge and > 0 with at least one
// (a line in the loop's plane has every side 0 and crosses nothing).
bool crossesForward(const Segment& line, std::span<const Vec3> w) {
  bool crosses = false;
  for (size_t i = 0; i < w.size(); ++i) {
    const int s = sideExact(line, Segment{w[i], w[(i + 1) % w.size()]});
    if (s < 0) return false;
    crosses = crosses || s > 0;
  }
  return crosses;
}

}  // namespace

void PortalSequenceStabber::describe(Level& level, std::span<const Vec3> portal, Vec3& newell,
                                     bool& degenerate) {
  level.original.assign(portal.begin(), portal.end());
  newell = newellNormal(portal);
  degenerate = isDegenerate(portal, newell, tol_);
  if (degenerate) ++stats_.degeneratePortals;
  level.hasPlane = !degenerate;
  if (!degenerate) {
    level.planeNormal = normalize(newell);
    level.planeMin = minDot(level.planeNormal, portal);
  }
}

StabbingResult PortalSequenceStabber::pushFirst(Level& level, std::span<const Vec3> portal) {
  Vec3 newell;
  bool degenerate = false;
  describe(level, portal, newell, degenerate);
  // The first portal fixes the LP frame.
  origin_ = portal.empty() ? Vec3{} : centroidOf(portal);
  scale_ = tol_.scale;
  invScale_ = 1.0 / scale_;
  firstDegenerate_ = degenerate;
  if (!degenerate) {
    normal_ = level.planeNormal;
    firstMinOffset_ = level.planeMin;
    pivot_ = dominantAxis(normal_);
  } else {
    level.lpValid = false;  // no crossing direction to normalise by: nothing is provable
  }
  level.source = level.clipped;
  rows_.clear();
  if (level.lpValid) appendRows(level.clipped, normal_);
  level.constraintEnd = rows_.size();
  std::optional<Segment> w;
  if (level.lpValid) {
    // The line along the normal through the centre is an LP point (with t lowered to what the
    // rows allow), and usually a witness: no LP solve is needed to start a sequence.
    const int j0 = (pivot_ + 1) % 3, j1 = (pivot_ + 2) % 3;
    level.optimum = LpVector{};
    level.optimum[0] = normal_[j0] / normal_[pivot_];
    level.optimum[1] = normal_[j1] / normal_[pivot_];
    level.optimum[kT] = kStabbingMaxGrazingSlope;
    level.optimal = false;
    lowerLazily(level, 0);
  }
  if (!degenerate && options_.seekWitness) {
    const Segment line{origin_, origin_ + normal_ * scale_};
    if (crossesForward(line, level.original)) w = line;
  }
  return accept(level, w);
}

bool PortalSequenceStabber::clipByEarlierPortals(Level& level, Level& prev) {
  // The line crosses the first portal's plane once, forward: everything later is in front.
  if (!firstDegenerate_) {
    clipInPlace(level.clipped, normal_, firstMinOffset_, tol_.length(), dist_, scratch_);
  }
  // Separating planes of (first, previous) portal; needs two distinct portals before this one.
  if (!level.clipped.empty() && depth_ >= 2) {
    // Found lazily, an edge at a time, and kept for the siblings: a portal clipped away by
    // the first few planes needs no more of them.
    for (size_t k = 0; !level.clipped.empty();) {
      if (k == prev.separators.size()) {
        if (prev.separatorCursor.done()) break;
        appendNextSeparators(prev.source, prev.clipped, prev.separatorCursor, prev.separators);
        continue;
      }
      const ClipPlane& plane = prev.separators[k++];
      clipInPlace(level.clipped, plane.unitNormal, plane.offset, tol_.length(), dist_, scratch_);
    }
  }
  return !level.clipped.empty();
}

bool PortalSequenceStabber::mayCrossLater(std::span<const Vec3> portal, const Vec3& center,
                                          double radius) {
  if (depth_ < 2) return true;
  Level& top = levels_[depth_ - 1];
  const double slack = tol_.length();
  // One plane at a time, no clipping: the portal is rejected when all of it lies behind one
  // plane (the ball first, then its vertices, with the clips' slack). A portal that only
  // several planes together cut away is kept: weaker than clipping it in turn, but the clips
  // cost more than the pruning they add (e3m4: 8 % more sequences searched, 8 % less time).
  auto keep = [&](const Vec3& unitNormal, double offset) {
    return sideOfLater(unitNormal, offset - slack, center, radius, portal) != LaterSide::Behind;
  };
  if (!firstDegenerate_ && !keep(normal_, firstMinOffset_)) return false;
  if (top.hasPlane && !keep(top.planeNormal, top.planeMin)) return false;
  for (size_t k = 0;;) {
    if (k == top.separators.size()) {
      if (top.separatorCursor.done()) return true;
      appendNextSeparators(top.source, top.clipped, top.separatorCursor, top.separators);
      continue;
    }
    const ClipPlane& plane = top.separators[k++];
    if (!keep(plane.unitNormal, plane.offset)) return false;
  }
}

std::span<const ClipPlane> PortalSequenceStabber::laterPlanes() {
  if (depth_ < 2) return {};
  Level& top = levels_[depth_ - 1];
  if (!top.laterReady) {
    while (!top.separatorCursor.done())
      appendNextSeparators(top.source, top.clipped, top.separatorCursor, top.separators);
    // In mayCrossLater's order: the first portal's plane, the last's, the separating planes.
    const double slack = tol_.length();
    top.later.clear();
    if (!firstDegenerate_) top.later.push_back({normal_, firstMinOffset_ - slack});
    if (top.hasPlane) top.later.push_back({top.planeNormal, top.planeMin - slack});
    for (const ClipPlane& p : top.separators) top.later.push_back({p.unitNormal, p.offset - slack});
    top.laterReady = true;
  }
  return top.later;
}

bool PortalSequenceStabber::clipFirstPortal(Level& level, const Level& prev, bool degenerate) {
  // Symmetrically, the line crosses the new portal's plane forward after crossing the first
  // portal: the first portal's useful part is behind that plane.
  if (!degenerate) {
    const Vec3& n = level.planeNormal;  // set by describe() (not degenerate)
    clipInPlace(level.source, -n, -maxDot(n, level.original), tol_.length(), dist_, scratch_);
    if (level.source.empty()) {
      return false;
    }
  }
  // And the separating planes of (new, previous) portal bound the first portal's useful part
  // (the same lemma for the reversed line; `vis` calls this the back clip). A smaller first
  // portal tightens every later clip, then the new portal is clipped once more by it.
  if (options_.backClip && depth_ >= 2) {
    const size_t before = level.source.size();
    if (!clipBySeparatingPlanes(level.clipped, prev.clipped, level.source, tol_)) {
      return false;
    }
    if (level.source != prev.source && level.source.size() + before > 0 &&
        !clipBySeparatingPlanes(level.source, prev.clipped, level.clipped, tol_)) {
      return false;
    }
  }
  return true;
}

StabbingResult PortalSequenceStabber::push(std::span<const Vec3> portal, bool mayDefer) {
  ++stats_.tests;
  witness_.reset();
  if (depth_ > 0 && levels_[depth_ - 1].blocked) return StabbingResult::Blocked;
  // Levels are reused slot by slot (their windings keep their capacity): no allocation per push
  // once the search has been this deep.
  if (levels_.size() <= depth_) levels_.resize(depth_ + 1);
  Level& level = levels_[depth_];
  level.clipped.assign(portal.begin(), portal.end());
  level.lpValid = options_.useLinearProgram;
  level.separators.clear();
  level.separatorCursor = SeparatorCursor{};
  level.laterReady = false;
  level.lpPending = level.blocked = false;
  level.witness.reset();
  level.basis = SimplexBasis{};
  level.optimal = false;
  level.optimum = LpVector{};
  if (depth_ == 0) return pushFirst(level, portal);

  Level& prev = levels_[depth_ - 1];
  level.lpValid = level.lpValid && prev.lpValid;
  if (options_.clipBySeparatingPlanes && !clipByEarlierPortals(level, prev)) {
    ++stats_.blockedByClipping;
    return StabbingResult::Blocked;
  }
  // The portal's own data, needed once it is past the clipping (which half the pushes are not).
  Vec3 newell;
  bool degenerate = false;
  describe(level, portal, newell, degenerate);
  level.source.assign(prev.source.begin(), prev.source.end());
  if (options_.clipBySeparatingPlanes && !clipFirstPortal(level, prev, degenerate)) {
    ++stats_.blockedByClipping;
    return StabbingResult::Blocked;
  }

  // A deferred LP of the previous level is solved now that a portal got through the clipping
  // on top of it (before this level's rows are added); if it is blocked, so is everything after.
  if (prev.lpPending) {
    prev.lpPending = false;
    if (solveLp(depth_ - 1) == StabbingResult::Blocked) {
      prev.blocked = true;
      ++stats_.deferredBlocked;
      return StabbingResult::Blocked;
    }
  }
  const size_t rowsBefore = rows_.size();
  if (level.lpValid) {
    if (!degenerate && level.clipped.size() >= 3) appendRows(level.clipped, level.planeNormal);
    // A shrunk first portal tightens the LP too (the line crosses the first plane inside it).
    if (level.source != prev.source && level.source.size() >= 3) appendRows(level.source, normal_);
  }
  level.constraintEnd = rows_.size();
  level.optimum = prev.optimum;
  level.optimal = prev.optimal;
  level.basis = prev.basis;
  if (options_.seekWitness) {
    if (std::optional<Segment> w = cheapWitness(level)) {
      // Proven stabbed without the LP; keep its point an LP point for later lazy steps.
      if (level.lpValid) lowerLazily(level, rowsBefore);
      return accept(level, w);
    }
  }
  if (level.lpValid) {
    std::optional<StabbingResult> r = tryLpWithoutSolve(depth_);
    if (!r && mayDefer && options_.deferLp && !options_.seekWitness) {
      // Only the subtree can still be pruned: solve when (if ever) a later portal survives its
      // clipping on top of this one.
      level.lpPending = true;
      ++stats_.lpDeferred;
      r = StabbingResult::Unresolved;
    }
    if (!r) r = solveLp(depth_);
    if (*r == StabbingResult::Blocked) {
      rows_.resize(rowsBefore);
      ++stats_.blockedByLp;
      return StabbingResult::Blocked;
    }
  }
  std::optional<Segment> w;
  if (level.lpValid && options_.seekWitness) {
    ++depth_;  // findWitness tests the sequence including the new level
    w = findWitness(level.optimum);
    --depth_;
  }
  return accept(level, w);
}

StabbingResult PortalSequenceStabber::accept(Level& level, std::optional<Segment> witness) {
  level.witness = witness;
  ++depth_;
  if (witness) {
    witness_ = witness;
    ++stats_.stabbed;
    return StabbingResult::Stabbed;
  }
  ++stats_.unresolved;
  return StabbingResult::Unresolved;
}

// The previous witness if it crosses the new portal too, else the line of the direction from the
// first portal's (clipped) centre to the new portal's (clipped) centre through the common part
// of all projections. Both confirmed exactly.
std::optional<Segment> PortalSequenceStabber::cheapWitness(const Level& level) {
  const Level& prev = levels_[depth_ - 1];
  if (prev.witness && crossesForward(*prev.witness, level.original)) return prev.witness;
  const Vec3 d = centroidOf(level.clipped) - centroidOf(level.source);
  if (!(lengthSquared(d) > 0)) return std::nullopt;
  return alongDirection(d, &level);
}

std::optional<Segment> PortalSequenceStabber::alongDirection(const Vec3& d, const Level* extra) {
  loops_.clear();
  for (size_t i = 0; i < depth_; ++i) loops_.emplace_back(levels_[i].original);
  if (extra) loops_.emplace_back(extra->original);
  std::optional<Segment> line = lineAlongDirection(loops_, d, witnessScratch_);
  if (!line) return std::nullopt;
  for (size_t i = 0; i < depth_; ++i)
    if (!crossesForward(*line, levels_[i].original)) return std::nullopt;
  if (extra && !crossesForward(*line, extra->original)) return std::nullopt;
  return line;
}

// Lazy step: the level's point (an LP point for the rows before `firstRow`) with t lowered to
// what the rows from `firstRow` on allow is still an LP point; it stays known-optimal only if t
// did not move.
void PortalSequenceStabber::lowerLazily(Level& level, size_t firstRow) const {
  LpVector& x = level.optimum;
  double t = x[kT];
  for (size_t i = firstRow; i < level.constraintEnd; ++i) {
    double rest = rows_[i].b;
    for (int j = 0; j < kT; ++j) rest -= rows_[i].a[j] * x[j];
    t = std::min(t, rest / rows_[i].a[kT]);  // the t coefficient of every row is positive
  }
  level.optimal = level.optimal && t == x[kT];
  x[kT] = std::max(t, lpBoxLo()[kT]);
}

// The LP point of the line from a to b (world points): its direction scaled to d·normal_ = 1
// (false unless the line crosses the first portal's plane forward and lies in the box), t the
// least value of rows [0, rowEnd); false as soon as a row puts t below the "not blocked"
// threshold (rows from the newest: the new portal's are the likeliest to).
bool PortalSequenceStabber::linePoint(const Vec3& a, const Vec3& b, size_t rowEnd,
                                      LpVector& x) const {
  const Vec3 p = toLocal(a);
  Vec3 d = toLocal(b) - p;
  const double along = dot(d, normal_);
  if (!(along > kRelativeLengthEpsilon * length(d))) return false;
  d = d / along;
  const Vec3 m = cross(p, d);
  const int j0 = (pivot_ + 1) % 3, j1 = (pivot_ + 2) % 3;
  x[0] = d[j0], x[1] = d[j1], x[2] = m.x, x[3] = m.y, x[4] = m.z;
  for (int j = 0; j < kT; ++j)
    if (!(std::abs(x[j]) <= kStabbingMaxGrazingSlope)) return false;
  const double threshold = options_.blockedBelow * sizeOf(x);
  double t = kStabbingMaxGrazingSlope;
  for (size_t i = rowEnd; i-- > 0;) {
    double rest = rows_[i].b;
    for (int j = 0; j < kT; ++j) rest -= rows_[i].a[j] * x[j];
    t = std::min(t, rest / rows_[i].a[kT]);
    if (t < threshold) return false;
  }
  x[kT] = std::max(t, lpBoxLo()[kT]);
  return true;
}

std::optional<StabbingResult> PortalSequenceStabber::tryLpWithoutSolve(size_t index) {
  Level& level = levels_[index];
  const Level& prev = levels_[index - 1];
  const size_t first = prev.constraintEnd;
  // If the previous point with t lowered is above the margin the answer is "not blocked" without
  // solving anything (most pushes).
  {
    const LpVector saved = level.optimum;
    const bool savedOptimal = level.optimal;
    lowerLazily(level, first);
    if (level.optimum[kT] >= options_.blockedBelow * sizeOf(level.optimum))
      return StabbingResult::Unresolved;
    level.optimum = saved;
    level.optimal = savedOptimal;
  }
  // Before solving: the lines through the centres of the (clipped) first and new portals, and of
  // the previous and new portals. Any box point is an LP point once t is the least row value, so
  // one that is above the margin proves "not blocked" as well as the optimum would; a third of
  // the solves on E1M1 end here.
  {
    const Vec3 target = centroidOf(level.clipped);
    for (const Winding* from : {static_cast<const Winding*>(&level.source), &prev.clipped}) {
      if (from->empty()) continue;
      LpVector x;
      if (!linePoint(centroidOf(*from), target, level.constraintEnd, x)) continue;
      if (x[kT] >= options_.blockedBelow * sizeOf(x)) {
        level.optimum = x;
        level.optimal = false;
        ++stats_.lpShortcuts;
        return StabbingResult::Unresolved;
      }
    }
  }
  return std::nullopt;
}

StabbingResult PortalSequenceStabber::solveLp(size_t index) {
  Level& level = levels_[index];
  const size_t first = levels_[index - 1].constraintEnd;
  const LpVector lo = lpBoxLo(), hi = lpBoxHi();
  LpVector c{};
  c[kT] = 1;
  const std::span<const LpConstraint> rows(rows_.data(), level.constraintEnd);
  ++stats_.lpSolves;
  // The dual simplex, warm-started from the deepest basis on this path; its "blocked" is taken
  // only on its re-checked Lagrangian bound, so solver rounding cannot cut a real sightline.
  SimplexResult simplex = maximizeDualSimplex(kDim, rows, c, lo, hi, level.basis);
  // A run that stalled or met a singular basis (degenerate LPs: many rows through one point, as
  // axis-aligned portals give) is tried once more with every row relaxed by a different tiny
  // amount, which breaks the ties. Relaxing only enlarges the feasible set, so that LP's bound
  // is still an upper bound here: its "blocked" is still a proof. (A dual simplex run costs a
  // few microseconds, Seidel's LP about a hundred.)
  if (simplex.status != SimplexResult::Status::Optimal) {
    perturbed_.assign(rows.begin(), rows.end());
    for (size_t i = 0; i < perturbed_.size(); ++i)
      perturbed_[i].b += kLpTieBreak * (1 + std::fmod(0.6180339887 * static_cast<double>(i), 1.0));
    simplex = maximizeDualSimplex(kDim, perturbed_, c, lo, hi, SimplexBasis{});
  }
  if (simplex.status == SimplexResult::Status::Optimal) {
    level.basis = simplex.basis;
    level.optimum = simplex.x;
    level.optimal = true;
    return simplex.certifiedUpperBound < options_.blockedBelow * sizeOf(simplex.x)
               ? StabbingResult::Blocked
               : StabbingResult::Unresolved;
  }
  ++stats_.simplexFallbacks;
  level.basis = SimplexBasis{};
  // Seidel's incremental step needs an optimal start; otherwise solve from scratch.
  std::optional<LpVector> x = level.optimal
                                  ? lp_.extend(kDim, rows, first, level.optimum, c, lo, hi)
                                  : lp_.solve(kDim, rows, c, lo, hi);
  level.optimal = true;
  if (!x) {
    // Cannot happen in exact arithmetic (the LP is feasible by construction): do not trust it.
    ++stats_.lpNumericalFailures;
    level.lpValid = false;
    return StabbingResult::Unresolved;
  }
  level.optimum = *x;
  if ((*x)[kT] < options_.blockedBelow * sizeOf(*x)) return StabbingResult::Blocked;
  return StabbingResult::Unresolved;
}

// Candidates from the LP point x, as Plücker coordinates (d, m): first the line of direction d
// through the common part of the portals' projections; then, since x need not be a line
// (d·m = 0), the nearest line with the same direction; then the line through the centres of the
// (clipped) first and last portals.
std::optional<Segment> PortalSequenceStabber::findWitness(const LpVector& x) {
  const int j0 = (pivot_ + 1) % 3, j1 = (pivot_ + 2) % 3;
  Vec3 d{};
  d[j0] = x[0];
  d[j1] = x[1];
  d[pivot_] = (1.0 - normal_[j0] * x[0] - normal_[j1] * x[1]) / normal_[pivot_];
  Vec3 m{x[2], x[3], x[4]};
  const double dd = lengthSquared(d);
  if (dd > 0) {
    if (std::optional<Segment> line = alongDirection(d, nullptr)) return line;
    m -= d * (dot(d, m) / dd);
    const Vec3 p = cross(d, m) / dd;  // the point of the line nearest the local origin
    const Vec3 u = d / std::sqrt(dd);
    const Segment line{toWorld(p), toWorld(p + u)};
    if (confirms(line)) return line;
  }
  const Level& top = levels_[depth_ - 1];
  const Vec3 a = centroidOf(top.source), b = centroidOf(top.clipped);
  if (depth_ >= 2 && !(a == b)) {
    const Segment line{a, b};
    if (confirms(line)) return line;
  }
  return std::nullopt;
}

// Exact: the line crosses every portal as pushed (not clipped) forward.
bool PortalSequenceStabber::confirms(const Segment& line) const {
  if (line.a == line.b) return false;
  for (size_t i = 0; i < depth_; ++i)
    if (!crossesForward(line, levels_[i].original)) return false;
  return true;
}

StabbingResult testPortalSequence(std::span<const Winding> sequence, const Tolerance& tol,
                                  StabbingOptions options, Segment* witness) {
  PortalSequenceStabber stabber(tol, options);
  StabbingResult result = StabbingResult::Unresolved;
  for (const Winding& portal : sequence) {
    result = stabber.push(portal);
    if (result == StabbingResult::Blocked) return result;
  }
  if (result == StabbingResult::Stabbed && witness) *witness = *stabber.witness();
  return result;
}

}  // namespace gv
