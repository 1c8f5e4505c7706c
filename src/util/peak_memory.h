// The process's peak resident memory, for the stats every long command reports.
#pragma once

#include <sys/resource.h>

namespace gv {

/// The largest resident set size of this process so far, in bytes (getrusage; Linux reports
/// kilobytes). 0 where the call fails.
inline double peakResidentBytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<double>(usage.ru_maxrss) * 1024.0;
}

}  // namespace gv
