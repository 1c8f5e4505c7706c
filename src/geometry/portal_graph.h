// A portal graph: convex cells joined by convex portals, nothing else (paper §4's adjacency
// graph). The neutral input of the cell PVS (visibility/cell_pvs.h): a Quake .prt file
// (quake/prt_portal_graph.h) and the BSP subdivision (visibility/cell_visibility.cpp) both convert
// to it. It lives here, below both, so that neither stage has to include the other.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/vec3.h"

namespace gv {

/// A convex portal between two cells.
struct GraphPortal {
  /// Vertices in order around the portal; their counter-clockwise (Newell) normal points from
  /// `back` into `front`.
  std::vector<Vec3> winding;
  uint32_t back = 0, front = 0;
};

/// Cells 0..cellCount-1 and the portals between them.
struct PortalGraph {
  size_t cellCount = 0;
  std::vector<GraphPortal> portals;
};

}  // namespace gv
