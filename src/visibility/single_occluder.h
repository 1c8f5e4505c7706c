// A pair hidden whole behind one polygon: every segment from S to R crosses the interior of one
// blocker. Exact and cheap (|S| x |R| points against the blocker's edges), it drops pairs the
// portal searches had to keep: occluders inside a cell (no portal separates S from R) and the
// answers of searches that ran past their budget.
#pragma once

#include <span>

#include "geometry/convex_polygon.h"

namespace gv {

/// True when S and R lie strictly on opposite sides of `blocker`'s plane (every vertex beyond
/// `margin`) and every segment between them crosses that plane inside `blocker` shrunk by
/// `margin`: then no segment from S to R is free. The segments between S and R cross the plane
/// in conv(S ∪ R) ∩ plane, the convex hull of where the segments between their vertices cross
/// it, so testing those |S| |R| points is exact. A blocker whose vertices stray from its plane
/// (within the importer's planarity tolerance) is taken as the slab they span: S and R beyond
/// it, the crossings of both its faces inside the outline. `margin`: a line within it of the
/// blocker's outline counts as passing by (the contact tolerance of the contract's checks).
bool hidesWhole(const ConvexPolygon& blocker, const ConvexPolygon& s, const ConvexPolygon& r,
                double margin);

/// hidesWhole in parts, for callers that test one blocker against many pairs (and one S against
/// many blockers): the blocker's slab once, each polygon's side of it once, the crossings last.
/// hidesWhole(b, s, r, m) == (ss = sideOfSlab(b, slab, s, m)) != 0 &&
///   sideOfSlab(b, slab, r, m) == -ss && crossesInside(b, slab, s, r, m), slab = occluderSlab(b).
struct OccluderSlab {
  double scale = 0;    ///< the length of the plane's normal
  double dev = 0;      ///< the vertices' largest distance from the plane, in its units
  bool usable = true;  ///< false for a degenerate plane or a non-finite vertex: hides nothing
};
OccluderSlab occluderSlab(const ConvexPolygon& blocker);
/// +1 (front) or -1 (back) when every vertex of `p` lies beyond the blocker's slab by more than
/// `margin`, else 0.
int sideOfSlab(const ConvexPolygon& blocker, const OccluderSlab& slab, const ConvexPolygon& p,
               double margin);
/// For S and R on opposite sides of the slab: every segment between them crosses both faces of
/// the slab inside the outline shrunk by `margin`.
bool crossesInside(const ConvexPolygon& blocker, const OccluderSlab& slab, const ConvexPolygon& s,
                   const ConvexPolygon& r, double margin);

/// An edge of a blocker as an inward half-plane across its plane: n × (b[i+1] − b[i]), which
/// points inside for a counter-clockwise outline seen from the front, and its length.
struct InwardEdge {
  Vec3 inward;
  double length = 0;
};
/// The blocker's edges into `out`, one per vertex (`out` holds as many); false when one is
/// degenerate (zero length): such a blocker hides nothing.
bool inwardEdges(const ConvexPolygon& blocker, std::span<InwardEdge> out);
/// crossesInside with the blocker's inwardEdges prepared (callers that test one blocker against
/// many pairs keep them): the same answer, without m cross products and square roots per call.
bool crossesInside(const ConvexPolygon& blocker, const OccluderSlab& slab,
                   std::span<const InwardEdge> edges, const ConvexPolygon& s,
                   const ConvexPolygon& r, double margin);

}  // namespace gv
