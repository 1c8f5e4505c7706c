// A parametric office building, the kind of densely occluded model of the paper's Fig. 1 and §7.
#pragma once

#include <cstddef>
#include <cstdint>

#include "geometry/vec3.h"
#include "scene/scene.h"

namespace gv {

/// Parameters of generateOffice. Lengths in metres. The defaults give a one-storey office of
/// 2 x 4 rooms with 406 patches, the scale of the paper's 403-patch model.
struct OfficeOptions {
  int floors = 1;   ///< storeys, stacked along +z (>= 1)
  int rows = 2;     ///< rows of rooms along y; each row has its own corridor on its -y side (>= 1)
  int columns = 4;  ///< rooms per row, along x (>= 1)
  bool doors = true;    ///< a door from every room to its corridor; false seals every room
  bool windows = true;  ///< an interior window in every wall between two rooms of a row
  bool furniture = true;  ///< `furniturePerRoom` boxes (desks, cabinets) on every room's floor
  bool lights = true;     ///< a ceiling light panel in every room and one per room in the corridor
  uint32_t seed = 1;  ///< seeds the door positions and the furniture; same seed, same scene

  double roomWidth = 4.0;       ///< clear room size along x
  double roomDepth = 5.0;       ///< clear room size along y
  double corridorWidth = 2.0;   ///< clear corridor width along y
  double storeyHeight = 2.8;    ///< clear height, floor to ceiling
  double slabThickness = 0.3;   ///< floor / roof slabs
  double wallThickness = 0.15;  ///< every wall, exterior and interior
  double doorWidth = 0.9;
  double doorHeight = 2.1;
  double windowWidth = 1.2;   ///< along the wall, centred in it
  double windowSill = 1.0;    ///< height of the window's bottom above the floor
  double windowHead = 2.1;    ///< height of the window's top above the floor
  int furniturePerRoom = 2;   ///< desks and cabinets alternate; placed in the back of the room
  double lightEmission = 10;  ///< emitted radiosity of the light panels, the same in R, G and B
};

/// The building: floors x rows x columns rooms.
///
/// Coordinates: z up, metres, the building's outer corner at the origin and everything in
/// x, y, z >= 0. With t = wallThickness, W = roomWidth, D = roomDepth, C = corridorWidth,
/// H = storeyHeight, s = slabThickness:
/// - x: exterior wall [0, t], then per column c the room x in [t + c(W+t), t + c(W+t) + W]
///   followed by a wall of thickness t (the last one exterior): X = t + columns (W + t).
/// - y: exterior wall [0, t], then per row r, from y_r = t + r P with P = C + t + D + t: the
///   corridor [y_r, y_r + C], the corridor wall (with the doors), the rooms
///   [y_r + C + t, y_r + C + t + D], a back wall (the last one exterior): Y = t + rows P.
/// - z: slab f (f = 0..floors) at [f (H+s), f (H+s) + s]; storey f's air between slabs f and f+1.
///
/// Every solid is an axis-aligned box with all six faces facing outward (see SceneBuilder): the
/// floor/roof slabs span the whole footprint; the walls stand between two slabs; a wall with a
/// door is split into the pieces beside the doors and a lintel above each door, so the door's
/// sides (jambs) and head are separate thin quads, as in the paper's Fig. 1; a wall with a window
/// into pieces left, right, below (sill) and above (head). Exterior walls and slabs close the
/// building: air in one room reaches another only through doors and windows, and storeys never see
/// each other. Each row's corridor is closed at both ends by the exterior walls (no stairs).
/// Furniture boxes stand on the floor, clear of walls and of a 1.2 m zone along the door wall.
/// Lights are one-sided quads facing down 2 cm below the ceiling.
///
/// Materials: wall (0.75, 0.73, 0.68), floor (0.45, 0.40, 0.35), ceiling (0.80, 0.80, 0.78),
/// jamb (0.35, 0.45, 0.70; door sides and head, window reveals), exterior (0.55), desk
/// (0.60, 0.45, 0.30), cabinet (0.50, 0.55, 0.60), light (0.8 reflectance, `lightEmission`).
/// Throws std::invalid_argument when the options are not a valid building (non-positive counts
/// or sizes, a door or window that does not fit its wall).
Scene generateOffice(const OfficeOptions& options = {});

/// The number of patches generateOffice(options) makes, without making them (exact).
size_t officePatchCount(const OfficeOptions& options);

/// Default options with floors, rows and columns chosen so that the patch count is near `target`
/// (within a few percent above ~2000 patches; the smallest office is ~150 patches): about
/// cbrt(target / 400) storeys of rooms twice as many columns as rows.
OfficeOptions officeOptionsForPatchCount(size_t target);

/// The air of room (floor, row, column): the box bounded by its walls, floor and ceiling.
Aabb officeRoomInterior(const OfficeOptions& options, int floor, int row, int column);
/// The air of the corridor of (floor, row).
Aabb officeCorridorInterior(const OfficeOptions& options, int floor, int row);

}  // namespace gv
