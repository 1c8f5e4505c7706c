// Candidate stabbing lines of a fixed direction (paper §4.1's "witness" step): with the direction
// chosen, a line crosses every convex portal iff its point lies in every portal's projection
// along that direction, an intersection of convex polygons in the plane. Cheap, so the stabbing
// test tries it before any linear programming.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "geometry/plucker.h"
#include "geometry/vec3.h"

namespace gv {

/// Scratch memory for lineAlongDirection (one per thread; keeps the hot path allocation-free).
struct WitnessScratch {
  std::vector<double> a, b;  // 2D polygons as x0 y0 x1 y1 ...
};

/// A line of direction `d` (non-zero) meeting every loop of `loops` (convex vertex loops, any
/// orientation), or nullopt when the projections along d share no point with some room to spare
/// (then a line of that direction is unlikely to survive exact confirmation). The line passes
/// through the centroid of the common region, so it tends to cross the portals' interiors.
/// Floating point: a candidate for exact confirmation, never a proof.
std::optional<Segment> lineAlongDirection(std::span<const std::span<const Vec3>> loops,
                                          const Vec3& d, WitnessScratch& scratch);

}  // namespace gv
