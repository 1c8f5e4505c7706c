// Lines between two polygons of one convex cell (paper §4.2; see facing_lines.h).
#include "visibility/facing_lines.h"

#include <algorithm>
#include <cmath>

namespace gv {

FacingLines facingLines(const ConvexPolygon& source, const ConvexPolygon& target, double eps) {
  double targetInFront = -INFINITY;  // max over T of the distance to S's plane
  for (const Vec3& q : target.vertices)
    targetInFront = std::max(targetInFront, source.plane.distance(q));
  if (!(targetInFront > eps)) return {};
  double hi = -INFINITY, lo = INFINITY;  // range over S of the distance to T's plane
  for (const Vec3& p : source.vertices) {
    const double d = target.plane.distance(p);
    hi = std::max(hi, d);
    lo = std::min(lo, d);
  }
  return {hi > eps, lo < -eps};
}

}  // namespace gv
