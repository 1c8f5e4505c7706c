// A furnished room: the kind of scene hierarchical radiosity was first shown on (Hanrahan,
// Salzman & Aupperle 1991, the room of SPLASH-2's RADIOSITY benchmark): one closed room with a
// table, chairs and a bookcase under ceiling lights, a few hundred polygons with many contacts
// (legs on the floor, a backrest on a seat) and small parts close to large walls.
#pragma once

#include "scene/scene.h"

namespace gv {

/// Parameters of generateFurnishedRoom. Lengths in metres.
struct FurnishedRoomOptions {
  double width = 6.0;        ///< room extent along x
  double depth = 5.0;        ///< room extent along y
  double height = 3.0;       ///< floor to ceiling
  int chairs = 4;            ///< around the table, 0..4 (one per side, long sides first)
  bool bookcase = true;      ///< a bookcase of three shelves against the wall at y = depth
  double lightEmission = 8;  ///< emitted radiosity of the two ceiling panels, R = G = B
};

/// The room is the inside of the box [0, width] x [0, depth] x [0, height], z up: six one-sided
/// rectangles facing inward (floor, ceiling, four walls), so light stays in. Two 0.8 m square
/// light panels face down 2 cm below the ceiling, over the two halves of the table. Furniture
/// is made of closed axis-aligned boxes (every face outward, as solids are modelled): a table
/// (top and four legs) at the room's centre, up to four chairs (seat, four legs, backrest) and a
/// bookcase (two sides, top, bottom and three shelves). The defaults give 224 patches.
/// Materials: wall (0.7, 0.68, 0.62), floor (0.45, 0.32, 0.2), ceiling (0.8), table
/// (0.55, 0.38, 0.22), chair (0.3, 0.35, 0.6), bookcase (0.6, 0.5, 0.35), light (reflectance
/// 0.8, `lightEmission`). Throws std::invalid_argument when the room is too small for its
/// furniture (width < 4, depth < 3.5, height < 2.2) or an option is out of range.
Scene generateFurnishedRoom(const FurnishedRoomOptions& options = {});

}  // namespace gv
