// Does a patch meet the convex hull of two others? The blocker criterion of paper §5: only a
// patch meeting conv(S, R) can stop a segment from S to R.
#pragma once

#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"

namespace gv {

/// conv(s ∪ r), prepared once for the many blocker candidates of one pair.
///
/// `meets(b)` is false only when a plane separates `b` from the hull (touching within
/// tol.length() counts as separated: it blocks no segment of positive measure). Candidate planes:
/// the planes of s, r and b, and the hull's side planes through an edge of one polygon and a
/// vertex of the other. Conservative: a polygon these planes cannot separate is reported as
/// meeting.
class PairHull {
 public:
  PairHull(const ConvexPolygon& s, const ConvexPolygon& r, const Tolerance& tol);
  /// `bBox` is b's bounding box (callers testing many pairs keep them).
  bool meets(const ConvexPolygon& b, const Aabb& bBox) const;
  bool meets(const ConvexPolygon& b) const { return meets(b, b.bounds()); }

 private:
  /// A plane n·(x − o) with the hull's range of values on it, kept only if the hull lies on one
  /// side (otherwise it can separate nothing).
  struct SidePlane {
    Vec3 n, o;
    double lo, hi, eps;  // hull range; tolerance in units of |n|
  };
  std::vector<Vec3> hull_;
  std::vector<SidePlane> planes_;
  Aabb box_;
  double eps_;
};

/// PairHull(s, r, tol).meets(b): the one-off form.
bool meetsConvexHull(const ConvexPolygon& b, const ConvexPolygon& s, const ConvexPolygon& r,
                     const Tolerance& tol);

}  // namespace gv
