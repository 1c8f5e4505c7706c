// Wall-clock timing of pipeline stages, for the seconds reported in stats and on the console.
#pragma once

#include <chrono>

namespace gv {

/// The clock every stage is timed with: monotonic, unaffected by clock changes.
using Clock = std::chrono::steady_clock;

/// Seconds elapsed since `start`.
inline double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace gv
