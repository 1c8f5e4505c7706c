// Depth-tested 3D segments by dense sampling of the clipped segment.
#include "render/segment_drawing.h"

#include <algorithm>
#include <cmath>

namespace gv {
namespace {

/// Points closer to the eye than this fraction of the segment's extent are clipped (a near
/// plane, so that projection never divides by ~0).
constexpr double kNearFraction = 1e-6;

/// Clips the parameter range [t0, t1] of p(t) = a + t (b − a) to {f(p) <= 0} for affine f given
/// by its values fa, fb at the ends. Returns false when nothing is left.
bool clipAffine(double fa, double fb, double& t0, double& t1) {
  if (fa > 0 && fb > 0) return false;
  if (fa <= 0 && fb <= 0) return true;
  const double t = fa / (fa - fb);
  if (fa > 0)
    t0 = std::max(t0, t);
  else
    t1 = std::min(t1, t);
  return t0 <= t1;
}

}  // namespace

void rasterizeSegment(const Camera& camera, const CameraFrame& frame,
                      const std::vector<float>& depth, const Vec3& a, const Vec3& b, bool depthTest,
                      const std::function<void(int x, int y)>& visit) {
  double t0 = 0, t1 = 1;
  const Vec3& forward = frame.forward;
  const double nearDepth =
      kNearFraction * std::max(distance(camera.eye, a), distance(camera.eye, b));
  // Near plane: depth(p) >= nearDepth, i.e. nearDepth − depth(p) <= 0.
  if (!clipAffine(nearDepth - dot(a - camera.eye, forward),
                  nearDepth - dot(b - camera.eye, forward), t0, t1))
    return;
  if (camera.cutaway &&
      !clipAffine(camera.cutaway->distance(a), camera.cutaway->distance(b), t0, t1))
    return;
  const Vec3 p0 = a + t0 * (b - a), p1 = a + t1 * (b - a);
  const std::optional<PixelPoint> q0 = frame.project(p0), q1 = frame.project(p1);
  if (!q0 || !q1) return;
  // The projection is a 2D segment q(s) = q0 + s (q1 − q0); keep the part over the image
  // (Liang–Barsky), then step through it at half-pixel spacing; 1/depth is affine in s.
  double s0 = 0, s1 = 1;
  const double dx = q1->x - q0->x, dy = q1->y - q0->y;
  const auto clip = [&](double p, double q) {  // keeps s with p·s <= q
    if (p == 0) return q >= 0;
    const double r = q / p;
    if (p < 0)
      s0 = std::max(s0, r);
    else
      s1 = std::min(s1, r);
    return s0 <= s1;
  };
  if (!clip(-dx, q0->x) || !clip(dx, camera.width - q0->x) || !clip(-dy, q0->y) ||
      !clip(dy, camera.height - q0->y))
    return;
  const double pixels = (s1 - s0) * std::hypot(dx, dy);
  const int steps = static_cast<int>(std::ceil(2.0 * pixels)) + 1;
  long lastPixel = -1;
  for (int k = 0; k <= steps; ++k) {
    const double s = s0 + (s1 - s0) * k / steps;
    const double pointDepth = 1.0 / ((1 - s) / q0->depth + s / q1->depth);
    const auto x = static_cast<long>(std::floor(q0->x + s * dx));
    const auto y = static_cast<long>(std::floor(q0->y + s * dy));
    if (x < 0 || y < 0 || x >= camera.width || y >= camera.height) continue;
    const long pixel = y * camera.width + x;
    if (pixel == lastPixel) continue;
    lastPixel = pixel;
    if (depthTest && pointDepth > depth[pixel] * (1 + kSegmentDepthSlack)) continue;
    visit(static_cast<int>(x), static_cast<int>(y));
  }
}

void drawSegment(RgbImage& image, const Camera& camera, const std::vector<float>& depth,
                 const Vec3& a, const Vec3& b, const SegmentStyle& style) {
  rasterizeSegment(camera, camera.frame(), depth, a, b, style.depthTest, [&](int x, int y) {
    uint8_t* c = image.at(x, y);
    for (int ch = 0; ch < 3; ++ch)
      c[ch] = static_cast<uint8_t>(
          std::lround((1 - style.opacity) * c[ch] + style.opacity * style.colour[ch]));
  });
}

}  // namespace gv
