// Default viewpoints: a roofless bird's-eye view of flat scenes, a view into the open side of
// box-like ones, and a view from inside closed levels.
#include "render/default_camera.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

#include "raycast/embree_scene.h"
#include "render/interior_camera.h"

namespace gv {
namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;
/// A patch counts as a ceiling when its normal is within ~25° of straight down.
constexpr double kCeilingCosine = 0.9;
/// The cut sits this fraction of the scene's height below the highest ceiling, so that the
/// ceiling and what hangs just under it (light panels) are removed, walls and furniture kept.
constexpr double kCutBelowCeiling = 0.03;
/// Direction scores closer than this fraction of the total patch area are ties.
constexpr double kOpenSideFraction = 0.01;
/// A first hit this close to the box's near face (fraction of its depth) is an outer wall.
constexpr double kShellFraction = 0.02;
/// The emitters' area vector picks the up axis when this fraction of it lies along one axis.
constexpr double kUpAxisDominance = 0.7;
/// Margin around the fitted box (fraction of the fitting distance).
constexpr double kFitMargin = 1.05;

Vec3 axis(int a) {
  Vec3 v{};
  v[a] = 1;
  return v;
}

Camera flatSceneCamera(const Scene& scene, const Aabb& box, int upAxis, Camera c) {
  const Vec3 up = axis(upAxis);
  const double top = box.hi[upAxis], bottom = box.lo[upAxis];
  const Tolerance tol = scene.tolerance();
  double ceiling = -INFINITY;
  for (const Patch& p : scene.patches) {
    if (dot(p.polygon.normal(), up) > -kCeilingCosine) continue;
    const double h = dot(p.polygon.centroid(), up);
    if (h < top - tol.length()) ceiling = std::max(ceiling, h);
  }
  double cut = top;
  if (std::isfinite(ceiling) && ceiling > bottom) {
    cut = ceiling - kCutBelowCeiling * (top - bottom);
    c.cutaway = Plane{up, cut};
  }
  Aabb kept = box;
  kept.hi[upAxis] = cut;
  // Horizontal axes of the plan: look from the -h1 side, turned 30° towards -h0.
  const int h0 = (upAxis + 1) % 3, h1 = (upAxis + 2) % 3;
  const double azimuth = 30 * kDegrees, elevation = kBuildingElevationDegrees * kDegrees;
  const Vec3 horizontal = std::cos(azimuth) * axis(h1) + std::sin(azimuth) * axis(h0);
  const Vec3 toEye = std::cos(elevation) * (-horizontal) + std::sin(elevation) * up;
  const double radius = 0.5 * kept.diagonal();
  const double aspect = static_cast<double>(c.width) / c.height;
  const double halfFov = 0.5 * c.fovYDegrees * kDegrees;
  const double halfFovX = std::atan(std::tan(halfFov) * aspect);
  c.target = kept.center();
  c.up = up;
  // The bounding sphere always fits; bisect down to the nearest distance at which every corner
  // of the kept box still projects inside the image shrunk by the margin.
  const auto fits = [&](double distance) {
    Camera t = c;
    t.eye = c.target + distance * toEye;
    const CameraFrame f = t.frame();
    for (int k = 0; k < 8; ++k) {
      const Vec3 corner{(k & 1) ? kept.hi.x : kept.lo.x, (k & 2) ? kept.hi.y : kept.lo.y,
                        (k & 4) ? kept.hi.z : kept.lo.z};
      const std::optional<PixelPoint> p = f.project(corner);
      if (!p) return false;
      const double mx = 0.5 * c.width * (1 - 1 / kFitMargin);
      const double my = 0.5 * c.height * (1 - 1 / kFitMargin);
      if (p->x < mx || p->x > c.width - mx || p->y < my || p->y > c.height - my) return false;
    }
    return true;
  };
  double far = kFitMargin * radius / std::sin(std::min(halfFov, halfFovX)), near = 0;
  if (fits(far)) {
    for (int i = 0; i < 50; ++i) {
      const double mid = 0.5 * (near + far);
      (fits(mid) ? far : near) = mid;
    }
  }
  c.eye = c.target + far * toEye;
  return c;
}

/// A closed building seen from outside shows its outer wall, lit by nothing. When the centre
/// ray's first hit is the front of a patch on the box face nearest the camera (within
/// kShellFraction of the box's depth), cut away everything up to the first patch behind it
/// whose back faces the camera: the inner face of that wall. The cut is perpendicular to the
/// view, so the picture is a section through the near rooms.
void peelOuterShell(const Scene& scene, const Aabb& box, int depthAxis, Camera& c) {
  const Tolerance tol = scene.tolerance();
  const Vec3 o = c.eye, d = c.forward();
  struct Hit {
    double t;
    bool front;
  };
  std::vector<Hit> hits;
  for (const Patch& p : scene.patches) {
    const Plane& plane = p.polygon.plane;
    const double dn = dot(plane.normal, d);
    if (dn == 0) continue;
    const double t = -plane.distance(o) / dn;
    if (t > 0 && p.polygon.contains(o + t * d, tol)) hits.push_back({t, dn < 0});
  }
  std::sort(hits.begin(), hits.end(), [](const Hit& a, const Hit& b) { return a.t < b.t; });
  if (hits.empty() || !hits[0].front) return;
  const double nearFace = d[depthAxis] > 0 ? box.lo[depthAxis] : box.hi[depthAxis];
  const double extent = box.extent()[depthAxis];
  if (std::abs((o + hits[0].t * d)[depthAxis] - nearFace) > kShellFraction * extent) return;
  for (const Hit& h : hits) {
    if (h.front) continue;
    c.cutaway = Plane::through(o + (h.t + tol.length()) * d, -d);
    return;
  }
}

/// The up axis of a box-like scene seen from inside: lights hang under ceilings, so the axis
/// along which the emitters' area vector points (downwards) when it clearly dominates; else the
/// box's shortest axis, as for flat scenes (a Quake level converted z up whose box is not quite
/// flat, lit by trims on every side of its light brushes, whose area vector is zero).
int interiorUpAxis(const Scene& scene, int shortestAxis) {
  Vec3 down{};
  for (const Patch& p : scene.patches)
    if (scene.materials[p.material].isEmitter())
      down = down + p.polygon.area() * p.polygon.normal();
  int a = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(down[k]) > std::abs(down[a])) a = k;
  return down[a] < 0 && -down[a] > kUpAxisDominance * length(down) ? a : shortestAxis;
}

Camera boxSceneCamera(const Scene& scene, const Aabb& box, Camera c) {
  const int upAxis = 1;
  const std::array<Vec3, 4> directions{axis(2), -axis(2), axis(0), -axis(0)};
  // A closed shell's area vector is zero, so every direction scores ~0 there: only a clear
  // difference (kOpenSideFraction of the total area) beats the earlier direction.
  size_t best = 0;
  double bestScore = -INFINITY;
  const double margin = kOpenSideFraction * scene.totalArea();
  for (size_t k = 0; k < directions.size(); ++k) {
    double score = 0;
    for (const Patch& p : scene.patches)
      score -= p.polygon.area() * dot(p.polygon.normal(), directions[k]);
    if (k == 0 || score > bestScore + margin) bestScore = score, best = k;
  }
  const Vec3 d = directions[best];
  const int depthAxis = best < 2 ? 2 : 0, widthAxis = best < 2 ? 0 : 2;
  const Vec3 e = box.extent();
  const double aspect = static_cast<double>(c.width) / c.height;
  const double tanY = std::tan(0.5 * c.fovYDegrees * kDegrees);
  const double distance =
      kFitMargin * std::max(0.5 * e[upAxis] / tanY, 0.5 * e[widthAxis] / (tanY * aspect)) +
      0.5 * e[depthAxis];
  c.target = box.center();
  c.eye = c.target - distance * d;
  c.up = axis(upAxis);
  peelOuterShell(scene, box, depthAxis, c);
  return c;
}

}  // namespace

Camera defaultCamera(const Scene& scene, int width, int height) {
  return defaultCamera(scene, {}, width, height);
}

Camera defaultCamera(const Scene& scene, std::span<const Rgb> patchRadiosity, int width,
                     int height) {
  Camera c;
  c.width = width;
  c.height = height;
  c.fovYDegrees = kDefaultFovDegrees;
  const Aabb box = scene.bounds();
  if (box.empty() || !(box.diagonal() > 0)) {
    c.eye = {0, 0, 1};
    c.target = {0, 0, 0};
    return c;
  }
  const Vec3 e = box.extent();
  std::array<int, 3> order{0, 1, 2};
  std::sort(order.begin(), order.end(), [&](int a, int b) { return e[a] < e[b]; });
  const bool flat = e[order[0]] < kFlatRatio * e[order[1]];
  const int upAxis = flat ? order[0] : interiorUpAxis(scene, order[0]);
  const Camera outside =
      flat ? flatSceneCamera(scene, box, upAxis, c) : boxSceneCamera(scene, box, c);
  // A closed level from outside: a flat one's picture is mostly shell (roofs and outer walls
  // facing the void, lit by nothing, or floors seen through culled ceilings); a box-like one is
  // a closed room the camera stands outside of (its air points see no way out). Either way,
  // look from inside.
  const EmbreeScene rays(scene);
  if (flat && shellFraction(scene, rays, outside) <= kMaxShellFraction) return outside;
  const std::vector<double> light = patchLight(scene, rays, patchRadiosity);
  const std::vector<AirPoint> air = findAirPoints(scene, rays, light, upAxis);
  if (air.empty()) return outside;
  const auto enclosed =
      std::count_if(air.begin(), air.end(), [](const AirPoint& p) { return p.enclosed; });
  if (!flat && 2 * static_cast<size_t>(enclosed) < air.size()) return outside;
  return interiorCamera(scene, rays, light, air, upAxis, c);
}

}  // namespace gv
