// The run report (report.html): the paper's §7 figures for this run beside the paper's own —
// §7.1 cells and portals, §7.2 pairs and the Fig. 13 histogram, §7.3 blockers vs shaft culling,
// Table 1 link evolution (§7.4) — with the run's pictures and timings. One file, no server.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace gv {

/// A picture to embed (as a data: URI).
struct ReportPicture {
  std::string file;     ///< its name, shown under it
  std::string caption;  ///< what it shows
  std::string png;      ///< the PNG file's bytes
};

/// Everything the report shows; each stage's stats.json is optional (its sections say so).
struct ReportInputs {
  std::string title;
  std::optional<nlohmann::json> cells, vis, radiosity;  ///< cells/, vis/, radiosity/ stats.json
  std::optional<nlohmann::json>
      timings;         ///< timings.json of `make run`: {"steps":[{name,seconds}]}
  std::string verify;  ///< what `globalvis verify` printed (vis/verify.txt), if saved
  std::vector<ReportPicture> pictures;
  std::string viewerHref;  ///< relative link to viewer.html; empty: no viewer
};

/// The report as one HTML document.
std::string reportHtml(const ReportInputs& inputs);

/// Reads a run directory into ReportInputs: the three stats.json files, timings.json,
/// vis/verify.txt, every PNG
/// in DIR/radiosity/ and DIR (render.png, links_visible.png, links_partial.png first) and
/// viewer.html if present. Throws InputError if the directory holds none of the stats files.
ReportInputs collectReportInputs(const std::filesystem::path& dir);

}  // namespace gv
