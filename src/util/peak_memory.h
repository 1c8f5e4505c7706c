// The process's peak resident memory, for the stats every long command reports, and a reset so
// that one process (the bench) can measure the peak of each of its stages; and the machine's
// memory (or its container's limit), which memory guards scale with.
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

/// The memory this process may use, in bytes: the machine's physical memory (sysconf), or the
/// limit of its control group if that is lower (a container: cgroup v2's memory.max, v1's
/// memory.limit_in_bytes; "max" or a huge value means none). 0 where nothing can be read.
inline double usableMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  double bytes =
      pages > 0 && pageSize > 0 ? static_cast<double>(pages) * static_cast<double>(pageSize) : 0.0;
  for (const char* path :
       {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
    std::ifstream in(path);
    double limit = 0;
    if (in >> limit && limit > 0 && (bytes == 0 || limit < bytes)) bytes = limit;
  }
  return bytes;
}

}  // namespace gv
