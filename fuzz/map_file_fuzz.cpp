// libFuzzer target for the Quake .map parser (quake/map_file.h): any byte string must end in a
// MapFile or an InputError — never a crash, hang, sanitizer report or other exception. Only the
// parser: the brush CSG behind `importMap` is exercised by the tests on real maps. Build with
// `make fuzz FUZZ_TARGET=map_file_fuzz` (clang).
#include <cstddef>
#include <cstdint>
#include <string>

#include "quake/map_file.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const gv::MapFile map = gv::parseMapText("input.map", text);
    (void)map;
  } catch (const gv::InputError&) {
  }
  return 0;
}
