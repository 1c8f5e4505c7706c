// Patches covering parts of other patches by contact. Supports paper §6 (blocker lists).
#include "linespace/contact_blockers.h"

#include <algorithm>

#include "geometry/box_sweep.h"
#include "linespace/blocker_geometry.h"
#include "linespace/tube.h"

namespace gv {

std::vector<std::vector<uint32_t>> contactBlockers(const Scene& scene) {
  const Tolerance tol = scene.tolerance();
  const double eps = tol.length();
  const size_t n = scene.patches.size();
  std::vector<Aabb> boxes(n);
  for (size_t p = 0; p < n; ++p) boxes[p] = scene.patches[p].polygon.bounds();
  std::vector<std::vector<uint32_t>> contacts(n);
  forEachOverlappingBoxPair(boxes, eps, [&](uint32_t a, uint32_t b) {
    const ConvexPolygon& pa = scene.patches[a].polygon;
    const ConvexPolygon& pb = scene.patches[b].polygon;
    if (contactCover(pa, BlockerGeometry::of(pb, b), tol) != ContactCover::None)
      contacts[a].push_back(b);
    if (contactCover(pb, BlockerGeometry::of(pa, a), tol) != ContactCover::None)
      contacts[b].push_back(a);
  });
  for (auto& c : contacts) std::sort(c.begin(), c.end());
  return contacts;
}

}  // namespace gv
