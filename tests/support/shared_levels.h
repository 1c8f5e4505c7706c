// The shared real levels (../shared/data/levels, beside the project's root) that some tests read;
// those tests skip when a level is absent.
#pragma once

#include <string>
#include <string_view>

namespace gv::test {

/// The path of shared level `name` (without its .obj).
inline std::string sharedLevelPath(std::string_view name) {
  return std::string(GV_SHARED_DATA_DIR) + "/levels/" + std::string(name) + ".obj";
}

}  // namespace gv::test
