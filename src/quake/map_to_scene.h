// Quake .map → Scene: brushes become convex solids, their visible faces (after removing the parts
// hidden inside or against other solids) become patches, light entities small emitting cubes.
#pragma once

#include <string>

#include "quake/map_file.h"
#include "scene/scene.h"

namespace gv {

/// Choices of the conversion (see docs in map_to_scene.cpp's header and README).
struct MapImportOptions {
  /// Movers (func_door, func_door_secret, func_plat, func_button, func_train, func_rotating,
  /// func_explosive ...) as solid geometry in their spawn position, as ericw-tools `light` lights
  /// them. When false they are left out (an open level, no doors).
  bool includeMovers = true;
  /// Edge of the emitting cube put at each light entity's origin, in map units (1 unit ~ 1 inch).
  double lightCubeSize = 8;
};

/// What the conversion kept and dropped (the skipped and dropped counts also as warnings).
struct MapImportStats {
  size_t entities = 0;
  size_t brushesIn = 0;              ///< every brush of every entity
  size_t solidBrushes = 0;           ///< brushes turned into solids (sky brushes included)
  size_t skyBrushes = 0;             ///< solid brushes with a sky* face
  size_t nonSolidEntityBrushes = 0;  ///< brushes of trigger_*, func_illusionary, info_* ...
  size_t moverBrushes = 0;           ///< brushes of movers (solid unless includeMovers is false)
  size_t clipBrushes = 0, hintBrushes = 0, originBrushes = 0, triggerBrushes = 0;
  size_t liquidBrushes = 0;        ///< a *water / *slime / *lava / *tele face: not solid
  size_t skipOnlyBrushes = 0;      ///< every face textured skip: not solid
  size_t degenerateBrushes = 0;    ///< collinear side points, empty, unbounded or flat solids
  size_t brushFaces = 0;           ///< boundary faces of the solids
  size_t skipFaces = 0;            ///< faces textured skip: solid but never drawn
  size_t hiddenFaces = 0;          ///< faces wholly inside or against other solids: no patch
  size_t cutFaces = 0;             ///< faces partly hidden, cut into the pieces left visible
  size_t skyFaces = 0;             ///< faces textured sky*: black (absorbing) patches
  size_t lights = 0;               ///< light / light_* entities turned into emitters
  size_t skippedLights = 0;        ///< light value <= 0, or the cube wholly inside solids
  size_t startOffLights = 0;       ///< switchable lights with START_OFF: left dark
  size_t surfaceLights = 0;        ///< light entities with "_surface": templates, no cube
  size_t surfaceLightPatches = 0;  ///< patches whose texture a surface light makes emit
  size_t patches = 0;
};

/// Converts a parsed map (`path` names it in messages). Patch::sourceFace is the 0-based index of
/// the patch's brush side counting every side of every brush in file order; light cubes have
/// kNoSourceFace. ImportReport::facesIn counts the solids' boundary faces; the warnings count what
/// was skipped or dropped (brush kinds, degenerate brushes, sky faces, skipped lights). Throws
/// InputError (with the entity's line) on a malformed origin, light value or colour, and when
/// nothing visible is left.
Scene mapToScene(const MapFile& map, const std::string& path, const MapImportOptions& options = {},
                 MapImportStats* stats = nullptr);

/// readMapFile + mapToScene.
Scene importMap(const std::string& path, const MapImportOptions& options = {},
                MapImportStats* stats = nullptr);

/// The emitted radiosity (per channel, white light) of the cube made for a light entity of value
/// `light`: total power kQuakeLightPowerPerValue × light spread over the cube's 6 faces.
double quakeLightEmission(double light, double cubeSize);

/// The emitted radiosity of faces textured like a surface-light template (a light entity with
/// "_surface"): ericw-tools copies the template every `spacing` units across those faces, so the
/// power of one light per spacing² of area.
double quakeSurfaceLightEmission(double light, double spacing);

/// ericw-tools' default "_surface_spacing" of surface lights, in map units.
inline constexpr double kQuakeSurfaceLightSpacing = 128;

/// Emitted power per unit of a light entity's "light" value, in (map unit)² × radiosity. Chosen
/// so that the default light (300) gives irradiance 1 (a white surface as bright as Kd) at 150
/// units, half its Quake reach (Quake's linear falloff reaches 0 at `light` units):
/// power = 4π · 150² · (light / 300) = 300π · light.
inline constexpr double kQuakeLightPowerPerValue = 300 * 3.14159265358979323846;

/// The default "light" value of a light entity without one (Quake's and ericw-tools').
inline constexpr double kQuakeDefaultLight = 300;

}  // namespace gv
