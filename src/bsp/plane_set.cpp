// Merging the support planes of patches within the model tolerance. Paper §3.
#include "bsp/plane_set.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace gv {
namespace {

/// A quantised (normal, offset): the hash bucket of a plane.
using Key = std::array<int64_t, 4>;

struct KeyHash {
  size_t operator()(const Key& k) const {
    uint64_t h = 1469598103934665603ull;
    for (int64_t v : k) h = (h ^ static_cast<uint64_t>(v)) * 1099511628211ull;
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

}  // namespace

PlaneSet PlaneSet::fromScene(const Scene& scene, const Tolerance& tol) {
  PlaneSet set;
  set.patchPlanes_.reserve(scene.patches.size());

  // Largest angle between merged normals. A patch joins a plane when every vertex lies within
  // the offset tolerance of it (the model tolerance's own test), with normals agreeing to within
  // this looser angle: the fitted normal of a small face whose vertices are off by a rounding
  // error wobbles by that error over its diameter, far more than the plane tolerance's angle
  // (a 1 m face with vertices 2e-5 out: 2e-5 rad), and two such faces of one wall left as
  // separate planes 1e-5 apart make the BSP cut slivers between them that the searches do not
  // cross (a room's floor and wall then miss each other: tests/visibility/messy_office_test).
  constexpr double kMergeAngle = 1e-3;
  const double angle = kMergeAngle;
  const double mergeCos = std::cos(kMergeAngle);
  // The distance from the origin of the farthest patch point: the offsets of two planes whose
  // normals differ by `angle` differ by up to angle * radius more than their centroids do.
  double radius = 0;
  for (const Patch& p : scene.patches) {
    for (const Vec3& v : p.polygon.vertices) radius = std::max(radius, length(v));
  }
  // Buckets twice the tolerance wide: any plane within tolerance of a query is in the query's
  // bucket or the neighbour on the side the query is nearer to, per coordinate (2^4 probes).
  const double normalCell = 2.0 * angle;
  const double offsetCell = 2.0 * (tol.planeOffset() + angle * radius);
  auto coords = [&](const Vec3& n, double d) {
    return std::array<double, 4>{n.x / normalCell, n.y / normalCell, n.z / normalCell,
                                 d / offsetCell};
  };
  auto keyOf = [](const std::array<double, 4>& c) {
    Key k;
    for (int i = 0; i < 4; ++i) k[i] = static_cast<int64_t>(std::floor(c[i]));
    return k;
  };

  auto withinOffset = [&](const Plane& rep, const ConvexPolygon& poly) {
    for (const Vec3& v : poly.vertices)
      if (!(std::abs(rep.distance(v)) <= tol.planeOffset())) return false;
    return true;
  };
  std::unordered_map<Key, std::vector<uint32_t>, KeyHash> buckets;
  buckets.reserve(scene.patches.size());
  for (const Patch& patch : scene.patches) {
    const Vec3 n = patch.polygon.plane.normal;
    const Vec3 c = patch.polygon.centroid();
    const double d = dot(n, c);
    int64_t found = -1;
    bool along = true;
    // Look for a representative facing either way.
    for (int sign = 1; sign >= -1 && found < 0; sign -= 2) {
      const Vec3 ns = n * static_cast<double>(sign);
      const std::array<double, 4> q = coords(ns, d * sign);
      const Key base = keyOf(q);
      for (int mask = 0; mask < 16 && found < 0; ++mask) {
        Key k = base;
        for (int i = 0; i < 4; ++i) {
          if (mask & (1 << i)) k[i] += (q[i] - std::floor(q[i]) < 0.5) ? -1 : 1;
        }
        auto it = buckets.find(k);
        if (it == buckets.end()) continue;
        for (uint32_t id : it->second) {
          const Plane& rep = set.planes_[id];
          if (dot(rep.normal, ns) >= mergeCos && withinOffset(rep, patch.polygon)) {
            found = id;
            along = sign > 0;
            break;
          }
        }
      }
    }
    if (found < 0) {
      found = static_cast<int64_t>(set.planes_.size());
      set.planes_.push_back(patch.polygon.plane);
      buckets[keyOf(coords(n, patch.polygon.plane.offset))].push_back(static_cast<uint32_t>(found));
    }
    set.patchPlanes_.push_back({static_cast<uint32_t>(found), along});
  }
  return set;
}

}  // namespace gv
