// Ray casting against the refined leaf elements of a radiosity solution (Embree 3), one-sided:
// only the fronts of elements are seen, as light only leaves and arrives there (paper §7.4).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "radiosity/element_mesh.h"
#include "radiosity/element_tree.h"
#include "render/camera.h"

typedef struct RTCDeviceTy* RTCDevice;
typedef struct RTCSceneTy* RTCScene;

namespace gv {

/// Where a ray first meets the front of a leaf element.
struct ElementHit {
  uint32_t face = 0;                 ///< index into ElementMesh::faces
  double t = 0;                      ///< ray parameter (unit direction: distance from the origin)
  std::array<uint32_t, 3> vertices;  ///< mesh vertices of the fan triangle hit
  std::array<double, 3> weights;     ///< barycentric weights of the hit point in that triangle
};

/// An Embree BVH over the faces of an ElementMesh, each convex face fan-triangulated. Back faces
/// are culled by an intersection filter that compares the ray with the element's own plane
/// normal (not Embree's triangle winding), so a ray passes through a patch seen from behind.
/// Coordinates are centred on the mesh's box before float conversion, as in EmbreeScene. Built
/// once; queries are const and thread-safe. The mesh and tree must outlive it.
class ElementBvh {
 public:
  /// Throws std::runtime_error if Embree fails.
  ElementBvh(const ElementMesh& mesh, const ElementTree& tree);
  ~ElementBvh();
  ElementBvh(const ElementBvh&) = delete;
  ElementBvh& operator=(const ElementBvh&) = delete;

  /// The nearest front-facing hit with t in [ray.tNear, ray.tFar]; nullopt if none.
  std::optional<ElementHit> firstFrontHit(const CameraRay& ray) const;

 private:
  const ElementMesh& mesh_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
  Vec3 origin_;
  std::vector<uint32_t> faceOfTriangle_;
  std::vector<uint32_t> fanOfTriangle_;  ///< k: the triangle (0, k, k+1) of its face
  std::vector<float> normals_;           ///< 3 per triangle: the element's front normal
};

}  // namespace gv
