// Convex planar polygons: patches, boundary faces of cells, portals. Paper §3.
#pragma once

#include <optional>
#include <vector>

#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "geometry/vec3.h"

namespace gv {

/// A convex planar polygon. Vertices are counter-clockwise seen from the front, i.e. from the side
/// `plane.normal` points to. Invariants (established by `fromVertices`, kept by every operation):
/// at least 3 vertices, no two consecutive vertices closer than the length tolerance, convex.
struct ConvexPolygon {
  std::vector<Vec3> vertices;
  Plane plane;

  /// Builds a polygon from vertices assumed convex and planar (within tolerance), computing the
  /// plane by Newell's method. Removes repeated consecutive vertices and collinear middle vertices.
  /// Returns nullopt when fewer than 3 distinct vertices remain or the polygon has zero width
  /// (twice its area over its longest edge below tol.length()).
  static std::optional<ConvexPolygon> fromVertices(std::vector<Vec3> vertices,
                                                   const Tolerance& tol);
  /// As `fromVertices`, but keeps `plane` (whose front the vertices must be counter-clockwise
  /// from) instead of refitting one: pieces of a split polygon and faces of a cell stay exactly on
  /// their support plane, so repeated splitting never drifts the plane.
  static std::optional<ConvexPolygon> fromVerticesInPlane(std::vector<Vec3> vertices,
                                                          const Plane& plane, const Tolerance& tol);

  double area() const;
  Vec3 centroid() const;  ///< area centroid
  Vec3 normal() const { return plane.normal; }
  Aabb bounds() const;
  /// The same polygon seen from the other side (reversed vertex order, flipped plane).
  ConvexPolygon flipped() const;
  /// Side of the whole polygon: Front/Back if every vertex is on that side or on the plane (and at
  /// least one strictly), On if all vertices are within tol.length(), Spanning otherwise.
  PlaneSide classify(const Plane& splitter, const Tolerance& tol) const;
  /// True when p lies in the polygon's plane (within tolerance) and inside or on its boundary.
  bool contains(const Vec3& p, const Tolerance& tol) const;
  /// The point of the polygon nearest to `x` (in it, or on its boundary).
  Vec3 nearestPoint(const Vec3& x) const;
};

/// The pieces of a polygon cut by a plane. For a polygon lying in the plane (within tolerance),
/// `on` holds it and front/back are empty; otherwise `on` is empty. A piece thinner than the
/// tolerance is dropped (reported empty) rather than returned as a sliver.
struct PolygonSplit {
  std::optional<ConvexPolygon> front, back, on;
};
PolygonSplit split(const ConvexPolygon& polygon, const Plane& splitter, const Tolerance& tol);

/// The part of `polygon` in front of (or on) `plane`: Sutherland–Hodgman against one halfspace.
std::optional<ConvexPolygon> clipToFront(const ConvexPolygon& polygon, const Plane& plane,
                                         const Tolerance& tol);

/// Whether two one-sided polygons can face each other: some vertex of each lies more than `eps`
/// in front of the other's plane. False when either lies wholly behind or on the other's plane
/// (within `eps`), so coplanar polygons never face each other.
bool canFace(const ConvexPolygon& a, const ConvexPolygon& b, double eps);

}  // namespace gv
