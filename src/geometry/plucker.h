// Plücker coordinates of oriented lines and the side of two lines: the algebra of stabbing lines
// through portal sequences (paper §4.1; a line stabs a convex portal iff its side with every
// oriented portal edge has one sign).
#pragma once

#include "geometry/vec3.h"

namespace gv {

/// A directed segment from `a` to `b`; as a line it is oriented a → b. Portal edges and sample
/// lines are given this way so that exact predicates can use the original end points.
struct Segment {
  Vec3 a, b;
};

/// Plücker coordinates of the oriented line through p then q: direction d = q - p and moment
/// m = p x q (so d·m = 0). Scaling by a positive factor gives the same oriented line; the
/// coordinates are not normalised, so `side` values are only meaningful in sign and relative size.
struct PluckerLine {
  Vec3 direction;
  Vec3 moment;

  /// The oriented line through p then q (p != q).
  static PluckerLine through(const Vec3& p, const Vec3& q) { return {q - p, cross(p, q)}; }
  static PluckerLine of(const Segment& s) { return through(s.a, s.b); }
  /// The same line with the opposite orientation.
  PluckerLine reversed() const { return {-direction, -moment}; }
};

/// The permuted inner product da·mb + ma·db (floating point, not exact). It is symmetric,
/// side(a, b) = side(b, a); it changes sign when either line is reversed; it is zero iff the
/// lines meet or are parallel. For a = line(p→q), b = line(r→s) it equals, up to rounding,
/// det[q - p, r - p, s - p], so its sign is orient3d(p, q, r, s):
/// positive when s is on the side of the plane (p, q, r) toward which (q - p) x (r - p) points;
/// geometrically, seen looking along a (from p toward q), b passes a clockwise.
inline double side(const PluckerLine& a, const PluckerLine& b) {
  return dot(a.direction, b.moment) + dot(a.moment, b.direction);
}

/// The exact sign of side(PluckerLine::of(l), PluckerLine::of(e)): orient3d(l.a, l.b, e.a, e.b).
/// +1, -1 as for `side`; 0 when the two lines are exactly coplanar (meet or are parallel).
int sideExact(const Segment& l, const Segment& e);

}  // namespace gv
