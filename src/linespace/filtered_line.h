// Plücker lines with a floating-point error bound, so that the side of two lines (paper §6.1:
// "inner products between points and hyperplanes") is decided exactly: the fast 5D inner product
// when its rounding cannot change the sign, orient3d of the end points otherwise.
#pragma once

#include "geometry/plucker.h"

namespace gv {

/// Rounding-error factor of `side` on Plücker coordinates made from double end points, relative
/// to the sum of absolute products (see FilteredLine): the direction (one subtraction, error u
/// per component), the moment (two products and a subtraction, <= 3u of its absolute sum), six
/// products and a sum of six terms (<= 6u) give at most ~10u; 32u = 2^-48 leaves margin for the
/// rounding of the bound itself.
inline constexpr double kPluckerSideErrorFactor = 0x1.0p-48;

/// An oriented line a → b as Plücker coordinates plus what the exact sign test needs: the end
/// points (for orient3d) and the absolute sizes of the coordinates (for the error bound).
struct FilteredLine {
  Segment segment;
  PluckerLine line;
  Vec3 absDirection;  ///< |d| per component
  Vec3 absMoment;     ///< per component |a_y b_z| + |a_z b_y| etc.: bounds the moment's rounding

  /// The line through a then b (a == b gives the zero line, on every side 0).
  static FilteredLine through(const Vec3& a, const Vec3& b);
};

/// The exact sign of side(a.line, b.line), i.e. orient3d(a.a, a.b, b.a, b.b) (see plucker.h for
/// its geometric meaning): the floating inner product when it exceeds its error bound, the exact
/// predicate otherwise. +1, -1, or 0 when the lines are exactly coplanar.
int sideSign(const FilteredLine& a, const FilteredLine& b);

}  // namespace gv
