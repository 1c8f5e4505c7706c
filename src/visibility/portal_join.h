// Portals joined after the cells are merged (convex_merge.h): between two merged cells the BSP
// leaves many coplanar pieces of one opening (each the overlap of one leaf face on either side),
// and every piece is a branch of every search through that opening. On real levels the merged
// cells kept a third more portals than distinct openings (retrojam1_ericw.map: 3,593 portals, 2,443
// distinct (cells, BSP node) pairs), and the cell search tried every order of them.
//
// Pieces between the same two cells in the same plane are joined where the convex hull of two
// of them is their union (its area is the sum of theirs). Conservative even where it is not
// exactly the union: a portal that grows only lets more lines through, so no search loses one.
#pragma once

#include <cstddef>

#include "bsp/subdivision.h"

namespace gv {

/// What joinCoplanarPortals did.
struct PortalJoinStats {
  size_t portalsBefore = 0, portalsAfter = 0;
};

/// Joins, two at a time until no two can be, portals of `sub` linking the same two cells (same
/// back and front) on the same BSP plane when the convex hull of both has no more area than the
/// two (up to rounding): that hull is then their union, the new portal. The merged polygon keeps
/// the first piece's plane (its normal still points from back into front). Portals are renumbered
/// in the order of their first piece and each cell's portal list rebuilt (a merged cell's parts
/// list the joined portal their pieces went into). Deterministic.
PortalJoinStats joinCoplanarPortals(Subdivision& sub);

}  // namespace gv
