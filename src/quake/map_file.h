// Quake level sources (.map, id Tech 2 / ericw-tools): entities with key/value pairs and convex
// brushes given by 3-point planes. Standard and Valve 220 texture axes; the scene input of issue
// #7.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "geometry/vec3.h"

namespace gv {

/// One side of a brush: the plane through three points and the texture drawn on it. By Quake's
/// convention the normal cross(p0 - p1, p2 - p1) points OUT of the solid (see `outwardNormal`).
struct MapBrushSide {
  std::array<Vec3, 3> points;
  std::string texture;  ///< as written (case kept), e.g. "*water1", "sky4", "e1u1/metal2_1"
  size_t line = 0;      ///< 1-based line in the file
  /// The (not normalised) outward normal of the side's plane by Quake's point order.
  Vec3 outwardNormal() const { return cross(points[0] - points[1], points[2] - points[1]); }
};

/// A convex brush: the intersection of the inner half-spaces of its sides.
struct MapBrush {
  std::vector<MapBrushSide> sides;
  size_t line = 0;  ///< line of its opening brace
};

/// An entity: key/value pairs in file order and the brushes it owns (worldspawn, func_*, ...).
struct MapEntity {
  std::vector<std::pair<std::string, std::string>> properties;
  std::vector<MapBrush> brushes;
  size_t line = 0;  ///< line of its opening brace
  /// The value of `key` (the first one if repeated), or nullptr.
  const std::string* value(const std::string& key) const;
  /// The classname, or "" when missing.
  std::string className() const;
};

/// A parsed .map file. Patches (patchDef2/3) and brush primitives (brushDef/brushDef3) are not
/// convex 3-point brushes: they are skipped and counted, with one warning each kind.
struct MapFile {
  std::vector<MapEntity> entities;
  size_t skippedPatches = 0;
  size_t skippedBrushPrimitives = 0;
  std::vector<std::string> warnings;
};

/// Parses .map text; `path` names it in messages. Accepts `//` comments, quoted keys and values,
/// brush sides `( x y z ) ( x y z ) ( x y z ) TEXTURE` followed by either the standard
/// `xoff yoff rot xscale yscale` or the Valve 220 `[ ux uy uz uoff ] [ vx vy vz voff ] rot xscale
/// yscale`, optionally followed on the same line by up to three integers (Quake 2 / Hexen 2
/// contents, flags, value). Throws InputError with the line of the offending token on anything
/// else: unbalanced braces, missing or non-finite numbers, a key without a value. Brushes with
/// too few sides are kept here; turning brushes into solids (map_to_scene.h) drops them.
MapFile parseMapText(const std::string& path, const std::string& text);

/// Reads and parses a .map file. Throws InputError when it cannot be read or is malformed.
MapFile readMapFile(const std::string& path);

}  // namespace gv
