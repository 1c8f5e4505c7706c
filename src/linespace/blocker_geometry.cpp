// Blockers as planes plus Plücker edge lines. Paper §6.1.
#include "linespace/blocker_geometry.h"

namespace gv {

BlockerGeometry BlockerGeometry::of(const ConvexPolygon& polygon, uint32_t patch) {
  BlockerGeometry b;
  b.patch = patch;
  b.plane = polygon.plane;
  b.vertices = polygon.vertices;
  const size_t n = polygon.vertices.size();
  b.edges.reserve(n);
  for (size_t k = 0; k < n; ++k)
    b.edges.push_back(FilteredLine::through(polygon.vertices[k], polygon.vertices[(k + 1) % n]));
  return b;
}

BlockerTable::BlockerTable(const Scene& scene) {
  blockers_.reserve(scene.patches.size());
  for (size_t p = 0; p < scene.patches.size(); ++p)
    blockers_.push_back(BlockerGeometry::of(scene.patches[p].polygon, static_cast<uint32_t>(p)));
}

BlockerTable::BlockerTable(std::span<const ConvexPolygon> polygons) {
  blockers_.reserve(polygons.size());
  for (size_t p = 0; p < polygons.size(); ++p)
    blockers_.push_back(BlockerGeometry::of(polygons[p], static_cast<uint32_t>(p)));
}

}  // namespace gv
