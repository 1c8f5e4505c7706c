// The project's one tolerance policy: every geometric "equal" / "on" decision scales with the
// size of the scene, never an absolute epsilon (absolute epsilons are what break Quake-family
// tools on large maps). Construct a Tolerance from the scene's bounding-box diagonal once and
// pass it down; kernels never invent their own epsilons.
#pragma once

#include "geometry/vec3.h"

namespace gv {

/// Relative size of "the same point" / "on the plane" decisions. 1e-9 of the scene diagonal is
/// ~10^6 ulps of double precision at that magnitude (so rounding in plane evaluations, ~10 ulps,
/// never crosses it) and still far below any feature a modeller draws (1e-9 of a 1 km level is
/// 1 micrometre).
inline constexpr double kRelativeLengthEpsilon = 1e-9;

/// Relative tolerance for modelling imprecision: a face whose vertices stray from their best-fit
/// plane by more than this fraction of the face's own diameter is "non-planar" and is
/// triangulated; two patch planes closer than this (angle in radians, and offset relative to the
/// scene) are treated as one plane by the BSP. Real levels (Quake .map brush planes rounded to
/// integer/0.1 units) need this to be loose; 1e-5 keeps a 10 m wall within 0.1 mm.
inline constexpr double kRelativeModelEpsilon = 1e-5;

/// Stabbing-line linear programs (paper §4.1, src/visibility/stabbing.cpp) run in coordinates
/// scaled to the scene (|x| <= 1) with unit-length Plücker hyperplanes. A sequence is declared
/// unstabbable only when even the best line misses some portal edge by more than this margin
/// (relative to the size of the line's coordinates): rounding in a 6-variable LP over unit rows
/// is ~1e-13, so a wrong "no" would need an error a million times larger; a "no" that falls
/// inside the margin is answered "maybe visible" instead.
inline constexpr double kStabbingLpMargin = 1e-7;

/// A stabbing line is normalised to cross the first portal with unit speed along its normal; its
/// tangential direction is bounded by this, so lines within atan(1e-4) ~ 0.006 degrees of the
/// first portal's plane are outside the LP's search box (a documented, measure-tiny limitation).
inline constexpr double kStabbingMaxGrazingSlope = 1e4;

/// Feasibility slack of the LP solver itself, relative to the size of the current point: a
/// constraint is "violated" only beyond rounding noise, so that degenerate (touching) constraints
/// do not trigger needless recursions.
inline constexpr double kLpRelativeFeasibility = 1e-12;

/// Tolerances of one scene. `scale` is the diagonal of its bounding box (at least 1e-300 so that a
/// degenerate scene still gets a positive tolerance).
struct Tolerance {
  double scale = 1.0;

  static Tolerance forBounds(const Aabb& box) {
    const double d = box.diagonal();
    return {d > 1e-300 ? d : 1.0};
  }
  /// Points closer than this are the same point; a point this close to a plane is on it.
  double length() const { return kRelativeLengthEpsilon * scale; }
  /// Offset tolerance for merging nearly identical planes and for "coplanar" patch tests.
  double planeOffset() const { return kRelativeModelEpsilon * scale; }
  /// Angle (as 1 - cos) below which two unit normals are parallel.
  double normalCos() const { return 0.5 * kRelativeModelEpsilon * kRelativeModelEpsilon; }
};

}  // namespace gv
