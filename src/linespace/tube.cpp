// Tubes and the four-outcome blocker classification. Paper §6.1, §6.2 (Figs. 10, 11).
//
// Why the outcomes are sound (the paper argues by convexity of conv(Π(S, R)) in linespace; the
// set of real lines through S and R is not that hull, so we argue directly instead):
//
// Bilinearity. For a fixed line e = (e.a → e.b), f(s, r) = side(line(s → r), e) =
// orient3d(s, r, e.a, e.b) is the 4x4 determinant of the homogeneous points (s,1), (r,1),
// (e.a,1), (e.b,1), linear in each row. A point s of S is a convex combination Σ λ_i S_i of S's
// vertices, so (s,1) = Σ λ_i (S_i,1); likewise r = Σ μ_j R_j. Hence
//   f(s, r) = Σ_i Σ_j λ_i μ_j f(S_i, R_j),
// a convex combination of the values on the extremal lines (vertex pairs). If every extremal line
// has f >= 0 (resp. < 0), so does every line from S to R. No convexity of line sets is needed.
//
// Line meets polygon. A line crossing B's plane meets the closed convex polygon B iff its sides
// with all of B's counter-clockwise edges have one sign (zeros allowed): positive when the line
// travels along B's normal, negative against it (the sign is that of the crossing point's 2D
// side of the edge, times the direction of travel).
//
// Between-ness (plane tests first). Lines are not segments: a line through S, B and R in the
// wrong order (B behind R, say) blocks nothing. So:
//  - B entirely behind (or on) S's plane, or behind R's: a segment from S's front to R's front
//    lies in S's open front halfspace (R's) except for its end point: it cannot meet B. Disjoint.
//  - S and R entirely on one closed side of B's plane: no segment crosses the plane. Disjoint.
//  - S on one side and R on the other ("between", each with a vertex strictly off the plane):
//    every segment from the interior of S to the interior of R crosses B's plane strictly
//    between its end points, all in the same direction σ (−1 when S is in front of B). Only then
//    are the line tests conclusive for segments:
//      all extremal lines σ-inside every edge  ⇒ (bilinearity) every line from S to R meets B,
//        and the crossing is on the segment ⇒ Occludes;
//      all extremal lines strictly outside one edge ⇒ every line misses B ⇒ Disjoint;
//      some extremal line inside all edges, some outside one ⇒ Impinges (kept);
//      none inside all, none outside one edge for all ⇒ Punt (kept).
//  - otherwise B's plane cuts S or R ("straddling"): some segments do not cross it at all, so B
//    never occludes completely. A segment meeting B runs from S ∩ H to R ∩ H' for the two
//    closed halfspaces H, H' of B's plane, H ≠ H'. So S and R are clipped into those two
//    "between" sub-problems (at most two; a part thinner than the tolerance is dropped, as the
//    policy below allows) and classified as above: Disjoint when both are, Impinges when either
//    occludes or impinges, else Punt. If a clipped part still straddles (rounding), the
//    σ-free line test decides: Disjoint only when two edges have all extremal lines strictly on
//    opposite sides (then no line has one sign on all edges, in either direction), else Punt.
// Contact (checked first): B lying on S's or R's plane (within the tolerance) and containing
// the whole element covers it with no gap: every segment ends on B ⇒ Occludes (a face hidden
// against another solid, a floor element under a box). A partial overlap is left to the plane
// tests (B on the element's plane is then disjoint from the segments' interiors): keeping it as
// impinging made links into half-covered elements PARTIAL, and the solver's refinement rule then
// kept them coarse, transferring the element's mean radiosity diluted by its covered part (a
// 27 % dark bias on a Cornell block face, measured). segmentBlocked still counts sample end
// points on a blocker as blocked.
// "On" a plane means within tol.length(), the project's policy: a vertex that close to B's
// plane counts as on it, which can misjudge segments only within that distance of the plane.
//
// PUNTs (beyond the paper): B is disjoint from all light-carrying segments iff no line crosses S
// along its normal, B (in a direction it can be crossed), and R against its normal; that is the
// stabbing test of the portal sequence S, B, R (punt_resolution.h).
#include "linespace/tube.h"

#include <cmath>
#include <optional>
#include <vector>

#include "linespace/punt_resolution.h"

namespace gv {
namespace {

struct PlaneSides {
  bool front = false, back = false;
};

PlaneSides sidesOf(std::span<const Vec3> points, const Plane& plane, double eps) {
  PlaneSides s;
  for (const Vec3& p : points) {
    const double d = plane.distance(p);
    s.front |= d > eps;
    s.back |= d < -eps;
  }
  return s;
}

bool noneInFront(std::span<const Vec3> points, const Plane& plane, double eps) {
  for (const Vec3& p : points)
    if (plane.distance(p) > eps) return false;
  return true;
}

}  // namespace

ContactCover contactCover(const ConvexPolygon& element, const BlockerGeometry& b,
                          const Tolerance& tol) {
  const double eps = tol.length();
  for (const Vec3& v : b.vertices)
    if (std::abs(element.plane.distance(v)) > eps) return ContactCover::None;
  // The inward planes of B's edges (perpendicular to B's plane): the element is covered when all
  // its vertices are inside every one, overlaps when clipping by all of them leaves something.
  const size_t n = b.vertices.size();
  std::vector<Plane> planes;
  planes.reserve(n);
  for (size_t k = 0; k < n; ++k) {
    const Vec3 inward = cross(b.plane.normal, b.vertices[(k + 1) % n] - b.vertices[k]);
    if (lengthSquared(inward) > 0) planes.push_back(Plane::through(b.vertices[k], inward));
  }
  bool all = true;
  for (const Plane& plane : planes)
    for (const Vec3& v : element.vertices) all &= plane.distance(v) >= -eps;
  if (all) return ContactCover::All;
  std::optional<ConvexPolygon> inside = element;
  for (size_t k = 0; k < planes.size() && inside; ++k)
    inside = clipToFront(*inside, planes[k], tol);
  return inside ? ContactCover::Part : ContactCover::None;
}

Tube::Tube(const ConvexPolygon& source, const ConvexPolygon& receiver)
    : source_(source), receiver_(receiver) {
  lines_.reserve(source.vertices.size() * receiver.vertices.size());
  for (const Vec3& s : source.vertices)
    for (const Vec3& r : receiver.vertices) lines_.push_back(FilteredLine::through(s, r));
}

namespace {

BlockerVerdict classify(const Tube& tube, const BlockerGeometry& b, const Tolerance& tol,
                        const TubeOptions& options, bool splitStraddling);

/// The straddling case: the two between sub-problems S ∩ H, R ∩ H' (see the top of the file).
BlockerVerdict classifyStraddling(const Tube& tube, const BlockerGeometry& b, const Tolerance& tol,
                                  const TubeOptions& options) {
  BlockerVerdict v;
  bool anyImpinges = false, anyPunt = false;
  for (const Plane& h : {b.plane, b.plane.flipped()}) {
    const std::optional<ConvexPolygon> s = clipToFront(tube.source(), h, tol);
    const std::optional<ConvexPolygon> r = clipToFront(tube.receiver(), h.flipped(), tol);
    if (!s || !r) continue;
    const BlockerVerdict part = classify(Tube(*s, *r), b, tol, options, false);
    anyImpinges |=
        part.outcome == BlockerOutcome::Occludes || part.outcome == BlockerOutcome::Impinges;
    anyPunt |= part.outcome == BlockerOutcome::Punt;
    v.wasPunt |= part.wasPunt;
  }
  v.outcome = anyImpinges ? BlockerOutcome::Impinges
                          : (anyPunt ? BlockerOutcome::Punt : BlockerOutcome::Disjoint);
  return v;
}

BlockerVerdict classify(const Tube& tube, const BlockerGeometry& b, const Tolerance& tol,
                        const TubeOptions& options, bool splitStraddling) {
  const double eps = tol.length();
  BlockerVerdict v;
  // A blocker lying on S's or R's plane (a box resting on a floor, a wall end against another
  // wall) covers the part of the element it overlaps: segments ending there end on B.
  for (const ConvexPolygon* end : {&tube.source(), &tube.receiver()}) {
    if (contactCover(*end, b, tol) != ContactCover::All) continue;
    v.outcome = BlockerOutcome::Occludes;
    v.byPlanes = true;
    return v;
  }
  // Plane tests: B must reach into the front of both S and R, and S and R must not lie on one
  // side of B's plane.
  if (noneInFront(b.vertices, tube.source().plane, eps) ||
      noneInFront(b.vertices, tube.receiver().plane, eps)) {
    v.outcome = BlockerOutcome::Disjoint;
    v.byPlanes = true;
    return v;
  }
  const PlaneSides s = sidesOf(tube.source().vertices, b.plane, eps);
  const PlaneSides r = sidesOf(tube.receiver().vertices, b.plane, eps);
  if (!(s.back || r.back) || !(s.front || r.front)) {
    v.outcome = BlockerOutcome::Disjoint;
    v.byPlanes = true;
    return v;
  }
  int sigma = 0;  // direction of travel of every S → R segment relative to B's normal
  if (s.front && !s.back && r.back && !r.front) sigma = -1;
  if (s.back && !s.front && r.front && !r.back) sigma = +1;
  v.between = sigma != 0;
  if (sigma == 0 && splitStraddling) return classifyStraddling(tube, b, tol, options);

  // Line tests: the sign of each extremal line against each edge.
  const std::span<const FilteredLine> lines = tube.extremalLines();
  const size_t edges = b.edges.size();
  // Per edge: are all lines strictly positive / strictly negative? Per line: one sign on all?
  constexpr size_t kMaxEdges = 64;
  bool allPositive[kMaxEdges], allNegative[kMaxEdges];
  const size_t tracked = edges < kMaxEdges ? edges : kMaxEdges;
  for (size_t k = 0; k < tracked; ++k) allPositive[k] = allNegative[k] = true;
  bool everyLineInside = true, someLineInside = false;
  for (const FilteredLine& line : lines) {
    bool hasPositive = false, hasNegative = false;
    for (size_t k = 0; k < edges; ++k) {
      const int sign = sideSign(line, b.edges[k]);
      hasPositive |= sign > 0;
      hasNegative |= sign < 0;
      if (k < tracked) {
        allPositive[k] &= sign > 0;
        allNegative[k] &= sign < 0;
      }
    }
    // "Inside" for a between blocker: σ·sign >= 0 on every edge; for a straddling one, the line
    // meets B's polygon (one sign on all edges, either way).
    const bool inside =
        sigma < 0 ? !hasPositive : (sigma > 0 ? !hasNegative : !(hasPositive && hasNegative));
    everyLineInside &= inside;
    someLineInside |= inside;
  }
  bool separated = false;
  if (sigma != 0) {
    for (size_t k = 0; k < tracked && !separated; ++k)
      separated = sigma > 0 ? allNegative[k] : allPositive[k];
  } else {
    bool anyPositive = false, anyNegative = false;
    for (size_t k = 0; k < tracked; ++k) {
      anyPositive |= allPositive[k];
      anyNegative |= allNegative[k];
    }
    separated = anyPositive && anyNegative;
  }

  if (separated) {
    v.outcome = BlockerOutcome::Disjoint;
  } else if (sigma != 0 && everyLineInside) {
    v.outcome = BlockerOutcome::Occludes;
  } else if (someLineInside) {
    v.outcome = BlockerOutcome::Impinges;
  } else {
    v.outcome = BlockerOutcome::Punt;
    v.wasPunt = true;
    if (options.resolvePunts && stabbingProvesDisjoint(tube, b, sigma, tol))
      v.outcome = BlockerOutcome::Disjoint;
  }
  return v;
}

}  // namespace

BlockerVerdict classifyBlocker(const Tube& tube, const BlockerGeometry& b, const Tolerance& tol,
                               const TubeOptions& options) {
  return classify(tube, b, tol, options, options.splitStraddling);
}

}  // namespace gv
