// Settling a PUNT exactly (beyond the paper's §6.2): a blocker the line tests cannot decide is
// disjoint from an interaction iff no line stabs the portal sequence S, B, R (§4.1).
#pragma once

#include "geometry/tolerance.h"
#include "linespace/blocker_geometry.h"
#include "linespace/tube.h"

namespace gv {

/// True only when the stabbing LP proves that no line leaves S's front, crosses B, and reaches
/// R's front; then no light-carrying segment from S to R meets B and B may be dropped.
///
/// `travel` is the direction in which S → R segments cross B's plane relative to its normal: +1
/// or -1 when S and R lie on opposite sides of it (the order S, B, R along every such line is
/// then fixed, so the stabber's separating-plane clipping is valid), 0 when B's plane cuts S or
/// R: then both crossing directions are tried, each by the LP alone (its constraints do not
/// depend on the order of the portals; the clipping does). False when the LP finds a line or
/// cannot decide (conservative).
bool stabbingProvesDisjoint(const Tube& tube, const BlockerGeometry& b, int travel,
                            const Tolerance& tol);

}  // namespace gv
