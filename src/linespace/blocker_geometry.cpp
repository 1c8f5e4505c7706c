// Blockers as planes plus Plücker edge lines. Paper §6.1.
#include "linespace/blocker_geometry.h"

namespace gv {

BlockerGeometry BlockerGeometry::of(const ConvexPolygon& polygon, uint32_t patch) {
  BlockerGeometry b;
  b.patch = patch;
  b.plane = polygon.plane;
  b.vertices = polygon.vertices;
  // The edge lines are taken through the vertices projected onto the plane. "Meets the polygon
  // iff the sides with all edges have one sign" holds for edges lying in its plane; a polygon a
  // hair out of true (within the importer's planarity tolerance) can have a short edge that
  // leaves the plane steeply, and that edge's side then flips for lines through the polygon's
  // middle, which would pass through the blocker: q3-oacmpdm3's bevel patch 3130, two corners
  // 1e-6 apart and one of them 7e-7 off its plane (the stabbing LP's rows had the same fault,
  // stabbing.cpp). Projected, the edges bound the polygon as it lies in its plane, moved by no
  // more than its own non-planarity.
  const size_t n = polygon.vertices.size();
  std::vector<Vec3> flat(n);
  for (size_t k = 0; k < n; ++k) {
    const Vec3& v = polygon.vertices[k];
    flat[k] = v - b.plane.normal * b.plane.distance(v);
  }
  b.edges.reserve(n);
  for (size_t k = 0; k < n; ++k)
    b.edges.push_back(FilteredLine::through(flat[k], flat[(k + 1) % n]));
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
