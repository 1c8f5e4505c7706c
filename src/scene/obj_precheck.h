// A line-by-line check of OBJ and MTL text before the real parser (tinyobjloader) runs. The parser
// is lenient by design (it reads "nan" as a number, skips bad indices, and reports no line
// numbers), so the precheck is what turns bad input into a message naming file and line.
#pragma once

#include <string>
#include <vector>

#include "geometry/vec3.h"

namespace gv {

/// A `mtllib` statement: the library's file name and the OBJ line that names it.
struct MtlReference {
  std::string name;
  size_t line = 0;
};

/// What the precheck read: vertex positions (correctly rounded, unlike tinyobjloader's fast
/// parser, which can be 1 ulp off and would break bit-exact round trips) and MTL references.
struct ObjPrecheck {
  std::vector<Vec3> vertices;
  std::vector<MtlReference> libraries;
};

/// Checks vertex records (3+ finite numbers), face records (3+ vertices, indices in range, never
/// 0) and collects `mtllib` references. Throws InputError with `path:line` on the first problem.
ObjPrecheck precheckObj(const std::string& path, const std::string& text);

/// Checks Kd / Ke records of an MTL file: three finite non-negative numbers each. Throws
/// InputError with `path:line`. Returns warnings (e.g. a reflectance above 1).
std::vector<std::string> precheckMtl(const std::string& path, const std::string& text);

}  // namespace gv
