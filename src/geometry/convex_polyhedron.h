// Convex polyhedra as halfspaces plus boundary polygons: the cells of the BSP. Paper §3.
#pragma once

#include <optional>
#include <vector>

#include "geometry/convex_polygon.h"
#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "geometry/vec3.h"

namespace gv {

/// One boundary face of a convex polyhedron. Its polygon's front faces OUT of the polyhedron
/// (vertices counter-clockwise seen from outside) and lies on halfspace `halfspace`.
struct PolyhedronFace {
  ConvexPolygon polygon;
  /// Index into ConvexPolyhedron::halfspaces of the plane supporting this face.
  int halfspace = -1;
  /// Free for the BSP: the id of the splitting plane (or input plane) this face lies on; -1 when
  /// it came from the initial box or nobody set it. Kept by `split` for faces that survive.
  int planeId = -1;
};

/// A bounded convex polyhedron {x : h.distance(x) <= 0 for every h in halfspaces}; every normal
/// points OUT. Invariants (kept by every operation): each halfspace supports exactly one face
/// (redundant halfspaces are dropped), there are at least 4 faces, and the polyhedron is thicker
/// than the length tolerance it was built with.
struct ConvexPolyhedron {
  std::vector<Plane> halfspaces;
  std::vector<PolyhedronFace> faces;

  /// The box as a polyhedron with its 6 faces in the order -x, +x, -y, +y, -z, +z; built from the
  /// box's corners exactly (no clipping). nullopt when the box is empty or flat in some axis.
  static std::optional<ConvexPolyhedron> fromAabb(const Aabb& box);

  /// The intersection of the halfspaces (normals out, inside = distance <= 0). Each face is a
  /// large square on its plane clipped by all other halfspaces; duplicate planes (same normal
  /// and offset within tolerance) are merged and planes supporting no face are dropped.
  /// nullopt when the intersection is empty, thinner than tol.length(), or unbounded; "unbounded"
  /// means reaching beyond kHalfspaceReachFactor × (tol.scale + max |offset|) from the origin.
  static std::optional<ConvexPolyhedron> fromHalfspaces(const std::vector<Plane>& planes,
                                                        const Tolerance& tol);

  /// Enclosed volume by the divergence theorem over the faces.
  double volume() const;
  /// Centre of mass of the solid (uniform density).
  Vec3 centroid() const;
  Aabb bounds() const;
  /// True when p is inside or within tol.length() of every halfspace.
  bool contains(const Vec3& p, const Tolerance& tol) const;
  /// Front/Back when every vertex is on that side or within tol.length() of the plane (and one is
  /// strictly on that side), Spanning when vertices are strictly on both sides. (A bounded solid
  /// cannot be On a plane; On is returned only for a degenerate polyhedron.)
  PlaneSide classify(const Plane& plane, const Tolerance& tol) const;
};

/// How far from the origin fromHalfspaces looks for a bounded intersection, relative to the scene
/// size plus the planes' offsets: the size of the initial square on each plane. 1e3 keeps the
/// rounding of clipping such a square (~1e3 × 2^-52 of the scene) far below tol.length() (1e-9).
inline constexpr double kHalfspaceReachFactor = 1e3;

/// The two parts of a polyhedron cut by a plane. A side that is empty, or whose part would be
/// thinner than the tolerance, is nullopt; otherwise each part is a valid polyhedron whose faces
/// include the cap on the splitting plane (for `back` facing along splitter.normal, for `front`
/// against it), carrying `capPlaneId` as its planeId.
struct PolyhedronSplit {
  std::optional<ConvexPolyhedron> front, back;
};
PolyhedronSplit split(const ConvexPolyhedron& polyhedron, const Plane& splitter,
                      const Tolerance& tol, int capPlaneId = -1);

}  // namespace gv
