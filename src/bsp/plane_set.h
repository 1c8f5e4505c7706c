// The distinct support planes of a scene's patches: coplanar patches (within the model
// tolerance, either facing) share one plane, which the BSP then splits on once. Paper §3.
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/plane.h"
#include "geometry/tolerance.h"
#include "scene/scene.h"

namespace gv {

/// Where a patch lies: the merged plane it belongs to and which way it faces it.
struct PatchPlane {
  uint32_t plane = 0;      ///< index into PlaneSet::planes()
  bool facesAlong = true;  ///< true when the patch's front is the plane's front (normals agree)
};

/// The merged support planes of a set of patches.
///
/// Two patches share a plane when their normals agree up to sign within Tolerance::normalCos()
/// and the patch's centroid lies within Tolerance::planeOffset() of the plane. Merging is not
/// transitive: each plane is the support plane of the first patch that created it (its normal
/// and offset are that patch's, oriented as that patch faces), and later patches join it only when
/// they are within tolerance of that representative, so no plane drifts by chaining.
/// Lookup is by hashing quantised normal and offset: O(patches) expected.
class PlaneSet {
 public:
  PlaneSet() = default;
  /// Merges the support planes of `scene.patches`, in patch order.
  static PlaneSet fromScene(const Scene& scene, const Tolerance& tol);

  const std::vector<Plane>& planes() const { return planes_; }
  /// Plane of patch `patch` (an index into the scene's patches).
  const PatchPlane& of(uint32_t patch) const { return patchPlanes_[patch]; }
  size_t patchCount() const { return patchPlanes_.size(); }

 private:
  std::vector<Plane> planes_;
  std::vector<PatchPlane> patchPlanes_;
};

}  // namespace gv
