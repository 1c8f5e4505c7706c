// globalvis: one executable, subcommands for each pipeline stage. Bad input ends in a message
// naming file and line and exit code 2; usage errors exit 1 (CLI11's convention).
#include <fmt/core.h>

#include <CLI/CLI.hpp>
#include <map>

#include "cli/commands.h"
#include "util/input_error.h"

int main(int argc, char** argv) {
  CLI::App app{
      "globalvis: conservative global visibility (Teller & Hanrahan 1993) and radiosity.\n"
      "Run `globalvis help` for the subcommands, `globalvis SUBCOMMAND --help` for their options."};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every subcommand");

  std::map<CLI::App*, gv::cli::Action> actions;
  auto add = [&](gv::cli::Action (*addCommand)(CLI::App&)) {
    gv::cli::Action action = addCommand(app);
    actions[app.get_subcommands({}).back()] = std::move(action);
  };
  add(gv::cli::addInfoCommand);
  add(gv::cli::addGenCommand);
  add(gv::cli::addCellsCommand);
  add(gv::cli::addRadiosityCommand);
  add(gv::cli::addPhotonsCommand);
  add(gv::cli::addVisCommand);
  add(gv::cli::addVerifyCommand);
  add(gv::cli::addPvsCommand);
  add(gv::cli::addViewCommand);
  add(gv::cli::addReportCommand);
  add(gv::cli::addBenchCommand);
  CLI::App* help = app.add_subcommand("help", "List the subcommands");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints the message (or the help asked for)
    return code == 0 ? 0 : 1;
  }
  if (help->parsed()) {
    fmt::print("{}\n\nSubcommands:\n", app.get_description());
    for (const CLI::App* sub : app.get_subcommands({}))
      fmt::print("  {:<10} {}\n", sub->get_name(), sub->get_description());
    fmt::print("\nRun `globalvis SUBCOMMAND --help` for a subcommand's options.\n");
    return 0;
  }
  try {
    for (auto& [sub, action] : actions)
      if (sub->parsed()) return action();
  } catch (const gv::InputError& e) {
    fmt::print(stderr, "globalvis: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "globalvis: error: {}\n", e.what());
    return 3;
  }
  return 1;
}
