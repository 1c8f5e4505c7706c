// `globalvis view DIR`: one static, self-contained HTML page (the three.js viewer bundled at build
// time, the run's data inline) showing the scene, cells, portals, links, tubes and blockers
// (paper §7.4-§7.5, Figs. 14-17). Opens from disk, no server, no network.
#include <fmt/core.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "cli/commands.h"
#include "cli/output_files.h"
#include "report/html_page.h"
#include "report/run_files.h"
#include "report/viewer_data.h"
#include "util/input_error.h"

namespace gv::cli {
namespace {

namespace fs = std::filesystem;

/// The bundled viewer script: --bundle, else web/viewer.js beside the executable, else the
/// build tree's (GV_VIEWER_BUNDLE, fixed at compile time).
fs::path findViewerBundle(const std::string& requested) {
  if (!requested.empty()) return requested;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec && fs::is_regular_file(exe.parent_path() / "web" / "viewer.js"))
    return exe.parent_path() / "web" / "viewer.js";
#ifdef GV_VIEWER_BUNDLE
  return GV_VIEWER_BUNDLE;
#else
  return exe.parent_path() / "web" / "viewer.js";
#endif
}

}  // namespace

std::string readViewerBundle(const std::string& requested) {
  const fs::path path = findViewerBundle(requested);
  std::ifstream in(path, std::ios::binary);
  if (!in)
    throw InputError(path.string(), 0,
                     "viewer bundle not found: build it with `make build` (runs `npm ci` and `npm "
                     "run build` in web/, needs node and npm), or pass --bundle FILE");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeViewerPage(const fs::path& dir, const fs::path& output, const std::string& bundlePath) {
  const std::string bundle = readViewerBundle(bundlePath);
  const RunFiles files = findRunFiles(dir);
  const std::string title = "globalvis viewer: " + dir.string();
  const nlohmann::json data = viewerDataJson(files, title);
  writeTextFile(viewerPageHtml(title, bundle, data), output);
  fmt::print("viewer: {} patches, {} pairs, {} cells, radiosity {}; wrote {} ({:.1f} MB)\n",
             data["patches"]["sizes"].size(),
             data["pairs"].is_null() ? 0 : data["pairs"]["s"].size(), data["cellCount"].get<long>(),
             data["elements"].is_null() ? (data["radiosity"].is_null() ? "none" : "per patch")
                                        : "per element",
             output.string(), double(fs::file_size(output)) / 1e6);
  for (const auto& note : data["notes"]) fmt::print("note: {}\n", note.get<std::string>());
}

Action addViewCommand(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "view",
      "Write a self-contained HTML viewer of a run (scene shaded by radiosity, cells, "
      "portals, VISIBLE/PARTIAL links, tubes and blockers; paper §7.5). Reads DIR/vis, "
      "DIR/cells, DIR/radiosity (as `make run` writes them) or the files in DIR");
  struct State {
    std::string dir, output, bundle;
  };
  auto s = std::make_shared<State>();
  cmd->add_option("dir", s->dir, "Run directory")->required();
  cmd->add_option("-o,--output", s->output, "Page to write (default DIR/viewer.html)");
  cmd->add_option("--bundle", s->bundle, "The bundled viewer script (default: the build's)");
  return [s] {
    const fs::path output =
        s->output.empty() ? fs::path(s->dir) / "viewer.html" : fs::path(s->output);
    writeViewerPage(s->dir, output, s->bundle);
    return 0;
  };
}

}  // namespace gv::cli
