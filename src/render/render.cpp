// One primary ray per pixel against the leaf elements; smooth or flat radiosity.
#include "render/render.h"

#include <tbb/parallel_for.h>

#include <cmath>

namespace gv {

RenderBuffers renderRadiosity(const RadiosityResult& result, const ElementMesh& mesh,
                              const ElementBvh& bvh, const Camera& camera, Shading shading) {
  camera.validate();
  RenderBuffers out;
  out.width = camera.width;
  out.height = camera.height;
  const size_t n = static_cast<size_t>(out.width) * out.height;
  out.radiance.assign(n, Rgb{});
  out.depth.assign(n, INFINITY);
  out.face.assign(n, kNoFace);
  const Vec3 forward = camera.forward();
  tbb::parallel_for(0, out.height, [&](int y) {
    for (int x = 0; x < out.width; ++x) {
      const CameraRay ray = camera.ray(x + 0.5, y + 0.5);
      const std::optional<ElementHit> hit = bvh.firstFrontHit(ray);
      if (!hit) continue;
      const size_t i = out.index(x, y);
      out.face[i] = hit->face;
      out.depth[i] = static_cast<float>(hit->t * dot(ray.direction, forward));
      if (shading == Shading::Flat) {
        out.radiance[i] = result.elementRadiosity[mesh.faceElement[hit->face]];
      } else {
        Rgb c;
        for (int k = 0; k < 3; ++k) {
          const Rgb& v = mesh.vertexRadiosity[hit->vertices[k]];
          const double w = hit->weights[k];
          c = {c.r + w * v.r, c.g + w * v.g, c.b + w * v.b};
        }
        out.radiance[i] = {std::max(0.0, c.r), std::max(0.0, c.g), std::max(0.0, c.b)};
      }
    }
  });
  return out;
}

}  // namespace gv
