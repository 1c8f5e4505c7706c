// The subcommands of the `globalvis` executable; each registers itself on the CLI11 app.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace gv::cli {

/// A subcommand's action, run after parsing; returns the process exit code.
using Action = std::function<int()>;

/// Each adds its subcommand to `app` and returns the action to run when it is chosen.
Action addInfoCommand(CLI::App& app);
Action addGenCommand(CLI::App& app);
Action addCellsCommand(CLI::App& app);
Action addRadiosityCommand(CLI::App& app);
Action addVisCommand(CLI::App& app);
Action addVerifyCommand(CLI::App& app);
Action addPvsCommand(CLI::App& app);

}  // namespace gv::cli
