// The CLI tests' runner (cli_support.hpp).
#include "cli_support.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "test_files.hpp"

namespace nut::testing {

CliRun runNut(const std::string& args, const std::string& group) {
  std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  std::replace(test.begin(), test.end(), '/', '.');  // a parameterised test's name is Name/param
  const std::string out = outputPath(group, test + ".stdout.txt"), err = outputPath(group, test + ".stderr.txt");
  const int status = std::system((std::string(NUT_CLI_PATH) + " > " + out + " 2> " + err + " " + args).c_str());
  CliRun r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.stdoutText = fileText(out);
  r.stderrText = fileText(err);
  return r;
}

std::string outputPath(const std::string& group, const std::string& name) {
  return (nut::testing::testOutputDir(group) / name).string();
}

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace nut::testing
