// Running the `nut` command as a user does, for the CLI tests: its exit status and what it printed.
#pragma once

#include <string>

namespace nut::testing {

struct CliRun {
  int exitCode = -1;
  std::string stdoutText, stderrText;
};

// Runs `nut <args>` through the shell, stdout and stderr going to files in the test output folder
// `group`, named after the current test (ctest runs tests in parallel). A redirection in `args`
// comes later in the command line, so it wins over the capture.
CliRun runNut(const std::string& args, const std::string& group);

// The path of `name` in the test output folder `group` (created).
std::string outputPath(const std::string& group, const std::string& name);

// A file's whole text ("" when it cannot be read).
std::string fileText(const std::string& path);

}  // namespace nut::testing
