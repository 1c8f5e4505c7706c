// The cluster tree: median splits of the patch centroids.
#include "radiosity/patch_clusters.h"

#include <algorithm>
#include <cmath>

namespace gv {

ClusterTree::ClusterTree(const Scene& scene) {
  const auto n = static_cast<uint32_t>(scene.patches.size());
  std::vector<Vec3> centroids(n);
  std::vector<Aabb> boxes(n);
  std::vector<double> reflectance(n);
  for (uint32_t p = 0; p < n; ++p) {
    const Patch& patch = scene.patches[p];
    centroids[p] = patch.polygon.centroid();
    boxes[p] = patch.polygon.bounds();
    const Rgb& r = scene.materials.at(patch.material).reflectance;
    reflectance[p] = std::max({r.r, r.g, r.b});
  }
  order_.resize(n);
  for (uint32_t p = 0; p < n; ++p) order_[p] = p;
  leafOf_.assign(n, kNoCluster);
  if (n == 0) return;
  nodes_.reserve(2 * static_cast<size_t>(n) - 1);
  build(0, n, scene, centroids, boxes, reflectance);
  areaBefore_.assign(n + 1, 0.0);
  for (uint32_t i = 0; i < n; ++i)
    areaBefore_[i + 1] = areaBefore_[i] + scene.patches[order_[i]].polygon.area();
}

uint32_t ClusterTree::build(uint32_t begin, uint32_t end, const Scene& scene,
                            const std::vector<Vec3>& centroids, const std::vector<Aabb>& boxes,
                            const std::vector<double>& reflectance) {
  const auto id = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  Cluster c;
  c.begin = begin;
  c.end = end;
  Aabb centers;
  for (uint32_t i = begin; i < end; ++i) {
    const uint32_t p = order_[i];
    c.box.add(boxes[p]);
    c.area += scene.patches[p].polygon.area();
    c.reflectance = std::max(c.reflectance, reflectance[p]);
    centers.add(centroids[p]);
  }
  if (end - begin == 1) {
    leafOf_[order_[begin]] = id;
  } else {
    const Vec3 e = centers.extent();
    const int axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
    const uint32_t mid = begin + (end - begin) / 2;
    // Ties broken by patch id, so the tree does not depend on the library's nth_element.
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](uint32_t a, uint32_t b) {
                       const double ka = centroids[a][axis], kb = centroids[b][axis];
                       return ka != kb ? ka < kb : a < b;
                     });
    c.left = build(begin, mid, scene, centroids, boxes, reflectance);
    c.right = build(mid, end, scene, centroids, boxes, reflectance);
  }
  nodes_[id] = c;
  return id;
}

uint32_t ClusterTree::patchByArea(uint32_t id, double u) const {
  const Cluster& c = nodes_[id];
  return order_[positionByWeight(areaBefore_, c.begin, c.end, u)];
}

uint32_t positionByWeight(std::span<const double> before, uint32_t begin, uint32_t end, double u) {
  const double lo = before[begin], hi = before[end];
  const double target = lo + u * (hi - lo);
  // The last position whose running sum is at or below the target.
  const auto it = std::upper_bound(before.begin() + begin + 1, before.begin() + end, target);
  return static_cast<uint32_t>(it - before.begin()) - 1;
}

double boxDistance(const Aabb& a, const Aabb& b) {
  double sum = 0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, a.lo[k] - b.hi[k], b.lo[k] - a.hi[k]});
    sum += gap * gap;
  }
  return std::sqrt(sum);
}

}  // namespace gv
