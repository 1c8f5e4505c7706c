// Exact orientation predicates (Shewchuk-style filtered, via CGAL): the combinatorial decisions
// of the pipeline — point vs plane, line vs line (Plücker side, paper §4.1) — that must never be
// answered wrongly by rounding.
#pragma once

#include "geometry/vec3.h"

namespace gv {

/// Exact sign of det[b - a, c - a, d - a] = dot(cross(b - a, c - a), d - a), for the double
/// inputs exactly as given (no rounding anywhere).
/// +1: d lies on the side of the plane through a, b, c toward which (b - a) x (c - a) points,
///     i.e. a, b, c are counter-clockwise seen from d; equivalently abcd is a positively
///     oriented (right-handed) tetrahedron. Example: orient3d(0, x, y, z) = +1.
/// -1: the other side. 0: the four points are exactly coplanar.
/// NOTE: this is the opposite sign of Shewchuk's `orient3d` (which is positive when d is below).
int orient3d(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// Exact sign of det[b - a, c - a] = (bx - ax)(cy - ay) - (by - ay)(cx - ax): +1 when a, b, c
/// turn counter-clockwise (c left of the directed line a→b), -1 clockwise, 0 exactly collinear.
int orient2d(double ax, double ay, double bx, double by, double cx, double cy);

/// orient2d of a, b, c projected along axis `dropAxis` (0, 1, 2) onto the two remaining axes
/// taken in cyclic order ((k+1)%3, (k+2)%3), so that the result is the exact sign of
/// cross(b - a, c - a)[dropAxis]. Use with `dominantAxis(normal)` to decide turns in a polygon's
/// plane: +1 then means counter-clockwise seen from the side normal[dropAxis] points to.
int orient2dProjected(const Vec3& a, const Vec3& b, const Vec3& c, int dropAxis);

}  // namespace gv
