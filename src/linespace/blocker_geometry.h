// The linespace form of a blocker (paper §6.1): its support plane and its edges as Plücker lines,
// made once per patch and shared by every tube whose blocker list names it.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "geometry/convex_polygon.h"
#include "linespace/filtered_line.h"
#include "scene/scene.h"

namespace gv {

/// A convex blocker polygon prepared for side tests. A line crossing the blocker's plane meets the
/// closed polygon iff its sides with all edges have one sign (zeros allowed): positive when it
/// travels along `plane.normal`, negative against it.
struct BlockerGeometry {
  uint32_t patch = 0;
  Plane plane;
  std::vector<Vec3> vertices;       ///< counter-clockwise seen from the front
  std::vector<FilteredLine> edges;  ///< vertices[k] → vertices[k+1]

  static BlockerGeometry of(const ConvexPolygon& polygon, uint32_t patch);
};

/// BlockerGeometry of every patch of a scene, indexed by patch id.
class BlockerTable {
 public:
  explicit BlockerTable(const Scene& scene);
  /// From bare polygons: blocker id k is polygons[k].
  explicit BlockerTable(std::span<const ConvexPolygon> polygons);

  const BlockerGeometry& operator[](uint32_t patch) const { return blockers_[patch]; }
  size_t size() const { return blockers_.size(); }

 private:
  std::vector<BlockerGeometry> blockers_;
};

}  // namespace gv
