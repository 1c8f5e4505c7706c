// libFuzzer target for the OBJ importer: any byte string must end in a Scene or an InputError —
// never a crash, hang, sanitizer report or other exception. Build with `make fuzz` (clang).
#include <cstddef>
#include <cstdint>
#include <string>

#include "scene/scene_io.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    // The path's directory does not exist, so `mtllib` lines give "not found" warnings only.
    const gv::Scene scene = gv::importObjText("/nonexistent-fuzz-dir/input.obj", text);
    (void)scene.totalArea();
  } catch (const gv::InputError&) {
  }
  return 0;
}
