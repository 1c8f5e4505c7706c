// Does a patch meet the convex hull of two others? The blocker criterion of paper §5: only a
// patch meeting conv(S, R) can stop a segment from S to R.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"

namespace gv {

/// conv(s ∪ r), prepared once for the many blocker candidates of one pair.
///
/// `meets(b)` is false only when a plane separates `b` from the hull (touching within
/// tol.length() counts as separated: it blocks no segment of positive measure), except across
/// the planes the hull is flat against: where the hull is less than kFlatHull tolerances deep
/// along a plane's normal (s and r nearly coplanar, as the pieces of one ramp a hair out of line
/// that coplanar_grazes.h pairs), every segment runs within a few tolerances of that plane, and
/// a patch touching it there (a box standing on the ramp, its edge on the ramp's plane) is the
/// first hit of a whole family of them (q3-oacmpdm4's pair (2589, 2592) and patch 2600). Across
/// such a plane b is separated only when it lies beyond the hull grown by the tolerance.
/// Candidate planes:
/// the planes of s, r and b, and the hull's side planes through an edge of one polygon and a
/// vertex of the other. Conservative: a polygon these planes cannot separate is reported as
/// meeting. Side planes that repeat one another (parallel boxes give each hull face up to four
/// times) are kept once: dropping a plane can only turn "separated" into "meets".
class PairHull {
 public:
  PairHull(const ConvexPolygon& s, const ConvexPolygon& r, const Tolerance& tol);
  /// The shaft of s and a group of receivers: conv(s ∪ box)'s side planes, for `separatesBox`
  /// and `box` only. Every pair hull conv(s, r) with r inside `around` lies in it, so a patch
  /// box this form separates can be dropped for all of the group's pairs with one test. Its
  /// planes are not facets of those pair hulls, so it separates only boxes lying more than
  /// twice the tolerance beyond the shaft: never a patch that meets a pair's hull grown by the
  /// tolerance, as the pair's own tests count meeting.
  PairHull(const ConvexPolygon& s, const Aabb& around, const Tolerance& tol);
  /// `bBox` is b's bounding box (callers testing many pairs keep them).
  bool meets(const ConvexPolygon& b, const Aabb& bBox) const;
  bool meets(const ConvexPolygon& b) const { return meets(b, b.bounds()); }
  /// The first, cheapest part of `meets`: false when b's box misses the hull's box (grown by the
  /// tolerance), and then `meets` is false too.
  bool boxMeets(const Aabb& bBox) const;
  /// The rest of `meets`, for callers that know boxMeets(b's box) holds:
  /// meets(b, box) == boxMeets(box) && meetsInBox(b).
  bool meetsInBox(const ConvexPolygon& b) const { return meetsInBox(b.vertices, b.plane.normal); }
  /// meetsInBox of the polygon with these vertices and plane normal.
  bool meetsInBox(std::span<const Vec3> vertices, const Vec3& normal) const {
    return meetsInBox(vertices, normal, length(normal));
  }
  /// meetsInBox with the normal's length, length(normal), given (callers testing many pairs
  /// keep it per patch).
  bool meetsInBox(std::span<const Vec3> vertices, const Vec3& normal, double normalLength) const;
  /// True when one side plane has all of `box` beyond it by at least half the tolerance: then
  /// meetsInBox is false for every polygon inside the box (that plane separates it). Lets a
  /// query over many candidates skip whole groups of them (PatchGrid::gatherInto). For the
  /// shaft form, beyond by at least three times the tolerance (see its constructor).
  bool separatesBox(const Aabb& box) const;
  /// separatesBox over many boxes: keeps, in order, the ids among ids[0, n) whose box
  /// (boxes[id]) no side plane separates, and returns how many. The same answers as calling
  /// separatesBox on each, found plane by plane over all the boxes: each plane's corner choice is
  /// made once, and the loop over boxes has no early exit to mispredict.
  size_t keepUnseparated(uint32_t* ids, size_t n, std::span<const Aabb> boxes) const;
  /// The hull's bounding box (not grown by the tolerance).
  const Aabb& box() const { return box_; }
  /// Side planes kept (after removing repeats), for tests and statistics.
  size_t planeCount() const { return c_.size(); }
  /// A hull less deep than this many tolerances along a plane's normal is flat against it.
  static constexpr double kFlatHull = 1000;

 private:
  /// Side planes, unit normal n and offset c, oriented so that the hull lies in n·x − c <= eps:
  /// a polygon with every vertex at n·x − c >= touch is separated, touch = −eps, or +eps for a
  /// plane the hull is flat against (see the class comment). Structure of arrays so that the
  /// loop over planes runs over contiguous doubles.
  std::vector<double> nx_, ny_, nz_, c_, touch_;
  std::vector<Vec3> hull_;
  Aabb box_;
  double eps_;
  /// The shaft form (see its constructor): separatesBox then asks a box to lie 3 eps beyond a
  /// plane (its hull lies within eps behind each plane, so such a box is 2 eps from every pair
  /// hull inside it); for a pair, touch + eps / 2 (its planes are the hull's facets, which
  /// meetsInBox tests at touch).
  bool shaft_ = false;

  void addPlane(const Vec3& n, double c, double touch);
  /// Keeps the plane with normal n through o if hull_ lies on one side of it (within eps). In
  /// the pair form a plane the hull is flat against gets the grown test; the shaft form's planes
  /// are only used by separatesBox, with its own margin.
  void consider(const Vec3& n, const Vec3& o);
};

/// PairHull(s, r, tol).meets(b): the one-off form.
bool meetsConvexHull(const ConvexPolygon& b, const ConvexPolygon& s, const ConvexPolygon& r,
                     const Tolerance& tol);

}  // namespace gv
