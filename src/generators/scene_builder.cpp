// Helpers for procedural scenes: add convex polygons, quads and axis-aligned boxes as patches.
#include "generators/scene_builder.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "geometry/convex_polygon.h"

namespace gv {

bool SceneBuilder::addPolygon(std::vector<Vec3> vertices, uint32_t material) {
  std::optional<ConvexPolygon> polygon = ConvexPolygon::fromVertices(std::move(vertices), tol_);
  if (!polygon) return false;
  scene_.patches.push_back(Patch{std::move(*polygon), material, kNoSourceFace});
  return true;
}

int SceneBuilder::addQuad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                          uint32_t material) {
  const Vec3 n = cross(b - a, c - a);
  const double nLength = length(n);
  const double diameter = std::max(distance(a, c), distance(b, d));
  // Planarity as the importer judges it: distance of d from plane(a, b, c) relative to the
  // quad's own size (geometry/tolerance.h, kRelativeModelEpsilon).
  const bool planar =
      nLength > 0 && std::abs(dot(n, d - a)) / nLength <= kRelativeModelEpsilon * diameter;
  if (planar) return addPolygon({a, b, c, d}, material) ? 1 : 0;
  int added = addPolygon({a, b, c}, material) ? 1 : 0;
  added += addPolygon({a, c, d}, material) ? 1 : 0;
  return added;
}

bool SceneBuilder::addAxisRect(int axis, bool positive, const Vec3& lo, const Vec3& hi,
                               uint32_t material) {
  // (u, v, axis) is a cyclic permutation of (x, y, z), so e_u x e_v = e_axis and the order
  // (u0,v0) (u1,v0) (u1,v1) (u0,v1) is counter-clockwise seen from +axis.
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  auto corner = [&](double cu, double cv) {
    Vec3 p;
    p[axis] = lo[axis];
    p[u] = cu;
    p[v] = cv;
    return p;
  };
  std::vector<Vec3> vertices{corner(lo[u], lo[v]), corner(hi[u], lo[v]), corner(hi[u], hi[v]),
                             corner(lo[u], hi[v])};
  if (!positive) std::reverse(vertices.begin(), vertices.end());
  return addPolygon(std::move(vertices), material);
}

int SceneBuilder::addBox(const Vec3& lo, const Vec3& hi, const BoxMaterials& materials,
                         uint32_t faces) {
  int added = 0;
  for (int axis = 0; axis < 3; ++axis) {
    for (int positive = 0; positive < 2; ++positive) {
      const int faceIndex = 2 * axis + positive;
      if ((faces & (1u << faceIndex)) == 0) continue;
      // The face lies at lo[axis] (facing -axis) or hi[axis] (facing +axis).
      Vec3 faceLo = lo, faceHi = hi;
      if (positive) faceLo[axis] = hi[axis];
      else faceHi[axis] = lo[axis];
      added += addAxisRect(axis, positive != 0, faceLo, faceHi, materials.face[faceIndex]) ? 1 : 0;
    }
  }
  return added;
}

}  // namespace gv
