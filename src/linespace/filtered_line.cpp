// Filtered exact Plücker side signs. Paper §6.1.
#include "linespace/filtered_line.h"

#include <cmath>

namespace gv {

FilteredLine FilteredLine::through(const Vec3& a, const Vec3& b) {
  FilteredLine l;
  l.segment = {a, b};
  l.line = PluckerLine::through(a, b);
  const Vec3& d = l.line.direction;
  l.absDirection = {std::abs(d.x), std::abs(d.y), std::abs(d.z)};
  l.absMoment = {std::abs(a.y * b.z) + std::abs(a.z * b.y),
                 std::abs(a.z * b.x) + std::abs(a.x * b.z),
                 std::abs(a.x * b.y) + std::abs(a.y * b.x)};
  return l;
}

int sideSign(const FilteredLine& a, const FilteredLine& b) {
  const double value = side(a.line, b.line);
  const double bound = kPluckerSideErrorFactor *
                       (dot(a.absDirection, b.absMoment) + dot(a.absMoment, b.absDirection));
  if (value > bound) return 1;
  if (value < -bound) return -1;
  // Lines through a common point are coplanar: exactly 0 without the exact predicate. Meshes
  // share vertices everywhere (an element's corner on a blocker's edge end), and there the
  // filter always fails.
  const Segment& p = a.segment;
  const Segment& q = b.segment;
  if (p.a == q.a || p.a == q.b || p.b == q.a || p.b == q.b || p.a == p.b || q.a == q.b) return 0;
  // Two lines parallel to the same coordinate axis (exactly: a direction component is computed
  // as zero iff the two end point coordinates are equal) are coplanar. Vertical edges and
  // vertical extremal lines meet this everywhere in architecture.
  const Vec3& u = a.line.direction;
  const Vec3& w = b.line.direction;
  for (int axis = 0; axis < 3; ++axis) {
    const int i = (axis + 1) % 3, j = (axis + 2) % 3;
    if (u[i] == 0 && u[j] == 0 && w[i] == 0 && w[j] == 0) return 0;
  }
  return sideExact(a.segment, b.segment);
}

}  // namespace gv
