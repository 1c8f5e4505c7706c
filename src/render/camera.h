// A pinhole camera for the pictures of a radiosity solution (paper §7.4, Fig. 14): primary rays,
// projection of points to pixels, and an optional cutaway half-space.
#pragma once

#include <optional>
#include <string>

#include "geometry/plane.h"
#include "geometry/vec3.h"

namespace gv {

/// A primary ray: points origin + t·direction for t in [tNear, tFar]; `direction` is unit.
struct CameraRay {
  Vec3 origin, direction;
  double tNear = 0, tFar = 0;  ///< tNear > tFar: the ray sees nothing (wholly cut away)
};

/// A point projected into the image: pixel coordinates (x right, y down, pixel (i, j) covers
/// [i, i+1) x [j, j+1)) and its depth along the viewing direction.
struct PixelPoint {
  double x = 0, y = 0;
  double depth = 0;  ///< distance along `forward`; > 0 in front of the camera
};

/// A camera's orthonormal frame and image scale, computed once for many projections.
struct CameraFrame {
  Vec3 eye, forward, right, up;
  double halfWidth = 1, halfHeight = 1;  ///< tan of the half field of view, across and up
  int width = 1, height = 1;
  /// Where world point p lands in the image; nullopt when p is not in front of the eye.
  std::optional<PixelPoint> project(const Vec3& p) const {
    const Vec3 v = p - eye;
    const double depth = dot(v, forward);
    if (!(depth > 0)) return std::nullopt;
    const double sx = dot(v, right) / (depth * halfWidth);
    const double sy = dot(v, up) / (depth * halfHeight);
    return PixelPoint{0.5 * (sx + 1.0) * width, 0.5 * (1.0 - sy) * height, depth};
  }
};

/// A perspective pinhole camera. Image rows go down, columns right; pixel (i, j) is sampled at
/// its centre (i + 0.5, j + 0.5). `up` need only be non-parallel to the view direction.
struct Camera {
  Vec3 eye{0, 0, 0};
  Vec3 target{0, 0, -1};
  Vec3 up{0, 1, 0};
  double fovYDegrees = 40;  ///< full vertical field of view
  int width = 800, height = 600;
  /// Cutaway: when set, everything strictly in front of this plane (distance > 0) is removed, as
  /// if the scene were sawn along it; rays start where they enter the kept half-space. The
  /// default camera of an enclosed building uses it to lift the roof off.
  std::optional<Plane> cutaway;

  /// The orthonormal frame: forward (eye → target), right, and the true up of the image.
  Vec3 forward() const;
  Vec3 right() const;
  Vec3 trueUp() const;
  CameraFrame frame() const;

  /// The ray through image position (x, y) in pixel units (use i + 0.5 for a pixel centre),
  /// clipped to the cutaway half-space.
  CameraRay ray(double x, double y) const;
  /// Where world point p lands in the image; nullopt when p is not in front of the eye.
  std::optional<PixelPoint> project(const Vec3& p) const;
  /// True when p survives the cutaway (no cutaway: always).
  bool kept(const Vec3& p) const { return !cutaway || cutaway->distance(p) <= 0; }
  /// Throws std::invalid_argument when the camera is unusable (eye == target, up parallel to
  /// the view, field of view outside (0, 180), image size < 1).
  void validate() const;
};

/// Parses `ex,ey,ez,tx,ty,tz[,fov]` (eye, target, optional vertical field of view in degrees)
/// into `camera`, keeping its image size and up vector and clearing its cutaway. Throws
/// std::invalid_argument with a message naming the problem.
Camera parseCamera(const std::string& text, Camera camera = {});

}  // namespace gv
