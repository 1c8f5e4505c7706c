// Oriented planes n·x = d with unit normal n: the support planes of patches and BSP splits.
#pragma once

#include "geometry/vec3.h"

namespace gv {

/// Which side of an oriented plane something lies on, within a tolerance.
enum class PlaneSide { Back = -1, On = 0, Front = 1, Spanning = 2 };

/// The plane {x : dot(normal, x) = offset}; `normal` is unit length and points to the front.
struct Plane {
  Vec3 normal{0, 0, 1};
  double offset = 0;

  /// Signed distance of p: positive in front.
  double distance(const Vec3& p) const { return dot(normal, p) - offset; }
  /// The same plane facing the other way.
  Plane flipped() const { return {-normal, -offset}; }
  /// Plane through p with the given (not necessarily unit) normal; normal must be non-zero.
  static Plane through(const Vec3& p, const Vec3& n) {
    const Vec3 u = normalize(n);
    return {u, dot(u, p)};
  }
  /// Side of p with "on" meaning |distance| <= eps.
  PlaneSide side(const Vec3& p, double eps) const {
    const double s = distance(p);
    return s > eps ? PlaneSide::Front : (s < -eps ? PlaneSide::Back : PlaneSide::On);
  }
};

}  // namespace gv
