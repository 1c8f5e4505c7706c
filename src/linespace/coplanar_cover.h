// Joint occlusion by coplanar blockers (beyond the paper's §6.2; its Fig. 17 case): a wall made
// of several patches hides R from S although no single patch does. Decided in the blockers' plane
// from the crossing points of the extremal lines.
#pragma once

#include <span>

#include "geometry/tolerance.h"
#include "linespace/blocker_geometry.h"
#include "linespace/tube.h"

namespace gv {

/// True when every segment from S to R meets one of `blockers`, which must all lie between S and
/// R (BlockerVerdict::between) and in one plane: every vertex of each within tol.length() of the
/// first one's plane P (false otherwise).
///
/// Why it is sound: for a line ℓ in P, the side of line(s → r) with ℓ is bilinear in (s, r)
/// (tube.cpp) and, as every S → R line crosses P in the same direction, its sign is the side of
/// the crossing point with ℓ. So if all extremal lines cross P on one side of ℓ, all lines do:
/// the crossing points of all S → R lines lie in H = the convex hull of the extremal lines'
/// crossing points (the intersection of all halfplanes holding those). If the blockers cover H,
/// every segment crosses P (between its ends) inside some blocker. Coverage is decided by
/// subtracting each blocker from H as convex pieces; a piece thinner than tol.length() is
/// dropped (the tolerance policy: a gap that thin is not a gap), which is what makes patches
/// sharing an edge cover their union despite rounding.
bool coplanarBlockersCover(const Tube& tube, std::span<const BlockerGeometry* const> blockers,
                           const Tolerance& tol);

}  // namespace gv
