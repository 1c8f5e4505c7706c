// A small pipeline run (gen office 1x2, cells, vis, radiosity) laid out as `make run` lays out
// out/, made once per test binary for the view and report tests.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/run_cli.h"
#include "support/temp_dir.h"

namespace gv::test {

/// Removes a directory when the test process ends.
struct RemoveAtExit {
  std::filesystem::path dir;
  ~RemoveAtExit() {
    std::error_code ec;
    if (!dir.empty()) std::filesystem::remove_all(dir, ec);
  }
};

/// The run directory (DIR/office.obj, DIR/cells, DIR/vis, DIR/radiosity); empty on failure, with
/// the failing command's output in `error`. One per process (ctest runs tests in parallel
/// processes), removed when the process ends.
inline const std::filesystem::path& smallRun(std::string* error = nullptr) {
  static std::string failure;
  static RemoveAtExit cleanup;
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::temp_directory_path() / "globalvis-tests" /
                   ("report-small-run-" + std::to_string(getpid()));
    cleanup.dir = d;
    std::filesystem::remove_all(d);
    std::filesystem::create_directories(d);
    const std::string obj = quoted(d / "office.obj");
    for (const std::string& args :
         {"gen office --rows 1 --columns 2 -o " + obj,
          "cells " + obj + " -o " + quoted(d / "cells"),
          "vis " + obj + " -o " + quoted(d / "vis") + " --min-coverage 0.3",
          "radiosity " + obj + " -o " + quoted(d / "radiosity") +
              " --quiet --max-refinements 1 --rays 4"}) {
      const CliResult r = runCli(args);
      if (r.exitCode != 0) {
        failure = "globalvis " + args + ":\n" + r.output;
        return std::filesystem::path();
      }
    }
    return d;
  }();
  if (error) *error = failure;
  return dir;
}

}  // namespace gv::test
