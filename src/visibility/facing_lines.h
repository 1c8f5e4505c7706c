// Lines between two convex polygons with no portal between them (both in one convex cell): the
// patch-to-patch test of paper §4.2 at sequence length two, decided without an LP.
#pragma once

#include "geometry/convex_polygon.h"

namespace gv {

/// Which ways a line leaving `source`'s front (crossing it along its normal) can then cross
/// `target`. A line crossing S along nS and then T from front to back exists iff some point q of
/// T lies in front of S's plane and some point p of S in front of T's plane: the line p→q is one
/// (direction q − p: nS·(q − p) = dS(q) > 0 and nT·(q − p) = −dT(p) < 0), and every such line
/// meets S and T at points with those signs. Back to front: a p behind T instead. "In front"
/// means by more than `eps` (so that lines grazing a plane within the length tolerance, which
/// block nothing of positive measure, do not count).
struct FacingLines {
  bool throughFront = false;  ///< a line crosses T from its front to its back
  bool throughBack = false;   ///< a line crosses T from its back to its front
};
FacingLines facingLines(const ConvexPolygon& source, const ConvexPolygon& target, double eps);

}  // namespace gv
