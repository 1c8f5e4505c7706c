// Clusters of patches for hierarchical radiosity (Smits, Arvo & Greenberg 1994; Sillion 1995):
// a binary tree over the scene's patches, so that two far groups of patches exchange light
// through one link rather than through a link per pair. Without it every facing pair is linked
// at the top and the links grow as n² (a 6.4k-patch level: 8 M initial links, 88 s before any
// refinement). The tree is geometry only; the solver owns the links between its nodes.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "geometry/vec3.h"
#include "scene/scene.h"

namespace gv {

/// Sentinel cluster id.
inline constexpr uint32_t kNoCluster = std::numeric_limits<uint32_t>::max();

/// A node of the cluster tree: the patches order()[begin .. end), two children or none (a leaf
/// holds exactly one patch).
struct Cluster {
  Aabb box;                ///< of the patches' polygons
  double area = 0;         ///< Σ patch areas
  double reflectance = 0;  ///< the largest reflectance channel over the patches
  uint32_t begin = 0, end = 0;
  uint32_t left = kNoCluster, right = kNoCluster;
  bool isLeaf() const { return left == kNoCluster; }
  uint32_t size() const { return end - begin; }
};

/// The tree: node 0 is the root (absent for an empty scene); children have larger ids than their
/// parent. Built by splitting the patch centroids at the median of the box's longest axis, so the
/// depth is ⌈log2 n⌉ and every node's patches are a contiguous range of order().
class ClusterTree {
 public:
  explicit ClusterTree(const Scene& scene);

  const Cluster& operator[](uint32_t id) const { return nodes_[id]; }
  size_t size() const { return nodes_.size(); }
  std::span<const Cluster> nodes() const { return nodes_; }
  /// The patches, in the tree's order.
  std::span<const uint32_t> order() const { return order_; }
  std::span<const uint32_t> patchesOf(uint32_t id) const {
    return std::span(order_).subspan(nodes_[id].begin, nodes_[id].size());
  }
  /// The leaf holding patch `p`.
  uint32_t leafOf(uint32_t p) const { return leafOf_[p]; }
  /// A patch of cluster `id` picked with probability proportional to its area, `u` in [0, 1).
  uint32_t patchByArea(uint32_t id, double u) const;
  /// Running sums of the patch areas in the tree's order (n + 1 values, the first 0).
  std::span<const double> areaBefore() const { return areaBefore_; }

 private:
  uint32_t build(uint32_t begin, uint32_t end, const Scene& scene,
                 const std::vector<Vec3>& centroids, const std::vector<Aabb>& boxes,
                 const std::vector<double>& reflectance);

  std::vector<Cluster> nodes_;
  std::vector<uint32_t> order_;
  std::vector<uint32_t> leafOf_;
  std::vector<double> areaBefore_;  ///< per position of order(): Σ areas before it (n + 1 values)
};

/// The position in [begin, end) picked with probability proportional to its weight, given the
/// running sums of the weights `before` (before[i] = Σ weights of positions < i), `u` in [0, 1).
uint32_t positionByWeight(std::span<const double> before, uint32_t begin, uint32_t end, double u);

/// The smallest distance between two boxes (0 when they touch or overlap).
double boxDistance(const Aabb& a, const Aabb& b);

}  // namespace gv
