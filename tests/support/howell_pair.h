// Howell's catalogue case C-11 as OBJ/MTL files for CLI tests: a grey receiver (Kd 0.6) and a
// non-reflecting emitter (Ke 3 2 1), unit squares 1 apart, directly opposed (F = 0.19982).
#pragma once

#include <filesystem>

#include "support/temp_dir.h"

namespace gv::test {

/// F of Howell C-11 (parallel, directly opposed unit squares at distance 1).
inline constexpr double kHowellC11 = 0.19982;

/// Writes DIR/pair.obj + DIR/pair.mtl (face 0: receiver at z = 0 facing up; face 1: emitter at
/// z = 1 facing down); returns the OBJ's path.
inline std::filesystem::path writeHowellPair(const std::filesystem::path& dir) {
  writeFile(dir / "pair.mtl",
            "newmtl grey\nKd 0.6 0.6 0.6\nKe 0 0 0\n"
            "newmtl light\nKd 0 0 0\nKe 3 2 1\n");
  writeFile(dir / "pair.obj",
            "mtllib pair.mtl\n"
            "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
            "v 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
            "usemtl grey\nf 1 2 3 4\n"
            "usemtl light\nf 5 8 7 6\n");
  return dir / "pair.obj";
}

}  // namespace gv::test
