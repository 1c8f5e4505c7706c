// A camera inside a closed level (issue #18 item 4): seen from outside, a level of outward-facing
// brushes is a black box of shell faces that no light reaches, so the default picture of such a
// scene is taken from within its air, in the best-lit open space (paper §7.4's pictures).
#pragma once

#include <span>
#include <vector>

#include "geometry/vec3.h"
#include "raycast/embree_scene.h"
#include "render/camera.h"
#include "scene/scene.h"

namespace gv {

/// A candidate viewpoint in the air of a scene and what rays from it see.
struct AirPoint {
  Vec3 eye;
  double openness = 0;     ///< mean free distance of the survey rays (a miss: the diagonal)
  double light = 0;        ///< mean light (patchLight) of the fronts the survey rays hit first
  double litOpenness = 0;  ///< mean light·(free distance) of those fronts
  bool enclosed = false;   ///< every survey ray hits a front: no way out of the scene from here
};

/// Per-patch light used to score viewpoints: the luminance of the reflected radiosity (B − Ke)
/// when a solution is given (`patchRadiosity` has a value per patch), else an estimate of the
/// same from one bounce of direct light, emitter centroid to patch centroid, with occlusion.
/// Saturated as a picture's exposure is: divided by the kLightSaturation percentile of the lit
/// patches' values and clamped to 1.
std::vector<double> patchLight(const Scene& scene, const EmbreeScene& rays,
                               std::span<const Rgb> patchRadiosity);

/// Candidate viewpoints in the scene's air, at eye height: points of a grid over the box (about
/// kAirGridPoints) dropped along −up onto the first patch below, which must be a floor seen from
/// its front, then raised by kEyeHeightFraction of the free height above that floor. A point is
/// kept when, of kSurveyRays rays in directions spread over the sphere, at most 1/16 hit a back
/// (the point is inside a solid) and at most 1/16 miss everything (it is outside the scene).
std::vector<AirPoint> findAirPoints(const Scene& scene, const EmbreeScene& rays,
                                    std::span<const double> light, int upAxis);

/// The fraction of the pixels of `camera` that see the shell of a closed level rather than
/// its inside: a surface whose front faces out of the scene (rays from it into its front
/// half-space mostly escape: the roofs and outer walls of a level of outward brushes), or a
/// surface seen only through a back the renderer culls (the ceilings of a level whose faces all
/// face into its air). The picture is sampled on a coarse grid and its visible surfaces found
/// as the renderer finds them (backs culled, the cutaway applied). 0 when no pixel sees anything.
double shellFraction(const Scene& scene, const EmbreeScene& rays, const Camera& camera);

/// The interior view: among the air points at least as open as their median (a pocket of air
/// beside a lamp is bright and shows nothing), the best-scored distinct eyes (score: the mean over
/// the survey rays of (light + δ)·(free distance), δ a small constant so that openness decides in
/// the dark; lit surfaces far away count most), the point and horizontal direction (pitched
/// kInteriorPitchDegrees down) whose picture, sampled on a coarse grid with backs culled, scores
/// best the same way per pixel: a near wall filling half the view scores little. Field of view
/// kInteriorFovDegrees, `up` along upAxis, no cutaway; image size from `base`. `airPoints` must not
/// be empty.
Camera interiorCamera(const Scene& scene, const EmbreeScene& rays, std::span<const double> light,
                      const std::vector<AirPoint>& airPoints, int upAxis, const Camera& base);

/// About this many grid points are dropped to floors (more: slower, finds smaller rooms).
inline constexpr int kAirGridPoints = 4096;
/// Rays per candidate viewpoint.
inline constexpr int kSurveyRays = 64;
/// The eye stands this fraction of the free height above its floor.
inline constexpr double kEyeHeightFraction = 0.35;
/// Vertical field of view of the interior camera (degrees): wide, as in a game.
inline constexpr double kInteriorFovDegrees = 75;
/// The interior camera looks this much below the horizontal (degrees).
inline constexpr double kInteriorPitchDegrees = 8;

}  // namespace gv
