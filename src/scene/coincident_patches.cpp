// Groups of coincident patches by a hash of their rounded vertex sets (see coincident_patches.h).
#include "scene/coincident_patches.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "util/fnv_hash.h"

namespace gv {
namespace {

using RoundedVertices = std::vector<std::array<int64_t, 3>>;

struct RoundedVerticesHash {
  size_t operator()(const RoundedVertices& v) const {
    Fnv1a h;
    for (const auto& p : v)
      for (const int64_t c : p) h.integer(c);
    return static_cast<size_t>(h.value());
  }
};

}  // namespace

std::vector<uint32_t> coincidentPatchGroups(const Scene& scene) {
  const size_t n = scene.patches.size();
  std::vector<uint32_t> group(n);
  const double grid = scene.tolerance().planeOffset();
  // Patches with one rounded vertex set; each list is split by facing below.
  std::unordered_map<RoundedVertices, std::vector<uint32_t>, RoundedVerticesHash> byVertices;
  byVertices.reserve(n);
  for (size_t p = 0; p < n; ++p) {
    RoundedVertices key;
    for (const Vec3& v : scene.patches[p].polygon.vertices)
      key.push_back({std::llround(v.x / grid), std::llround(v.y / grid), std::llround(v.z / grid)});
    std::sort(key.begin(), key.end());
    std::vector<uint32_t>& same = byVertices[key];
    group[p] = static_cast<uint32_t>(p);
    const Vec3& normal = scene.patches[p].polygon.plane.normal;
    for (const uint32_t q : same)
      if (group[q] == q && dot(scene.patches[q].polygon.plane.normal, normal) > 0) {
        group[p] = q;
        break;
      }
    same.push_back(static_cast<uint32_t>(p));
  }
  return group;
}

}  // namespace gv
