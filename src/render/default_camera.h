// A sensible default viewpoint for any scene, so that `globalvis radiosity` can always draw its
// pictures (paper §7.4, Fig. 14) without being told where to look.
#pragma once

#include "render/camera.h"
#include "scene/scene.h"

namespace gv {

/// The default camera for `scene` at the given image size. Patches are one-sided and the
/// renderer culls their backs, so a camera outside a room sees through the walls whose fronts
/// face into it (a cutaway for free). Two cases, by the shape of the scene's bounding box:
///
/// - Flat (its shortest side under kFlatRatio times the middle one: a building, a level): that
///   axis is up. The roof is sawn off by a cutaway plane just below the highest ceiling (the
///   highest down-facing patch below the top of the box), and the camera looks down at the
///   centre at kBuildingElevationDegrees from the side, fitting the box's bounding sphere.
/// - Otherwise (a room, a Cornell box): +y is up (the OBJ convention). The camera looks
///   horizontally at the box's centre along the horizontal axis direction whose far side the
///   camera sees most of: the largest (area facing the camera − area facing away), which
///   prefers the open side of an open box; ties go to +z (the Cornell box's published camera
///   looks along +z). It stands back far enough that the near face of the box fills the view.
///   If what it sees in the middle is the outside of an outer wall (a closed building), a
///   cutaway perpendicular to the view removes that wall: a section through the near rooms.
Camera defaultCamera(const Scene& scene, int width = 800, int height = 600);

/// A box is "flat" when its shortest extent is below this fraction of its middle extent.
inline constexpr double kFlatRatio = 0.75;
/// How steeply the default camera of a flat scene looks down (degrees above the horizontal).
inline constexpr double kBuildingElevationDegrees = 55;
/// Default vertical field of view (degrees); near the Cornell box's published 39.3°.
inline constexpr double kDefaultFovDegrees = 40;

}  // namespace gv
