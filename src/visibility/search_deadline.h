// The time budget of `vis`'s searches: PropagationOptions::deadline checked inside the searches
// themselves (a single long search could otherwise overrun it), cheaply.
#pragma once

#include <cstdint>
#include <stdexcept>

#include "util/timing.h"

namespace gv {

/// Thrown by computeVisibility when PropagationOptions::deadline has passed.
struct PropagationDeadlineExceeded : std::runtime_error {
  PropagationDeadlineExceeded() : std::runtime_error("visibility propagation: deadline passed") {}
};

/// Throws PropagationDeadlineExceeded once `deadline` has passed; reads the clock every 64 calls
/// (a search step costs far more than a clock read, but there are millions of them).
class DeadlineCheck {
 public:
  Clock::time_point deadline = Clock::time_point::max();
  void operator()() {
    if (deadline == Clock::time_point::max() || ++calls_ % 64 != 0) return;
    if (Clock::now() > deadline) throw PropagationDeadlineExceeded();
  }

 private:
  uint32_t calls_ = 0;
};

}  // namespace gv
