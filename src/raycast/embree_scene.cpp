// Embree 3 BVH over a scene's patches: occlusion of segments and first hits of rays.
#include "raycast/embree_scene.h"

#include <embree3/rtcore.h>

#include <stdexcept>
#include <string>

namespace gv {
namespace {

/// Our intersect context: Embree's, followed by what the filter callback needs. Embree passes
/// the address of the first member back to the callback, which casts it to this (the standard
/// Embree 3 idiom for per-query filter data; the struct is standard-layout).
struct IgnoreContext {
  RTCIntersectContext base;
  const uint32_t* patchOfTriangle;
  uint32_t ignoreA;
  uint32_t ignoreB;
};

/// Rejects hits on the ignored patches, so a segment between two patches is not stopped by its
/// own end points (an offset would instead miss blockers that touch the end patches, such as a
/// wall meeting the floor).
void ignoreFilter(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const IgnoreContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t patch = ctx->patchOfTriangle[RTCHitN_primID(args->hit, args->N, i)];
    if (patch == ctx->ignoreA || patch == ctx->ignoreB) args->valid[i] = 0;
  }
}

void throwOnError(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE)
    throw std::runtime_error(std::string("Embree: ") + what + " failed (error " +
                             std::to_string(static_cast<int>(e)) + ")");
}

IgnoreContext makeContext(const uint32_t* patchOfTriangle, uint32_t a, uint32_t b) {
  IgnoreContext ctx{};
  rtcInitIntersectContext(&ctx.base);
  ctx.patchOfTriangle = patchOfTriangle;
  ctx.ignoreA = a;
  ctx.ignoreB = b;
  if (a != kNoPatch || b != kNoPatch) ctx.base.filter = &ignoreFilter;
  return ctx;
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene) : patchCount_(scene.patches.size()) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  origin_ = scene.bounds().center();
  if (!isFinite(origin_)) origin_ = Vec3{};

  size_t vertexCount = 0, triangleCount = 0;
  for (const Patch& p : scene.patches) {
    vertexCount += p.polygon.vertices.size();
    triangleCount += p.polygon.vertices.size() - 2;
  }
  scene_ = rtcNewScene(device_);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
  rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
  if (triangleCount > 0) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangleCount));
    throwOnError(device_, "allocating geometry buffers");
    patchOfTriangle_.reserve(triangleCount);
    size_t v = 0, t = 0;
    for (size_t id = 0; id < scene.patches.size(); ++id) {
      const std::vector<Vec3>& poly = scene.patches[id].polygon.vertices;
      const auto first = static_cast<unsigned>(v);
      for (const Vec3& p : poly) {
        const Vec3 q = p - origin_;
        vertices[3 * v + 0] = static_cast<float>(q.x);
        vertices[3 * v + 1] = static_cast<float>(q.y);
        vertices[3 * v + 2] = static_cast<float>(q.z);
        ++v;
      }
      // A fan: the patch is convex, so every fan triangle lies inside it.
      for (unsigned k = 1; k + 1 < poly.size(); ++k) {
        indices[3 * t + 0] = first;
        indices[3 * t + 1] = first + k;
        indices[3 * t + 2] = first + k + 1;
        patchOfTriangle_.push_back(static_cast<uint32_t>(id));
        ++t;
      }
    }
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene_);
  throwOnError(device_, "building the BVH");
}

EmbreeScene::~EmbreeScene() {
  if (scene_) rtcReleaseScene(scene_);
  if (device_) rtcReleaseDevice(device_);
}

bool EmbreeScene::occluded(const Vec3& from, const Vec3& to, uint32_t ignoreA,
                           uint32_t ignoreB) const {
  if (patchOfTriangle_.empty()) return false;
  IgnoreContext ctx = makeContext(patchOfTriangle_.data(), ignoreA, ignoreB);
  const Vec3 o = from - origin_;
  const Vec3 d = to - from;
  RTCRay ray{};
  ray.org_x = static_cast<float>(o.x);
  ray.org_y = static_cast<float>(o.y);
  ray.org_z = static_cast<float>(o.z);
  ray.dir_x = static_cast<float>(d.x);
  ray.dir_y = static_cast<float>(d.y);
  ray.dir_z = static_cast<float>(d.z);
  ray.tnear = 0.0f;
  ray.tfar = 1.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.time = 0.0f;
  ray.flags = 0;
  rtcOccluded1(scene_, &ctx.base, &ray);
  // Embree marks an occluded ray by setting tfar to -inf.
  return ray.tfar < 0.0f;
}

std::optional<RayHit> EmbreeScene::firstHit(const Vec3& origin, const Vec3& direction, double tMax,
                                            uint32_t ignore) const {
  if (patchOfTriangle_.empty()) return std::nullopt;
  IgnoreContext ctx = makeContext(patchOfTriangle_.data(), ignore, kNoPatch);
  const Vec3 o = origin - origin_;
  RTCRayHit rh{};
  rh.ray.org_x = static_cast<float>(o.x);
  rh.ray.org_y = static_cast<float>(o.y);
  rh.ray.org_z = static_cast<float>(o.z);
  rh.ray.dir_x = static_cast<float>(direction.x);
  rh.ray.dir_y = static_cast<float>(direction.y);
  rh.ray.dir_z = static_cast<float>(direction.z);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tMax >= static_cast<double>(std::numeric_limits<float>::max())
                    ? std::numeric_limits<float>::infinity()
                    : static_cast<float>(tMax);
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.time = 0.0f;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &ctx.base, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return RayHit{patchOfTriangle_[rh.hit.primID], static_cast<double>(rh.ray.tfar)};
}

}  // namespace gv
