// Conservative shrinking of portals along a portal sequence: the separating planes of the
// anti-penumbra (paper §4.1, Fig. 5; the same planes Quake's `vis` uses). Every clip here keeps
// every point where a stabbing line can cross the clipped portal, so it can only prune sequences
// that admit no stabbing line.
#pragma once

#include <span>
#include <vector>

#include "geometry/tolerance.h"
#include "geometry/vec3.h"

namespace gv {

/// A convex portal carried by the stabbing search: vertices in order around it, counter-clockwise
/// seen from the side sightlines go to. Unlike ConvexPolygon it may be thin (a clipped sliver is
/// kept, never dropped: dropping it could lose a real sightline).
using Winding = std::vector<Vec3>;

/// The part of `in` where dot(unitNormal, x) - offset >= -slack, written to `out`
/// (Sutherland–Hodgman; `out` empty when nothing is left). The slack (a few orders of magnitude
/// above rounding) makes the result contain the exact clipped region despite rounded
/// intersection points.
void clipToHalfspace(std::span<const Vec3> in, const Vec3& unitNormal, double offset, double slack,
                     Winding& out);

/// Clips `target` (a portal later in the sequence than `pass`, which is later than `source`) by
/// every plane through an edge of `source` and a vertex of `pass`, or an edge of `pass` and a
/// vertex of `source`, that separates them: the other vertices of the two polygons strictly on
/// opposite sides, decided exactly. Keeps the pass's side. Returns false when nothing of `target`
/// is left (then no line stabs source, pass, target in that order).
///
/// Why no sightline is lost: let a line cross source at s, pass at p, target at r, in this order
/// along it (convex cells in between force the order). Let f be the signed distance to a
/// separating plane, negative on the source's side. f(s) <= 0 <= f(p), and s != p because the
/// strict test makes the two polygons meet the plane in disjoint sets (an edge and a vertex off
/// its line). f is affine along the line, so it is non-decreasing from s to p and onward:
/// f(r) >= f(p) >= 0. The kept halfspace therefore contains r; the clip slack only adds points.
bool clipBySeparatingPlanes(std::span<const Vec3> source, std::span<const Vec3> pass,
                            Winding& target, const Tolerance& tol);

/// A clipping halfspace: keeps dot(unitNormal, x) >= offset (less the clip slack).
struct ClipPlane {
  Vec3 unitNormal;
  double offset = 0;
};

/// The separating planes clipBySeparatingPlanes(source, pass, ·) clips by, in its order: they
/// depend on the pair only, so a search can find them once and clip every later portal by them.
void separatingPlanes(std::span<const Vec3> source, std::span<const Vec3> pass,
                      std::vector<ClipPlane>& out);

/// Clips `target` by each plane in turn (`scratch` is working memory); false when nothing is left.
bool clipByPlanes(std::span<const ClipPlane> planes, Winding& target, Winding& scratch,
                  const Tolerance& tol);

/// Counter-clockwise normal of a vertex loop (Newell's method), not normalised; zero for a
/// degenerate loop. Points to the side sightlines cross toward.
Vec3 newellNormal(std::span<const Vec3> loop);

}  // namespace gv
