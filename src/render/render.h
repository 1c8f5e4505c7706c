// Ray-cast pictures of a radiosity solution (paper §7.4): linear radiance per pixel from the
// leaf elements, seen one-sided through the camera, before tone mapping.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "radiosity/element_mesh.h"
#include "radiosity/hierarchical_radiosity.h"
#include "render/camera.h"
#include "render/element_bvh.h"

namespace gv {

/// How a hit element is coloured.
enum class Shading {
  Smooth,  ///< per-vertex radiosity (ElementMesh) interpolated across the fan triangle hit
  Flat,    ///< the leaf element's own radiosity: shows the mesh the solver refined
};

/// Sentinel: the pixel sees no element.
inline constexpr uint32_t kNoFace = std::numeric_limits<uint32_t>::max();

/// What the camera sees, one sample at each pixel centre.
struct RenderBuffers {
  int width = 0, height = 0;
  std::vector<Rgb> radiance;   ///< linear radiosity seen (radiosity units); 0 where nothing
  std::vector<float> depth;    ///< distance along Camera::forward(); +inf where nothing
  std::vector<uint32_t> face;  ///< ElementMesh face seen, or kNoFace
  size_t index(int x, int y) const { return static_cast<size_t>(y) * width + x; }
};

/// Casts one ray per pixel (rows in parallel) against the fronts of the leaf elements.
RenderBuffers renderRadiosity(const RadiosityResult& result, const ElementMesh& mesh,
                              const ElementBvh& bvh, const Camera& camera,
                              Shading shading = Shading::Smooth);

}  // namespace gv
