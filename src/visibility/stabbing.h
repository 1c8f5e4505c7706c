// Stabbing lines through portal sequences (paper §4.1): does an oriented line cross every portal
// of a sequence, in order? The primitive operation of visibility propagation, incremental so that
// a depth-first search over portal sequences pushes and pops one portal at a time.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "geometry/plucker.h"
#include "geometry/tolerance.h"
#include "geometry/vec3.h"
#include "visibility/dual_simplex.h"
#include "visibility/linear_program.h"
#include "visibility/portal_clipping.h"
#include "visibility/separator_search.h"
#include "visibility/witness_line.h"

namespace gv {

/// Outcome of a stabbing test.
enum class StabbingResult {
  /// Proven: no stabbing line exists (the sequence can be pruned). Never answered when one exists.
  Blocked,
  /// A stabbing line was found and confirmed with exact orientation tests (see `witness()`).
  Stabbed,
  /// Neither proven; callers must treat it as visible (conservative).
  Unresolved,
};

/// True unless the sequence is proven blocked: what visibility propagation continues on.
inline bool mayBeVisible(StabbingResult r) {
  return r != StabbingResult::Blocked;
}

/// What the stabber did, summed over all pushes.
struct StabbingStats {
  uint64_t tests = 0;                ///< pushes answered
  uint64_t blockedByClipping = 0;    ///< target clipped away by separating planes
  uint64_t blockedByLp = 0;          ///< Plücker LP infeasible beyond the margin
  uint64_t stabbed = 0;              ///< confirmed by an exact witness line
  uint64_t unresolved = 0;           ///< LP feasible, no witness: answered "maybe visible"
  uint64_t lpNumericalFailures = 0;  ///< solver broke down (answered Unresolved)
  uint64_t degeneratePortals = 0;    ///< portals of ~zero area (their edges are not used)
  uint64_t lpSolves = 0;             ///< pushes that ran the LP solver (the costly step)
  uint64_t simplexFallbacks = 0;     ///< of which the dual simplex failed and Seidel's LP ran
  uint64_t lpShortcuts = 0;          ///< pushes a line through portal centres kept without a solve
  uint64_t lpDeferred = 0;           ///< LP solves put off (StabbingOptions::deferLp)
  uint64_t deferredBlocked = 0;      ///< of which, once solved, proved the sequence blocked

  StabbingStats& operator+=(const StabbingStats& o);
};

/// Options; the defaults are what propagation should use.
struct StabbingOptions {
  /// Shrink each new portal by the separating planes of the first and the previous portal (and
  /// the first by the new one's plane) before the LP: conservative, cheap, and prunes most of a
  /// search. Off: the LP alone decides (used by tests to check each part separately).
  bool clipBySeparatingPlanes = true;
  /// Run the Plücker LP. Off: only clipping decides (everything else is Unresolved).
  bool useLinearProgram = true;
  /// Look for an exact witness line when the LP is feasible (only changes Stabbed vs Unresolved;
  /// never the pruning). Costs one exact side test per portal edge.
  bool seekWitness = true;
  /// Also clip the first portal by the separating planes of (new, previous) portal (`vis`'s back
  /// clip). Prunes a few more sequences before the LP, at the price of finding those planes anew
  /// on every push.
  bool backClip = false;
  /// Let push(portal, mayDefer = true) put off an LP solve that only prunes: the push answers
  /// Unresolved, and the LP is solved when a later portal gets through the clipping on top of
  /// it; if it then proves blocked, that push and every further push on the level answer Blocked
  /// (see isTopBlocked()). A search then reaches the same cells with fewer solves (and a few more
  /// pushes: the clipping of portals behind a level whose LP would have pruned it). For searches
  /// that need no answer for the level itself (the leaf PVS, when its cell is already visible).
  /// Ignored when seekWitness is set.
  bool deferLp = false;
  /// The LP answers Blocked when even the best line's worst edge clearance t* (the LP's objective,
  /// in scene-scaled units) is below this times the size of its coordinates. The default, a small
  /// negative margin, never drops a line that touches the portals' edges (closed portals, the
  /// conservative reading for rounding). A small positive value reads the portals as open: lines
  /// that only graze an edge (clearance below it, a measure-tiny set no ray sampling proves)
  /// are not sightlines. The clipping is unaffected (it keeps touching lines either way).
  double blockedBelow = -kStabbingLpMargin;
};

/// An incremental stabbing-line test for a growing sequence of convex portals.
///
/// Conventions: a portal is a convex vertex loop, counter-clockwise seen from the side sightlines
/// go to (its Newell normal is the direction of travel: the cell it leads into). Consecutive
/// portals lead into and out of the same convex cell; then a line that crosses every portal in
/// its direction of travel crosses them in sequence order, and is a sightline through the cells.
/// A stabbing line is such a line through the closed portals (touching edges counts).
///
/// Method (Teller): with Plücker coordinates π of the line, it crosses a convex portal in its
/// direction of travel iff side(π, e) >= 0 for each of the portal's edges e (oriented
/// counter-clockwise). Those are linear in π, so a sequence has a stabbing line only if the LP
///   maximise t  s.t.  side(π, e)/|e| >= t for all edges,  d·n_first = 1,  |π| in a box
/// has t* >= 0. `Blocked` is answered only when t* < -kStabbingLpMargin·|π*|: every line within
/// the box misses some edge by more than rounding could explain. A feasible LP point need not be a
/// line (the Plücker quadric d·m = 0); candidate lines are checked with exact side tests
/// (sideExact = orient3d): the line of the LP optimum's direction through the common part of the
/// portals' projections along it (`witness_line.h`), the optimum projected to the nearest line, and
/// a line through the portals' centres; failing all the answer is `Unresolved` (counted).
///
/// Cheap first: the LP is only solved when no witness is at hand. Before it, a push tries the
/// previous level's witness (one exact test per new edge) and a line of the direction from the
/// first portal's centre to the new portal's centre; a confirmed one answers `Stabbed` at once.
///
/// Known limit: lines within ~atan(1/kStabbingMaxGrazingSlope) of the first portal's plane are
/// outside the LP's box (a measure-tiny set of grazing lines); lines lying in a portal's plane do
/// not cross it and are not stabbing lines here.
///
/// Not thread safe; use one per thread. Deterministic: same pushes, same answers.
class PortalSequenceStabber {
 public:
  /// `tol.scale` (the scene's size) sets the clip slack and the LP's coordinate frame.
  explicit PortalSequenceStabber(const Tolerance& tol, StabbingOptions options = {});

  /// Tests the current sequence followed by `portal`. On Blocked the sequence is unchanged; on
  /// Stabbed or Unresolved the portal is appended (undo with pop()).
  StabbingResult push(std::span<const Vec3> portal, bool mayDefer = false);
  /// Whether the last portal pushed turned out blocked after all (its deferred LP was solved by a
  /// later push, which answered Blocked): nothing more can be pushed on it; pop it.
  bool isTopBlocked() const { return depth_ > 0 && levels_[depth_ - 1].blocked; }
  /// Removes the last portal pushed (the sequence must not be empty).
  void pop();
  /// Whether a stabbing line of the current sequence may cross `portal` anywhere after the last
  /// portal (next, or further on through other portals): false only when one plane proves that
  /// none does. Such a line is in front of the first and the last portal's planes there, and on
  /// the pass's side of every separating plane of (first, last) (the lemma of
  /// portal_clipping.h holds for every point of the line beyond the pass), so a portal wholly
  /// behind one of those planes (by more than the clip slack) is not crossed. Each plane is
  /// tried alone, without clipping the portal by the others: a portal only their intersection
  /// excludes is kept (conservative). `vis`'s "target checks": a search may drop
  /// from its might-see set the cells none of whose portals any line can cross. Always true for
  /// sequences of fewer than two portals. Reads and extends the last level's separators only.
  /// `center` and `radius`: a ball holding every vertex of the portal with some room for
  /// rounding (cell_pvs.cpp: 1e-9 of the radius and of the length tolerance): planes it lies
  /// beyond or within decide without the vertices. With `portal` empty only the ball is tested
  /// (false when one plane has all of it behind: then no portal inside it can be crossed).
  bool mayCrossLater(std::span<const Vec3> portal, const Vec3& center, double radius);
  /// Every plane mayCrossLater tests for the current sequence (all its separating planes found
  /// first), each with its offset lowered by the clip slack: a point p is on the kept side when
  /// dot(unitNormal, p) >= offset. Empty for sequences of fewer than two portals (nothing is
  /// rejected). Valid until the next push or pop. For many tests against one sequence:
  /// LaterPlanes::keep below, in a hierarchy of balls.
  std::span<const ClipPlane> laterPlanes();
  /// Empties the sequence (keeps statistics).
  void clear();
  /// Number of portals in the sequence.
  size_t depth() const { return depth_; }

  /// The last confirmed stabbing line (after a Stabbed push), oriented along the travel direction.
  const std::optional<Segment>& witness() const { return witness_; }
  /// The portal at `index` as shrunk by separating-plane clipping (a superset of where stabbing
  /// lines cross it).
  std::span<const Vec3> clippedPortal(size_t index) const { return levels_[index].clipped; }

  const StabbingStats& stats() const { return stats_; }
  void resetStats() { stats_ = {}; }

 private:
  struct Level {
    Winding original;  // as pushed
    Winding clipped;   // after separating-plane clipping
    Winding source;    // the first portal as clipped by this level's plane (for later clips)
    size_t constraintEnd = 0;        // LP rows of levels [0, this]
    LpVector optimum{};              // an LP point with those rows (t = its worst row)
    bool optimal = false;            // whether `optimum` is known to be the LP optimum
    bool lpValid = false;            // false once the LP broke down (then everything is Unresolved)
    std::optional<Segment> witness;  // a confirmed stabbing line of levels [0, this], if known
    SimplexBasis basis;  // the last LP basis on this path: a warm start for deeper levels
    // Separating planes of (source, clipped): they clip every portal pushed after this level.
    std::vector<ClipPlane> separators;
    SeparatorCursor separatorCursor;  // how far `separators` has been found (lazily)
    bool lpPending = false;           // the LP solve was deferred (deferLp)
    std::vector<ClipPlane> later;     // laterPlanes(), once asked for
    bool laterReady = false;
    // The portal's plane as a slab (unit Newell normal, least offset of its vertices); a
    // degenerate portal has none.
    bool hasPlane = false;
    Vec3 planeNormal{};
    double planeMin = 0;
    bool blocked = false;  // the deferred solve proved the sequence blocked
  };

  // Parts of push: the portal's own data (level.original, its Newell normal, degeneracy, its
  // plane), the first portal of a sequence, the clipping of a later portal by the earlier ones
  // (false: none of it is left), and the clipping of the first portal by a later one (false: none
  // left).
  void describe(Level& level, std::span<const Vec3> portal, Vec3& newell, bool& degenerate);
  StabbingResult pushFirst(Level& level, std::span<const Vec3> portal);
  bool clipByEarlierPortals(Level& level, Level& prev);
  bool clipFirstPortal(Level& level, const Level& prev, bool degenerate);
  std::optional<StabbingResult> tryLpWithoutSolve(size_t index);
  StabbingResult solveLp(size_t index);
  bool linePoint(const Vec3& a, const Vec3& b, size_t rowEnd, LpVector& x) const;
  void lowerLazily(Level& level, size_t firstRow) const;
  std::optional<Segment> cheapWitness(const Level& level);
  StabbingResult accept(Level& level, std::optional<Segment> witness);
  void appendRows(std::span<const Vec3> loop, const Vec3& planeNormal);
  std::optional<Segment> findWitness(const LpVector& x);
  bool confirms(const Segment& line) const;
  std::optional<Segment> alongDirection(const Vec3& d, const Level* extra);
  Vec3 toLocal(const Vec3& p) const { return (p - origin_) * invScale_; }
  Vec3 toWorld(const Vec3& p) const { return origin_ + p * scale_; }

  Tolerance tol_;
  StabbingOptions options_;
  std::vector<Level> levels_;  // slots [0, depth_) hold the sequence; later ones are spare storage
  size_t depth_ = 0;
  std::vector<LpConstraint> rows_;
  std::vector<LpConstraint> perturbed_;  // rows_ relaxed for a retry of a degenerate LP
  SeidelLp lp_;
  StabbingStats stats_;
  std::optional<Segment> witness_;
  // Frame of the current sequence, fixed by its first portal: origin at its centre, lengths in
  // units of the scene size, normalisation d·normal_ = 1 solved for coordinate pivot_.
  Vec3 origin_;
  double scale_ = 1, invScale_ = 1;
  Vec3 normal_;
  int pivot_ = 0;
  bool firstDegenerate_ = false;
  double firstMinOffset_ = 0;  // min of normal_·x over the first portal (its slab's back)
  Winding scratch_;
  std::vector<double> dist_;
  WitnessScratch witnessScratch_;
  std::vector<std::span<const Vec3>> loops_;
};

/// Where a ball, and a polygon inside it, lie against a plane whose kept side is
/// dot(unitNormal, p) >= offset: wholly in front of it (the ball), behind it (the ball, or every
/// vertex of the polygon when one is given), or across it. mayCrossLater's test of one plane.
enum class LaterSide { Behind, Across, InFront };
inline LaterSide sideOfLater(const Vec3& unitNormal, double offset, const Vec3& center,
                             double radius, std::span<const Vec3> vertices) {
  const double d = dot(unitNormal, center) - offset;
  if (d >= radius) return LaterSide::InFront;
  if (d < -radius) return LaterSide::Behind;
  if (vertices.empty()) return LaterSide::Across;  // the ball alone: it rejects nothing
  for (const Vec3& v : vertices)
    if (dot(unitNormal, v) - offset >= 0) return LaterSide::Across;
  return LaterSide::Behind;
}

/// The test of mayCrossLater against a set of planes (PortalSequenceStabber::laterPlanes), for a
/// hierarchy of balls: the bits of `mask` name the planes still to test (the first 64; any
/// beyond are always tested). A ball wholly in front of a plane clears its bit, so the balls
/// and polygons inside it skip that plane; nothing is kept that mayCrossLater rejects, nor
/// rejected that it keeps.
struct LaterPlanes {
  std::span<const ClipPlane> planes;

  uint64_t all() const {
    return planes.size() >= 64 ? ~uint64_t{0} : (uint64_t{1} << planes.size()) - 1;
  }
  /// False when one plane has the ball (and, when `vertices` is not empty, every vertex) behind.
  bool keep(const Vec3& center, double radius, std::span<const Vec3> vertices,
            uint64_t& mask) const {
    for (size_t i = 0; i < planes.size(); ++i) {
      if (i < 64 && !(mask >> i & 1)) continue;
      const ClipPlane& h = planes[i];
      const LaterSide side = sideOfLater(h.unitNormal, h.offset, center, radius, vertices);
      if (side == LaterSide::Behind) return false;
      if (side == LaterSide::InFront && i < 64) mask &= ~(uint64_t{1} << i);
    }
    return true;
  }
};

/// One-shot form: the result of pushing every portal of `sequence` (stopping at the first
/// Blocked); `witness`, when given, receives the confirmed line on Stabbed.
StabbingResult testPortalSequence(std::span<const Winding> sequence, const Tolerance& tol,
                                  StabbingOptions options = {}, Segment* witness = nullptr);

}  // namespace gv
