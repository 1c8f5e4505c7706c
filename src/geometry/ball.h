// Bounding balls of point sets and of other balls: the cheap first test before a polygon's
// vertices are tested against a plane (the target checks of the cell PVS, the over-budget
// answers of the patch searches).
#pragma once

#include <algorithm>
#include <span>

#include "geometry/tolerance.h"
#include "geometry/vec3.h"

namespace gv {

/// The points within `radius` of `center`.
struct Ball {
  Vec3 center;
  double radius = 0;
};

/// A radius grown so that ball tests against planes hold despite rounding (1e-9 of the radius
/// and of the length tolerance, far above the ~1e-16 relative error of a dot product).
inline double withRoundingRoom(double radius, const Tolerance& tol) {
  return radius * (1 + 1e-9) + 1e-9 * tol.length();
}

/// A ball holding every point: about their mean, out to the farthest, with rounding room. The
/// empty set gets the zero ball.
inline Ball ballAround(std::span<const Vec3> points, const Tolerance& tol) {
  Ball b;
  if (points.empty()) return b;
  for (const Vec3& v : points) b.center += v;
  b.center = b.center / double(points.size());
  for (const Vec3& v : points) b.radius = std::max(b.radius, length(v - b.center));
  b.radius = withRoundingRoom(b.radius, tol);
  return b;
}

/// A ball holding every ball of `balls` (as ballAround, over their centres and radii).
inline Ball ballAroundBalls(std::span<const Ball> balls, const Tolerance& tol) {
  Ball b;
  if (balls.empty()) return b;
  for (const Ball& x : balls) b.center += x.center;
  b.center = b.center / double(balls.size());
  for (const Ball& x : balls) b.radius = std::max(b.radius, length(x.center - b.center) + x.radius);
  b.radius = withRoundingRoom(b.radius, tol);
  return b;
}

}  // namespace gv
