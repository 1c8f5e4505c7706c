// Brush solids and hidden-surface CSG for Quake maps: a brush is the intersection of its sides'
// inner half-spaces; a face's parts inside or flat against another solid are not visible.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/convex_polyhedron.h"
#include "quake/map_file.h"

namespace gv {

/// A brush as a solid. `shape`'s faces front OUT of the solid (into the air); `faceSide[i]` is the
/// index into the brush's sides of the side face i lies on (its texture).
struct BrushSolid {
  ConvexPolyhedron shape;
  std::vector<int> faceSide;
  Aabb box;
};

/// Merges nearly identical brush planes across a map, either facing: a plane that stays within
/// Tolerance::planeOffset() of a plane seen before over the whole brush (its bounding sphere) is
/// replaced by that one (flipped as needed). Editors write off-grid brushes with rounded points,
/// so two brushes meant to touch can leave gaps or slivers of a few thousandths of a unit between
/// slightly different planes; qbsp closes them by merging planes within its epsilons. First come,
/// first kept: no plane drifts by chaining, and a brush moves by at most planeOffset.
class PlaneSnapper {
 public:
  explicit PlaneSnapper(const Tolerance& tol) : tol_(tol) {}
  /// The representative of `plane` for a brush within `radius` of `centre` (`plane` becomes a
  /// representative itself when nothing is near).
  Plane snap(const Plane& plane, const Vec3& centre, double radius);

 private:
  Tolerance tol_;
  std::map<std::array<int64_t, 3>, std::vector<Plane>> buckets_;  ///< by quantised canonical normal
};

/// The solid of a brush, or nullopt when it is degenerate: a side whose three points are
/// collinear (within the length tolerance), or an intersection that is empty, flat or unbounded.
/// With a snapper, the side planes are snapped first.
std::optional<BrushSolid> brushSolid(const MapBrush& brush, const Tolerance& tol,
                                     PlaneSnapper* snapper = nullptr);

/// How a face lying in the plane of one of `other`'s faces (within `onTolerance`) is treated.
/// (Only "on the plane" and "wholly outside" use the loose `onTolerance`; hiding a part needs it
/// inside within the length tolerance, so a loose tolerance never cuts a crack into a surface.)
/// Opposite facing (two solids touching face to face) is always hidden: that part is between two
/// solids. Same facing (two solids with a common surface) is hidden only when `otherWinsTies`,
/// so that of two coincident faces exactly one survives.
/// With `flatAgainstOnly`, only the part flat against an opposite-facing face of `other` is hidden:
/// a face not lying in one of `other`'s planes is kept whole even where it passes through `other`.
struct CoplanarRule {
  bool otherWinsTies = false;
  double onTolerance = 0;
  bool flatAgainstOnly = false;
};

/// The parts of `face` not hidden by the convex solid `other`: the pieces outside it, plus the
/// pieces on its boundary that the coplanar rule keeps. Returns {face} unchanged (not cut up) when
/// `other` hides none of it; an empty vector when it hides all of it.
std::vector<ConvexPolygon> visibleParts(const ConvexPolygon& face, const ConvexPolyhedron& other,
                                        const CoplanarRule& rule, const Tolerance& tol);

}  // namespace gv
