// Boolean operations on convex polygons lying in one plane: the intersection of two cells' faces
// and the subtraction of opaque patches from it, which leave the portals. Paper §3.
#pragma once

#include <optional>
#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/tolerance.h"

namespace gv {

/// The edge planes of a convex polygon: through each edge, perpendicular to the polygon's plane,
/// front = the polygon's inside. A point in the polygon's plane is inside the polygon iff it is in
/// front of (or on) all of them, whatever its offset along the normal: so a polygon whose plane
/// differs from the other operand's by a merge tolerance still cuts it where it projects.
std::vector<Plane> edgePlanes(const ConvexPolygon& polygon);

/// The part of `a` inside `b` (both in one plane up to tolerance; `b` may face either way). Keeps
/// `a`'s plane and orientation. nullopt when they overlap in less than a sliver of width
/// tol.length().
std::optional<ConvexPolygon> intersectCoplanar(const ConvexPolygon& a, const ConvexPolygon& b,
                                               const Tolerance& tol);

/// Appends to `out` the convex pieces of `a` minus `b` (pairwise disjoint, each keeping `a`'s
/// plane and orientation; slivers thinner than tol.length() are dropped). At most one piece per
/// edge of `b`. Returns false when `b` does not cut `a` at all (then `a` itself was appended).
bool subtractCoplanar(const ConvexPolygon& a, const ConvexPolygon& b, const Tolerance& tol,
                      std::vector<ConvexPolygon>& out);

}  // namespace gv
