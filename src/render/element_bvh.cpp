// Embree BVH over leaf elements with back-face culling by the elements' own normals.
#include "render/element_bvh.h"

#include <embree3/rtcore.h>

#include <stdexcept>
#include <string>

namespace gv {
namespace {

/// Rejects hits on the back of an element: its front normal must face the ray (n·d < 0).
void cullBackFaces(const RTCFilterFunctionNArguments* args) {
  const auto* normals = static_cast<const float*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const float* n = normals + 3 * prim;
    const float facing = n[0] * RTCRayN_dir_x(args->ray, args->N, i) +
                         n[1] * RTCRayN_dir_y(args->ray, args->N, i) +
                         n[2] * RTCRayN_dir_z(args->ray, args->N, i);
    if (!(facing < 0)) args->valid[i] = 0;
  }
}

void throwOnError(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                             std::to_string(static_cast<int>(e)) + ")");
}

}  // namespace

ElementBvh::ElementBvh(const ElementMesh& mesh, const ElementTree& tree) : mesh_(mesh) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  Aabb box;
  for (const Vec3& p : mesh.positions) box.add(p);
  origin_ = box.empty() ? Vec3{} : box.center();

  size_t triangleCount = 0;
  for (const auto& f : mesh.faces) triangleCount += f.size() - 2;
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  if (triangleCount > 0) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangleCount));
    throwOnError(device_, "allocating geometry buffers");
    for (size_t v = 0; v < mesh.positions.size(); ++v) {
      const Vec3 q = mesh.positions[v] - origin_;
      vertices[3 * v + 0] = static_cast<float>(q.x);
      vertices[3 * v + 1] = static_cast<float>(q.y);
      vertices[3 * v + 2] = static_cast<float>(q.z);
    }
    faceOfTriangle_.reserve(triangleCount);
    fanOfTriangle_.reserve(triangleCount);
    normals_.reserve(3 * triangleCount);
    size_t t = 0;
    for (size_t f = 0; f < mesh.faces.size(); ++f) {
      const std::vector<uint32_t>& face = mesh.faces[f];
      const Vec3 n = tree[mesh.faceElement[f]].polygon.normal();
      for (uint32_t k = 1; k + 1 < face.size(); ++k, ++t) {
        indices[3 * t + 0] = face[0];
        indices[3 * t + 1] = face[k];
        indices[3 * t + 2] = face[k + 1];
        faceOfTriangle_.push_back(static_cast<uint32_t>(f));
        fanOfTriangle_.push_back(k);
        normals_.insert(normals_.end(), {static_cast<float>(n.x), static_cast<float>(n.y),
                                         static_cast<float>(n.z)});
      }
    }
    rtcSetGeometryUserData(geometry, normals_.data());
    rtcSetGeometryIntersectFilterFunction(geometry, &cullBackFaces);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene_);
  throwOnError(device_, "building the element BVH");
}

ElementBvh::~ElementBvh() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

std::optional<ElementHit> ElementBvh::firstFrontHit(const CameraRay& ray) const {
  if (faceOfTriangle_.empty() || !(ray.tNear <= ray.tFar)) return std::nullopt;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  const Vec3 o = ray.origin - origin_;
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(ray.direction.x);
  rh.ray.dir_y = static_cast<float>(ray.direction.y);
  rh.ray.dir_z = static_cast<float>(ray.direction.z);
  rh.ray.tnear = static_cast<float>(ray.tNear);
  rh.ray.tfar = static_cast<float>(std::min(ray.tFar, 3.0e38));
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  ElementHit hit;
  const uint32_t tri = rh.hit.primID;
  hit.face = faceOfTriangle_[tri];
  hit.t = rh.ray.tfar;
  const std::vector<uint32_t>& face = mesh_.faces[hit.face];
  const uint32_t k = fanOfTriangle_[tri];
  hit.vertices = {face[0], face[k], face[k + 1]};
  // Embree's (u, v) weight the triangle's second and third vertices.
  const double u = rh.hit.u, v = rh.hit.v;
  hit.weights = {1.0 - u - v, u, v};
  return hit;
}

}  // namespace gv
