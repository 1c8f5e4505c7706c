// The interior camera of closed levels: air points found by rays, scored by light and openness.
#include "render/interior_camera.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>

#include "geometry/tolerance.h"

namespace gv {
namespace {

constexpr double kDegrees = std::numbers::pi / 180.0;
/// A first hit below the point counts as a floor when its normal is within ~45° of up.
constexpr double kFloorCosine = 0.7;
/// Backs culled on the way to a visible surface: more than this many in a row is a pile of
/// coincident faces, and the ray gives up.
constexpr int kMaxCulledBacks = 32;
/// Rays from a visible surface into its front half-space (about half of this many).
constexpr int kShellRays = 32;
/// The picture grid sampled for the shell test and for scoring interior views.
constexpr int kSampleColumns = 32, kSampleRows = 24;
/// Air points whose views are scored (the best by their own survey).
constexpr size_t kViewCandidates = 24;
/// Horizontal directions tried at each of them.
constexpr int kViewAzimuths = 24;
/// Patch-emitter pairs of the direct-light estimate at most (beyond: every k-th emitter, × k).
constexpr size_t kDirectLightPairs = size_t{1} << 22;
/// Patch light saturates (is 1) from this percentile of the lit patches' light up.
constexpr double kLightSaturation = 0.9;
/// δ of the scores, as a fraction of the saturated light: openness decides where none is seen.
constexpr double kLightFloor = 0.05;

double luminance(const Rgb& c) {
  return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
}

/// n directions spread evenly over the unit sphere (the Fibonacci spiral): deterministic.
std::vector<Vec3> sphereDirections(int n) {
  std::vector<Vec3> d;
  const double golden = std::numbers::pi * (3 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = 1 - (k + 0.5) * 2.0 / n, r = std::sqrt(std::max(0.0, 1 - z * z));
    d.push_back({r * std::cos(golden * k), r * std::sin(golden * k), z});
  }
  return d;
}

Vec3 axis(int a) {
  Vec3 v{};
  v[a] = 1;
  return v;
}

struct Seen {
  uint32_t patch = kNoPatch;
  double t = 0;
  bool throughBack = false;  ///< the ray passed a culled back on its way
};

/// The first front along the ray, as the renderer sees it (backs are culled).
std::optional<Seen> firstFront(const Scene& scene, const EmbreeScene& rays, Vec3 origin,
                               const Vec3& d) {
  double travelled = 0;
  uint32_t ignore = kNoPatch;
  for (int k = 0; k <= kMaxCulledBacks; ++k) {
    const std::optional<RayHit> hit = rays.firstHit(origin, d, INFINITY, ignore);
    if (!hit) return std::nullopt;
    travelled += hit->t;
    if (dot(scene.patches[hit->patch].polygon.normal(), d) < 0)
      return Seen{hit->patch, travelled, k > 0};
    origin = origin + hit->t * d;
    ignore = hit->patch;
  }
  return std::nullopt;
}

/// The mean of (light + floor)·distance over a set of rays: lit surfaces far away score most, a
/// near wall scores little however bright. Linear in the distance: with √distance a near wall in
/// full sky light outscored the view across q3-oa_dm2's courtyard.
struct RayTally {
  double sum = 0;
  int count = 0;
  void add(double l, double t, double lightFloor) {
    ++count;
    sum += (l + lightFloor) * t;
  }
  double score() const { return count == 0 ? 0 : sum / count; }
};

}  // namespace

namespace {

/// patchLight before saturation.
std::vector<double> rawLight(const Scene& scene, const EmbreeScene& rays,
                             std::span<const Rgb> patchRadiosity) {
  const size_t n = scene.patches.size();
  std::vector<double> light(n, 0.0);
  if (patchRadiosity.size() == n) {
    for (size_t k = 0; k < n; ++k) {
      const Rgb& ke = scene.materials[scene.patches[k].material].emission;
      const Rgb& b = patchRadiosity[k];
      light[k] = std::max(0.0, luminance(Rgb{b.r - ke.r, b.g - ke.g, b.b - ke.b}));
    }
    return light;
  }
  // No solution: one bounce of direct light, centroid to centroid (the point-to-point form
  // factor A_e cos cos / (π r²), r² at least A_e so that touching patches stay finite).
  std::vector<uint32_t> emitters;
  for (uint32_t k = 0; k < n; ++k)
    if (scene.materials[scene.patches[k].material].isEmitter()) emitters.push_back(k);
  if (emitters.empty()) return light;
  const size_t stride = std::max<size_t>(1, n * emitters.size() / kDirectLightPairs);
  const double offset = scene.tolerance().planeOffset();
  for (uint32_t k = 0; k < n; ++k) {
    const Patch& p = scene.patches[k];
    const Vec3 np = p.polygon.normal(), cp = p.polygon.centroid() + offset * np;
    const Rgb& kd = scene.materials[p.material].reflectance;
    Rgb e{};
    for (size_t i = k % stride; i < emitters.size(); i += stride) {
      const Patch& q = scene.patches[emitters[i]];
      const Vec3 nq = q.polygon.normal(), cq = q.polygon.centroid() + offset * nq;
      const Vec3 v = cq - cp;
      const double r2 = dot(v, v), cosP = dot(np, v), cosQ = -dot(nq, v);
      if (!(cosP > 0 && cosQ > 0) || rays.occluded(cp, cq, k, emitters[i])) continue;
      const double area = q.polygon.area();
      const double f = static_cast<double>(stride) * area * cosP * cosQ /
                       (std::numbers::pi * r2 * std::max(r2, area));
      const Rgb& ke = scene.materials[q.material].emission;
      e = Rgb{e.r + f * ke.r, e.g + f * ke.g, e.b + f * ke.b};
    }
    light[k] = luminance(Rgb{kd.r * e.r, kd.g * e.g, kd.b * e.b});
  }
  return light;
}

}  // namespace

std::vector<double> patchLight(const Scene& scene, const EmbreeScene& rays,
                               std::span<const Rgb> patchRadiosity) {
  std::vector<double> light = rawLight(scene, rays, patchRadiosity);
  // Saturate as the picture's exposure does: past a high percentile everything is white, so
  // that a near wall under a lamp does not outscore a well-lit hall.
  std::vector<double> lit;
  for (double l : light)
    if (l > 0) lit.push_back(l);
  if (lit.empty()) return light;
  const size_t rank = static_cast<size_t>(kLightSaturation * static_cast<double>(lit.size() - 1));
  std::nth_element(lit.begin(), lit.begin() + rank, lit.end());
  const double white = lit[rank];
  for (double& l : light) l = std::min(l / white, 1.0);
  return light;
}

std::vector<AirPoint> findAirPoints(const Scene& scene, const EmbreeScene& rays,
                                    std::span<const double> light, int upAxis) {
  const Aabb box = scene.bounds();
  const Vec3 e = box.extent(), up = axis(upAxis);
  const double cap = box.diagonal();
  // Grid steps of one size along every axis, about kAirGridPoints cells in all.
  const double step = std::cbrt(std::max(e.x, 1e-300) * std::max(e.y, 1e-300) *
                                std::max(e.z, 1e-300) / kAirGridPoints);
  int n[3];
  for (int a = 0; a < 3; ++a) n[a] = std::clamp(static_cast<int>(std::ceil(e[a] / step)), 1, 256);
  const std::vector<Vec3> directions = sphereDirections(kSurveyRays);
  std::vector<AirPoint> points;
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const Vec3 q{box.lo.x + (i + 0.5) * e.x / n[0], box.lo.y + (j + 0.5) * e.y / n[1],
                     box.lo.z + (k + 0.5) * e.z / n[2]};
        const std::optional<RayHit> floor = rays.firstHit(q, -up);
        if (!floor || dot(scene.patches[floor->patch].polygon.normal(), up) < kFloorCosine)
          continue;
        const Vec3 f = q - floor->t * up;
        const std::optional<RayHit> above = rays.firstHit(f, up, INFINITY, floor->patch);
        if (!above || dot(scene.patches[above->patch].polygon.normal(), up) > 0) continue;
        AirPoint p;
        p.eye = f + kEyeHeightFraction * above->t * up;
        int backs = 0, misses = 0;
        for (const Vec3& d : directions) {
          const std::optional<RayHit> hit = rays.firstHit(p.eye, d);
          const double t = hit ? std::min(hit->t, cap) : cap;
          p.openness += t;
          if (!hit) {
            ++misses;
          } else if (dot(scene.patches[hit->patch].polygon.normal(), d) >= 0) {
            ++backs;
          } else {
            p.light += light[hit->patch];
            p.litOpenness += light[hit->patch] * t;
          }
        }
        if (16 * backs > kSurveyRays || 16 * misses > kSurveyRays) continue;
        p.openness /= kSurveyRays;
        p.light /= kSurveyRays;
        p.litOpenness /= kSurveyRays;
        p.enclosed = backs == 0 && misses == 0;
        points.push_back(p);
      }
  return points;
}

double shellFraction(const Scene& scene, const EmbreeScene& rays, const Camera& camera) {
  const double offset = scene.tolerance().planeOffset();
  const std::vector<Vec3> directions = sphereDirections(kShellRays);
  int covered = 0, shell = 0;
  for (int row = 0; row < kSampleRows; ++row)
    for (int col = 0; col < kSampleColumns; ++col) {
      const CameraRay r = camera.ray((col + 0.5) * camera.width / kSampleColumns,
                                     (row + 0.5) * camera.height / kSampleRows);
      if (r.tNear > r.tFar) continue;
      const Vec3 start = r.origin + r.tNear * r.direction;
      const std::optional<Seen> seen = firstFront(scene, rays, start, r.direction);
      if (!seen) continue;
      ++covered;
      if (seen->throughBack) {
        ++shell;
        continue;
      }
      const Vec3 n = scene.patches[seen->patch].polygon.normal();
      const Vec3 x = start + seen->t * r.direction + offset * n;
      int out = 0, cast = 0;
      for (const Vec3& d : directions) {
        if (dot(d, n) <= 0) continue;
        ++cast;
        out += !rays.firstHit(x, d, INFINITY, seen->patch);
      }
      shell += 2 * out > cast;
    }
  return covered == 0 ? 0 : static_cast<double>(shell) / covered;
}

Camera interiorCamera(const Scene& scene, const EmbreeScene& rays, std::span<const double> light,
                      const std::vector<AirPoint>& airPoints, int upAxis, const Camera& base) {
  const Vec3 up = axis(upAxis);
  const double cap = scene.bounds().diagonal();
  double bestLight = 0;
  for (const AirPoint& p : airPoints) bestLight = std::max(bestLight, p.light);
  const double lightFloor = bestLight > 0 ? kLightFloor : 1;
  const auto surveyScore = [&](const AirPoint& p) {
    return p.litOpenness + lightFloor * p.openness;
  };
  // Large open spaces only: a pocket of air beside a lamp is the brightest place of a level and
  // shows nothing. Of the points at least as open as the median, the best distinct eyes.
  std::vector<double> openness;
  for (const AirPoint& p : airPoints) openness.push_back(p.openness);
  const auto middle = openness.begin() + static_cast<std::ptrdiff_t>(openness.size() / 2);
  std::nth_element(openness.begin(), middle, openness.end());
  std::vector<const AirPoint*> ranked;
  for (const AirPoint& p : airPoints)
    if (p.openness >= *middle) ranked.push_back(&p);
  std::sort(ranked.begin(), ranked.end(), [&](const AirPoint* a, const AirPoint* b) {
    return surveyScore(*a) > surveyScore(*b);
  });
  const double same = scene.tolerance().length();
  std::vector<const AirPoint*> candidates;
  for (const AirPoint* p : ranked) {
    if (candidates.size() == kViewCandidates) break;
    if (std::none_of(candidates.begin(), candidates.end(),
                     [&](const AirPoint* q) { return distance(p->eye, q->eye) <= same; }))
      candidates.push_back(p);
  }
  const int h0 = (upAxis + 1) % 3, h1 = (upAxis + 2) % 3;
  const double pitch = kInteriorPitchDegrees * kDegrees;
  Camera best = base;
  best.cutaway.reset();
  best.fovYDegrees = kInteriorFovDegrees;
  best.up = up;
  double bestScore = -1;
  for (const AirPoint* candidate : candidates) {
    Camera view = best;
    view.eye = candidate->eye;
    for (int a = 0; a < kViewAzimuths; ++a) {
      const double azimuth = 2 * std::numbers::pi * a / kViewAzimuths;
      const Vec3 horizontal = std::cos(azimuth) * axis(h0) + std::sin(azimuth) * axis(h1);
      view.target = view.eye + std::cos(pitch) * horizontal - std::sin(pitch) * up;
      RayTally tally;
      for (int row = 0; row < kSampleRows; ++row)
        for (int col = 0; col < kSampleColumns; ++col) {
          const CameraRay r = view.ray((col + 0.5) * view.width / kSampleColumns,
                                       (row + 0.5) * view.height / kSampleRows);
          const std::optional<Seen> seen = firstFront(scene, rays, r.origin, r.direction);
          if (!seen) {
            tally.add(0, 0, lightFloor);  // a crack to the outside: nothing to see
            continue;
          }
          tally.add(light[seen->patch], std::min(seen->t, cap), lightFloor);
        }
      const double score = tally.score();
      if (score > bestScore) bestScore = score, best = view;
    }
  }
  return best;
}

}  // namespace gv
