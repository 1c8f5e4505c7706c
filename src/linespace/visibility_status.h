// The paper's three visibility classes of an interaction between two elements (§4.2, §6.2),
// shared by the linespace tubes and the radiosity solver that consumes them.
#pragma once

#include <cstdint>

namespace gv {

/// INVISIBLE: no segment between the elements carries light; PARTIAL: unknown or some do;
/// VISIBLE: no segment between them meets another patch.
enum class VisibilityStatus : uint8_t { Invisible = 0, Partial = 1, Visible = 2 };

}  // namespace gv
