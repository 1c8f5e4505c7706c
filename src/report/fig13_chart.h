// The paper's Fig. 13 as an inline SVG bar chart: stabbing successes and failures of the
// inter-cell portal sequences, by sequence length (§7.2).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gv {

/// Grouped bars per sequence length (index = length in portals): successes green, failures
/// red, with axes, tick labels and a legend. Empty histograms give a chart saying so.
std::string fig13ChartSvg(const std::vector<uint64_t>& successes,
                          const std::vector<uint64_t>& failures);

}  // namespace gv
