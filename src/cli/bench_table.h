// `globalvis bench`'s output: the table (markdown, for the terminal and docs/BENCHMARKS.md), the
// same as JSON, and the machine it ran on.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/bench_run.h"

namespace gv::cli {

/// The machine, from /proc/cpuinfo ("model name"), the hardware threads and /proc/meminfo.
struct MachineInfo {
  std::string cpu = "unknown CPU";
  unsigned threads = 0;
  double memoryGiB = 0;
  std::string describe() const;  ///< "AMD EPYC ..., 2 threads, 7.8 GiB"
};
MachineInfo describeMachine();

/// Today's date in UTC, YYYY-MM-DD.
std::string todayUtc();

/// The rows as a markdown table, then one line per failure and note.
std::string benchTableMarkdown(const std::vector<BenchRow>& rows);

/// One row as JSON (absent stages are null).
nlohmann::json benchRowJson(const BenchRow& row);

}  // namespace gv::cli
