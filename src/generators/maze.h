// A random perfect maze: a densely occluded floor plan where almost every cell hides the others.
#pragma once

#include <cstdint>

#include "scene/scene.h"

namespace gv {

/// Parameters of generateMaze. Lengths in metres.
struct MazeOptions {
  int width = 8;    ///< cells along x (>= 1)
  int height = 8;   ///< cells along y (>= 1)
  uint32_t seed = 1;  ///< seeds the maze and the light positions; same seed, same scene
  double cellSize = 2.0;       ///< distance between wall centre lines
  double wallThickness = 0.1;  ///< walls are centred on the grid lines
  double wallHeight = 2.5;     ///< clear height between floor and ceiling slabs
  double slabThickness = 0.2;  ///< floor and ceiling slabs
  int lights = 0;  ///< light panels, each in a different random cell; 0 = one per 16 cells (>= 1)
  double lightEmission = 10;  ///< emitted radiosity of the light panels, the same in R, G and B
};

/// A perfect maze (exactly one path between any two cells: a spanning tree of the grid made by a
/// randomized depth-first search) on width x height cells of cellSize, z up, the grid's corner at
/// the origin: cell (i, j) is x in [i s, (i+1) s], y in [j s, (j+1) s], floor at z = 0, ceiling
/// at z = wallHeight. Walls are closed axis-aligned boxes (all faces outward) of thickness
/// wallThickness centred on the grid lines: collinear wall segments are merged into one box, and
/// boxes never overlap (a vertex square belongs to the wall along x when there is one). The outer
/// wall and the floor and ceiling slabs (spanning the outer wall) close the maze. Lights are
/// one-sided quads facing down 2 cm below the ceiling, centred in their cells.
/// Deterministic: the seed's std::mt19937 stream is mapped to choices without the standard
/// library's distributions, so every platform builds the same maze.
/// Materials: wall (0.7, 0.68, 0.62), floor (0.5, 0.45, 0.4), ceiling (0.8), outside (0.5),
/// light (0.8 reflectance, `lightEmission`). Throws std::invalid_argument on invalid options.
Scene generateMaze(const MazeOptions& options = {});

}  // namespace gv
