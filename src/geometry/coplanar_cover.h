// Joint occlusion by coplanar polygons (beyond the paper's §6.2; its Fig. 17 case): a wall made
// of several patches hides R from S although no single patch does. Decided in the wall's plane
// from the points where the segments between the vertices of S and of R cross it. Used by the
// blocker stage of `vis` (visibility/blocker_detection.cpp: such pairs are INVISIBLE) and by the
// linespace tube classification (linespace/tube_classification.h).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/convex_polygon.h"

namespace gv {

/// A convex polygon lying in `plane` (unit normal), its vertices counter-clockwise seen from the
/// plane's front: a view of a ConvexPolygon or of the linespace's BlockerGeometry.
struct PlanarOutline {
  const Plane* plane = nullptr;
  std::span<const Vec3> vertices;
};

/// True when every segment from S to R meets one of `blockers`. The caller guarantees that S and
/// R lie strictly on opposite sides of the first blocker's plane P; every vertex of every blocker
/// must lie within `eps` of P (false otherwise).
///
/// Why it is sound: every segment from S to R crosses P once, at a convex combination of the
/// points where the segments between the vertices of S and of R cross it (conv(S ∪ R) ∩ P is the
/// convex hull H of those points). If the blockers cover H, every segment crosses P (between its
/// ends) inside some blocker. Coverage is decided by subtracting each blocker from H as convex
/// pieces; a piece thinner than `eps` is dropped (the tolerance policy: a gap that thin is not a
/// gap, as the portals of bsp/subdivision.h, which are never that thin), which is what makes
/// patches sharing an edge cover their union despite rounding. One of those crossing points
/// farther than `eps` outside every blocker answers false at once (the uncovered part of H there
/// could be a wedge thinner than `eps`: false is then the looser answer, never a wrong one).
bool coplanarOutlinesCover(const ConvexPolygon& s, const ConvexPolygon& r,
                           std::span<const PlanarOutline> blockers, double eps);

/// Scratch memory of someCoplanarGroupCovers, kept by callers that ask many times.
struct CoplanarGroups {
  std::vector<uint8_t> grouped;
  std::vector<PlanarOutline> group;
  /// After a true answer: the covering group, as indices into `outlines`, its first member first.
  std::vector<uint32_t> members;
};

/// Whether a group of two or more of `outlines` lying in one plane hides R from S together
/// (coplanarOutlinesCover). Each outline must have S and R strictly on opposite sides of its
/// plane. A group is an outline and the later ones with every vertex within `eps` of its plane.
bool someCoplanarGroupCovers(const ConvexPolygon& s, const ConvexPolygon& r,
                             std::span<const PlanarOutline> outlines, double eps,
                             CoplanarGroups& scratch);

}  // namespace gv
