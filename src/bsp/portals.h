// The portal stage of the subdivision: coaffine patches per boundary face and the portals
// between leaf cells. Paper §3 ("Next, the portals ... are explicitly constructed").
#pragma once

#include "bsp/subdivision.h"

namespace gv {

/// Fills, for `sub.cells` made from `sub.tree.leaves` (shape copied, faces sized to match), each
/// face's coaffine patches and portals, each cell's portal list, and `sub.portals`.
/// Per BSP node: the leaf faces on its plane from the back side are intersected with those from
/// the front side (found through a grid of their 2D bounds), and the node's coplanar patch
/// fragments are subtracted from each overlap.
void buildPortals(Subdivision& sub);

}  // namespace gv
