// Pairs of overlapping boxes found by a sweep along x: the candidates of the contact tests
// (linespace/contact_blockers.h, scene/contact_split.h). Near-linear when boxes overlap little.
#pragma once

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <vector>

#include "geometry/vec3.h"

namespace gv {

/// Calls visit(a, b) once for every unordered pair of distinct indices whose boxes overlap
/// within `eps` on all three axes (a, b in sweep order: a's box starts first along x).
template <class Visit>
void forEachOverlappingBoxPair(const std::vector<Aabb>& boxes, double eps, Visit&& visit) {
  std::vector<uint32_t> order(boxes.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(),
            [&](uint32_t a, uint32_t b) { return boxes[a].lo.x < boxes[b].lo.x; });
  for (size_t i = 0; i < order.size(); ++i) {
    const Aabb& a = boxes[order[i]];
    for (size_t j = i + 1; j < order.size() && boxes[order[j]].lo.x <= a.hi.x + eps; ++j) {
      const Aabb& b = boxes[order[j]];
      if (b.lo.y > a.hi.y + eps || a.lo.y > b.hi.y + eps || b.lo.z > a.hi.z + eps ||
          a.lo.z > b.hi.z + eps)
        continue;
      visit(order[i], order[j]);
    }
  }
}

}  // namespace gv
