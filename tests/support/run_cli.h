// Runs the built `globalvis` executable (path fixed at build time) and captures what it prints.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace gv::test {

struct CliResult {
  int exitCode = -1;
  std::string output;  ///< stdout and stderr together
};

/// Runs `globalvis ARGS` through the shell; ARGS is pasted verbatim (quote paths yourself).
inline CliResult runCli(const std::string& args) {
  CliResult r;
  const std::string command = std::string("'") + GV_CLI_PATH + "' " + args + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace gv::test
