// Drawing 3D line segments over a rendered picture (the links and element edges of the paper's
// Fig. 14), depth-tested against what the camera sees.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "render/camera.h"
#include "render/png_image.h"

namespace gv {

/// Relative depth slack of the depth test (one pixel's sample of a surface differs slightly from
/// the depth of a point on it elsewhere in the pixel, most at grazing angles).
inline constexpr double kSegmentDepthSlack = 0.01;

/// Calls visit(x, y) for each pixel segment a–b covers: the segment is clipped to the part in
/// front of the eye and kept by the camera's cutaway, its projection to the image, then stepped
/// at half-pixel spacing (perspective-correct), each pixel visited at most once. With
/// `depthTest`, a point is skipped when it lies behind the surface seen at its pixel:
/// depth > sceneDepth · (1 + kSegmentDepthSlack), so a segment on a surface (an element edge,
/// a link's end at an element centroid) stays visible where that surface is seen. `depth` is
/// RenderBuffers::depth (camera.width × camera.height).
void rasterizeSegment(const Camera& camera, const CameraFrame& frame,
                      const std::vector<float>& depth, const Vec3& a, const Vec3& b, bool depthTest,
                      const std::function<void(int x, int y)>& visit);

/// How drawSegment draws.
struct SegmentStyle {
  std::array<uint8_t, 3> colour{255, 255, 255};
  double opacity = 1;  ///< each covered pixel becomes (1 − opacity)·old + opacity·colour
  bool depthTest = true;
};

/// Blends segment a–b into `image` (camera-sized) with rasterizeSegment's pixels.
void drawSegment(RgbImage& image, const Camera& camera, const std::vector<float>& depth,
                 const Vec3& a, const Vec3& b, const SegmentStyle& style);

}  // namespace gv
