// Runs the built `globalvis` executable (path fixed at build time) and captures what it prints.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <string>

namespace gv::test {

struct CliResult {
  int exitCode = -1;
  std::string output;  ///< what it printed (runCli: stdout and stderr together)
};

/// `p` in single quotes, for pasting into a command line.
inline std::string quoted(const std::filesystem::path& p) {
  std::string s = "'";  // built by append: GCC 12 warns falsely (-Wrestrict) on "'" + string
  s.append(p.string()).append("'");
  return s;
}

/// Runs a shell command line, capturing its stdout.
inline CliResult runShell(const std::string& command) {
  CliResult r;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.output.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

/// Runs `globalvis ARGS` through the shell; ARGS is pasted verbatim (quote paths yourself).
inline CliResult runCli(const std::string& args) {
  return runShell(std::string("'") + GV_CLI_PATH + "' " + args + " 2>&1");
}

/// As runCli, but `output` is stdout alone (stderr discarded): for output parsed by a script.
inline CliResult runCliStdout(const std::string& args) {
  return runShell(std::string("'") + GV_CLI_PATH + "' " + args + " 2>/dev/null");
}

}  // namespace gv::test
