// Ray casting against a whole Scene with Embree 3: the brute-force visibility oracle that
// HSA91's `rays` mode samples (paper §6.3 contrasts it with blocker lists) and that
// `globalvis verify` checks conservative visibility against.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "geometry/vec3.h"
#include "scene/scene.h"

// Embree's handles, forward-declared so that users of this header need not see rtcore.h.
typedef struct RTCDeviceTy* RTCDevice;
typedef struct RTCSceneTy* RTCScene;

namespace gv {

/// Sentinel: "ignore no patch" in the queries below.
inline constexpr uint32_t kNoPatch = std::numeric_limits<uint32_t>::max();

/// The nearest patch a ray meets.
struct RayHit {
  uint32_t patch = kNoPatch;  ///< index into Scene::patches
  double t = 0;               ///< ray parameter of the hit: point = origin + t * direction
};

/// An Embree BVH over every patch of a scene (each convex patch fan-triangulated), built once in
/// the constructor and read-only afterwards: every query is const and safe to call from many
/// threads at once.
///
/// Precision: Embree works in single precision. Coordinates are translated to the centre of the
/// scene's box before conversion so that precision is relative to the scene's size, not to its
/// distance from the origin; the scene is built with Embree's robust (watertight) mode so that a
/// ray through a shared edge of two triangles of one patch, or of two abutting patches, is not
/// lost between them. Patches are two-sided to rays (a ray meets a patch from either side):
/// occlusion is physical, whatever the patch's orientation.
class EmbreeScene {
 public:
  /// Builds the BVH. Throws std::runtime_error if Embree fails (out of memory, bad device).
  explicit EmbreeScene(const Scene& scene);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  /// True when the open segment from `from` to `to` meets a patch other than `ignoreA` and
  /// `ignoreB` (pass kNoPatch for none). The end points themselves are excluded: the segment is
  /// parameterised from `from` to `to` over [0, 1] and tested over (0, 1), with no offset, so
  /// that a segment between points on two patches is never blocked by its own end patches when
  /// those are ignored.
  bool occluded(const Vec3& from, const Vec3& to, uint32_t ignoreA = kNoPatch,
                uint32_t ignoreB = kNoPatch) const;

  /// The first patch other than `ignore` met by the ray origin + t * direction, t in (0, tMax];
  /// nullopt if none. `direction` need not be unit length (t is in its units).
  std::optional<RayHit> firstHit(const Vec3& origin, const Vec3& direction,
                                 double tMax = std::numeric_limits<double>::infinity(),
                                 uint32_t ignore = kNoPatch) const;

  /// Number of patches in the BVH (those of the scene it was built from).
  size_t patchCount() const { return patchCount_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  Vec3 origin_;                           ///< subtracted from coordinates before float conversion
  std::vector<uint32_t> patchOfTriangle_;  ///< Embree primitive id -> patch id
  size_t patchCount_ = 0;
};

}  // namespace gv
