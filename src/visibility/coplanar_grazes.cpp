// Nearly coplanar patches facing each other (see coplanar_grazes.h).
#include "visibility/coplanar_grazes.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace gv {
namespace {

/// Puts `patch` in the sorted seen list with the front flag set; true when the pair was
/// not already seen front to front.
bool markSeenFront(std::vector<uint32_t>& list, uint32_t patch) {
  auto it = std::lower_bound(list.begin(), list.end(), seenEntry(patch, 0));
  if (it != list.end() && seenPatch(*it) == patch) {
    if (seenFlags(*it) & kSeenFront) return false;
    *it = seenEntry(patch, seenFlags(*it) | kSeenFront);
    return true;
  }
  list.insert(it, seenEntry(patch, kSeen | kSeenFront));
  return true;
}

}  // namespace

size_t addCoplanarGrazes(const Scene& scene, const PlaneSet& planes, const Tolerance& tol,
                         std::vector<PatchSearchResult>& seen) {
  const size_t n = std::min(scene.patches.size(), planes.patchCount());
  // Per merged plane and facing, its patches grouped by their own plane equation: patches with
  // equal equations are coplanar exactly and never face each other.
  using Equation = std::tuple<double, double, double, double>;
  std::map<std::pair<uint32_t, bool>, std::map<Equation, std::vector<uint32_t>>> groups;
  for (uint32_t p = 0; p < n; ++p) {
    const Plane& own = scene.patches[p].polygon.plane;
    const PatchPlane& merged = planes.of(p);
    groups[{merged.plane, merged.facesAlong}]
          [{own.normal.x, own.normal.y, own.normal.z, own.offset}]
              .push_back(p);
  }
  const double eps = tol.length();
  size_t added = 0;
  for (const auto& [key, byEquation] : groups) {
    if (byEquation.size() < 2) continue;
    for (auto a = byEquation.begin(); a != byEquation.end(); ++a) {
      for (auto b = std::next(a); b != byEquation.end(); ++b) {
        for (uint32_t s : a->second) {
          for (uint32_t t : b->second) {
            if (!canFace(scene.patches[s].polygon, scene.patches[t].polygon, eps)) continue;
            const bool newS = markSeenFront(seen[s].seen, t);
            const bool newT = markSeenFront(seen[t].seen, s);
            added += newS || newT;
          }
        }
      }
    }
  }
  return added;
}

}  // namespace gv
