// libFuzzer target for the Quake .prt reader (quake/prt_file.h): any byte string must end in a
// PrtFile or an InputError — never a crash, hang, sanitizer report, other exception or a huge
// allocation from a count in the header. Build with `make fuzz FUZZ_TARGET=prt_file_fuzz` (clang).
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "quake/prt_file.h"
#include "util/input_error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const gv::PrtFile prt = gv::parsePrt(in, "input.prt");
    (void)prt.portals.size();
  } catch (const gv::InputError&) {
  }
  return 0;
}
