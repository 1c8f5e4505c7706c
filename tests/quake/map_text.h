// Writing tiny Quake .map texts for tests: axis-aligned box brushes with Quake's point order.
#pragma once

#include <string>

#include "geometry/vec3.h"

namespace gv::test {

/// One brush side line whose plane has outward normal s·e_k through `p` (k = axis, s = ±1), by
/// Quake's rule normal = (p0 - p1) × (p2 - p1): p0 = p1 + e_{k+1}, p2 = p1 + s·e_{k+2}.
inline std::string boxSide(int k, int s, double at, const std::string& texture) {
  double p1[3] = {0, 0, 0};
  p1[k] = at;
  double p0[3] = {p1[0], p1[1], p1[2]};
  double p2[3] = {p1[0], p1[1], p1[2]};
  p0[(k + 1) % 3] += 64;
  p2[(k + 2) % 3] += 64 * s;
  auto pt = [](const double* p) {
    return "( " + std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) +
           " ) ";
  };
  return pt(p0) + pt(p1) + pt(p2) + texture + " 0 0 0 1 1\n";
}

/// An axis-aligned box brush [lo, hi] in standard format, every side textured `texture`.
inline std::string boxBrush(const Vec3& lo, const Vec3& hi, const std::string& texture = "wall") {
  std::string out = "{\n";
  for (int k = 0; k < 3; ++k) {
    out += boxSide(k, -1, lo[k], texture);
    out += boxSide(k, +1, hi[k], texture);
  }
  return out + "}\n";
}

/// A point entity with a classname and an origin, plus extra "key" "value" lines.
inline std::string pointEntity(const std::string& className, const Vec3& origin,
                               const std::string& extra = "") {
  return "{\n\"classname\" \"" + className + "\"\n\"origin\" \"" + std::to_string(origin.x) + " " +
         std::to_string(origin.y) + " " + std::to_string(origin.z) + "\"\n" + extra + "}\n";
}

/// worldspawn holding the given brush texts.
inline std::string world(const std::string& brushes) {
  return "// Game: Quake\n{\n\"classname\" \"worldspawn\"\n" + brushes + "}\n";
}

}  // namespace gv::test
