// Pinhole camera: frame, primary rays with the cutaway, projection.
#include "render/camera.h"

#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace gv {
namespace {

double tanHalfFov(const Camera& c) {
  return std::tan(0.5 * c.fovYDegrees * std::numbers::pi / 180.0);
}

}  // namespace

Vec3 Camera::forward() const {
  return normalize(target - eye);
}
Vec3 Camera::right() const {
  return normalize(cross(forward(), up));
}
Vec3 Camera::trueUp() const {
  return cross(right(), forward());
}

CameraRay Camera::ray(double x, double y) const {
  const double t = tanHalfFov(*this);
  const double aspect = static_cast<double>(width) / static_cast<double>(height);
  const double sx = (2.0 * x / width - 1.0) * t * aspect;
  const double sy = (1.0 - 2.0 * y / height) * t;
  CameraRay r;
  r.origin = eye;
  r.direction = normalize(forward() + sx * right() + sy * trueUp());
  r.tNear = 0;
  r.tFar = INFINITY;
  if (cutaway) {
    // Kept: distance(eye + t d) = d0 + t·dn <= 0.
    const double d0 = cutaway->distance(eye);
    const double dn = dot(cutaway->normal, r.direction);
    if (dn == 0) {
      if (d0 > 0) r.tFar = -1;
    } else if (dn < 0) {
      r.tNear = std::max(0.0, -d0 / dn);
    } else {
      r.tFar = -d0 / dn;  // negative when the eye is cut away and the ray leaves: sees nothing
      if (r.tFar < 0) r.tNear = 1, r.tFar = 0;
    }
  }
  return r;
}

CameraFrame Camera::frame() const {
  CameraFrame f;
  f.eye = eye;
  f.forward = forward();
  f.right = right();
  f.up = trueUp();
  f.halfHeight = tanHalfFov(*this);
  f.halfWidth = f.halfHeight * static_cast<double>(width) / static_cast<double>(height);
  f.width = width;
  f.height = height;
  return f;
}

std::optional<PixelPoint> Camera::project(const Vec3& p) const {
  return frame().project(p);
}

void Camera::validate() const {
  if (!isFinite(eye) || !isFinite(target) || !isFinite(up))
    throw std::invalid_argument("camera: non-finite coordinates");
  if (lengthSquared(target - eye) == 0)
    throw std::invalid_argument("camera: eye and target coincide");
  if (lengthSquared(cross(target - eye, up)) <=
      1e-12 * lengthSquared(target - eye) * lengthSquared(up))
    throw std::invalid_argument("camera: up is parallel to the viewing direction");
  if (!(fovYDegrees > 0 && fovYDegrees < 180))
    throw std::invalid_argument("camera: field of view must be in (0, 180) degrees");
  if (width < 1 || height < 1) throw std::invalid_argument("camera: image size must be >= 1");
}

Camera parseCamera(const std::string& text, Camera camera) {
  std::vector<double> values;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string field = text.substr(start, comma - start);
    double v = 0;
    const char* first = field.data();
    const char* last = field.data() + field.size();
    while (first < last && *first == ' ') ++first;
    const auto [end, ec] = std::from_chars(first, last, v);
    if (ec != std::errc() || end != last || first == last)
      throw std::invalid_argument("camera: '" + field + "' is not a number in '" + text +
                                  "' (expected ex,ey,ez,tx,ty,tz[,fov])");
    values.push_back(v);
    start = comma + 1;
  }
  if (values.size() != 6 && values.size() != 7)
    throw std::invalid_argument("camera: expected 6 or 7 numbers (ex,ey,ez,tx,ty,tz[,fov]), got " +
                                std::to_string(values.size()));
  camera.eye = {values[0], values[1], values[2]};
  camera.target = {values[3], values[4], values[5]};
  if (values.size() == 7) camera.fovYDegrees = values[6];
  camera.cutaway.reset();
  // Keep the given up unless it is parallel to the new view; then fall back to another axis.
  const Vec3 f = camera.target - camera.eye;
  if (lengthSquared(cross(f, camera.up)) <= 1e-6 * lengthSquared(f) * lengthSquared(camera.up))
    camera.up = std::abs(f.z) < std::abs(f.y) ? Vec3{0, 0, 1} : Vec3{0, 1, 0};
  camera.validate();
  return camera;
}

}  // namespace gv
