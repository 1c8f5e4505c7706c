// The process's peak resident memory, for the stats every long command reports, and a reset so
// that one process (the bench) can measure the peak of each of its stages; and the machine's
// physical memory, which memory guards scale with.
#pragma once

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace gv {

/// The largest resident set size of this process since it started or since the last
/// resetPeakResident, in bytes: Linux's VmHWM (/proc/self/status), else getrusage's maximum
/// (which no reset lowers). 0 where neither is available.
inline double peakResidentBytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) * 1024.0;  // in kB
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<double>(usage.ru_maxrss) * 1024.0;  // Linux reports kilobytes
}

/// Lowers the peak that peakResidentBytes reports to the current resident size (Linux >= 4.0:
/// "5" to /proc/self/clear_refs). Returns false where that is not possible; the peak then
/// stays the process's.
inline bool resetPeakResident() {
  std::ofstream clear("/proc/self/clear_refs");
  return static_cast<bool>(clear << "5") && static_cast<bool>(clear.flush());
}

/// The machine's physical memory in bytes (sysconf), 0 where it cannot be read.
inline double physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && pageSize > 0 ? static_cast<double>(pages) * static_cast<double>(pageSize)
                                   : 0.0;
}

}  // namespace gv
