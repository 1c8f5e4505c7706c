// `globalvis report DIR`: DIR/report.html, the paper's §7 figures for a run beside the paper's
// own (tables, the Fig. 13 chart, Table 1), its pictures and timings, and the viewer.
#include <fmt/core.h>

#include <filesystem>
#include <memory>

#include "cli/commands.h"
#include "cli/output_files.h"
#include "report/report_html.h"

namespace gv::cli {

Action addReportCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "report",
      "Write DIR/report.html: the paper's §7 figures for a run (DIR/cells, DIR/vis, "
      "DIR/radiosity stats.json) beside the paper's, with pictures, timings and the "
      "viewer; opens from disk");
  struct State {
    std::string dir, output, bundle;
    bool viewer = false;
  };
  auto s = std::make_shared<State>();
  cmd->add_option("dir", s->dir, "Run directory (as `make run` writes: out/)")->required();
  cmd->add_option("-o,--output", s->output, "Page to write (default DIR/report.html)");
  cmd->add_flag("--viewer", s->viewer,
                "First write DIR/viewer.html (as `globalvis view DIR`), then link and frame it");
  cmd->add_option("--bundle", s->bundle, "With --viewer: the bundled viewer script");
  return [s] {
    const std::filesystem::path dir(s->dir);
    const std::filesystem::path output =
        s->output.empty() ? dir / "report.html" : std::filesystem::path(s->output);
    if (s->viewer) writeViewerPage(dir, dir / "viewer.html", s->bundle);
    ReportInputs inputs = collectReportInputs(dir);
    if (!inputs.viewerHref.empty())  // the link is relative to the page
      inputs.viewerHref = std::filesystem::relative(dir / inputs.viewerHref,
                                                    std::filesystem::absolute(output).parent_path())
                              .generic_string();
    writeTextFile(reportHtml(inputs), output);
    fmt::print("report: stats of {}{}{}, {} pictures, viewer {}; wrote {}\n",
               inputs.cells ? "cells " : "", inputs.vis ? "vis " : "",
               inputs.radiosity ? "radiosity" : "", inputs.pictures.size(),
               inputs.viewerHref.empty() ? "not present" : "linked", output.string());
    return 0;
  };
}

}  // namespace gv::cli
