// Does a patch meet the convex hull of two others? The blocker criterion of paper §5: only a
// patch meeting conv(S, R) can stop a segment from S to R.
#pragma once

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"

namespace gv {

/// False only when a plane separates `b` from conv(s ∪ r) (touching within tol.length() counts as
/// separated: it blocks no segment of positive measure). Candidate planes: the planes of s, r and
/// b, and the hull's side planes through an edge of one polygon and a vertex of the other.
/// Conservative: a pair it cannot separate with these planes is reported as meeting.
bool meetsConvexHull(const ConvexPolygon& b, const ConvexPolygon& s, const ConvexPolygon& r,
                     const Tolerance& tol);

}  // namespace gv
