// A sensible default viewpoint for any scene, so that `globalvis radiosity` can always draw its
// pictures (paper §7.4, Fig. 14) without being told where to look.
#pragma once

#include <span>

#include "render/camera.h"
#include "scene/scene.h"

namespace gv {

/// The default camera for `scene` at the given image size. Patches are one-sided and the
/// renderer culls their backs, so a camera outside a room sees through the walls whose fronts
/// face into it (a cutaway for free). Two views from outside, by the shape of the scene's
/// bounding box, and one from inside for closed levels:
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
/// - A closed level (issue #18 item 4), seen from inside instead (render/interior_camera.h):
///   a flat scene whose view above shows more than kMaxShellFraction shell (faces towards the
///   void, as the roofs and outer walls of a Quake level of outward brushes, or floors seen
///   only through culled ceilings, as in a Doom level whose faces all face its air), or a
///   box-like scene most of whose air points see no way out (the camera would stand outside a
///   closed room). The camera stands in the air at eye height, in the best-lit open space, and
///   looks horizontally (slightly down) where the most lit surface is far away, with a wide
///   field of view. Up is the flat axis; for a box-like level the axis the emitters face down
///   along, else its shortest axis (a Quake level converted z up whose box is not quite flat).
///   The light is the solution's when given, else one bounce of direct light from the emitters.
///
/// The Cornell box and the generated offices keep their outside views (their shell fractions
/// are ~0 and ~0.17; the Cornell box's air sees out of its open front).
Camera defaultCamera(const Scene& scene, int width = 800, int height = 600);
/// The same, with the solution's per-patch radiosity (RadiosityResult::patchRadiosity) to find
/// the best-lit open space of a closed level; an empty span scores by emission alone.
Camera defaultCamera(const Scene& scene, std::span<const Rgb> patchRadiosity, int width,
                     int height);

/// A box is "flat" when its shortest extent is below this fraction of its middle extent.
inline constexpr double kFlatRatio = 0.75;
/// How steeply the default camera of a flat scene looks down (degrees above the horizontal).
inline constexpr double kBuildingElevationDegrees = 55;
/// A flat scene whose default picture shows more shell than this (fraction of the pixels that
/// see something) is a closed level, looked at from inside.
inline constexpr double kMaxShellFraction = 0.5;
/// Default vertical field of view (degrees); near the Cornell box's published 39.3°.
inline constexpr double kDefaultFovDegrees = 40;

}  // namespace gv
