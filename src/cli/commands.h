// The subcommands of the `globalvis` executable; each registers itself on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>
#include <filesystem>
#include <functional>
#include <string>

namespace gv::cli {

/// A subcommand's action, run after parsing; returns the process exit code.
using Action = std::function<int()>;

/// Each adds its subcommand to `app` and returns the action to run when it is chosen.
Action addInfoCommand(CLI::App& app);
Action addGenCommand(CLI::App& app);
Action addCellsCommand(CLI::App& app);
Action addRadiosityCommand(CLI::App& app);
Action addPhotonsCommand(CLI::App& app);
Action addVisCommand(CLI::App& app);
Action addVerifyCommand(CLI::App& app);
Action addPvsCommand(CLI::App& app);
Action addViewCommand(CLI::App& app);
Action addReportCommand(CLI::App& app);
Action addBenchCommand(CLI::App& app);

/// The bundled viewer script (`requested`, else the build's); throws InputError when missing.
std::string readViewerBundle(const std::string& requested);
/// Writes the viewer page of run directory `dir` to `output` (`globalvis view`).
void writeViewerPage(const std::filesystem::path& dir, const std::filesystem::path& output,
                     const std::string& bundlePath);

}  // namespace gv::cli
