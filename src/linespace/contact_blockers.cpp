// Patches covering parts of other patches by contact. Supports paper §6 (blocker lists).
#include "linespace/contact_blockers.h"

#include <algorithm>
#include <numeric>

#include "linespace/blocker_geometry.h"
#include "linespace/tube.h"

namespace gv {

std::vector<std::vector<uint32_t>> contactBlockers(const Scene& scene) {
  const Tolerance tol = scene.tolerance();
  const double eps = tol.length();
  const size_t n = scene.patches.size();
  std::vector<Aabb> boxes(n);
  for (size_t p = 0; p < n; ++p) boxes[p] = scene.patches[p].polygon.bounds();
  std::vector<uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](uint32_t a, uint32_t b) { return boxes[a].lo.x < boxes[b].lo.x; });
  std::vector<std::vector<uint32_t>> contacts(n);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t a = order[i];
    for (size_t j = i + 1; j < n && boxes[order[j]].lo.x <= boxes[a].hi.x + eps; ++j) {
      const uint32_t b = order[j];
      bool overlap = true;
      for (int axis = 1; axis < 3 && overlap; ++axis)
        overlap = boxes[b].lo[axis] <= boxes[a].hi[axis] + eps &&
                  boxes[a].lo[axis] <= boxes[b].hi[axis] + eps;
      if (!overlap) continue;
      const ConvexPolygon& pa = scene.patches[a].polygon;
      const ConvexPolygon& pb = scene.patches[b].polygon;
      if (contactCover(pa, BlockerGeometry::of(pb, b), tol) != ContactCover::None)
        contacts[a].push_back(b);
      if (contactCover(pb, BlockerGeometry::of(pa, a), tol) != ContactCover::None)
        contacts[b].push_back(a);
    }
  }
  for (auto& c : contacts) std::sort(c.begin(), c.end());
  return contacts;
}

}  // namespace gv
