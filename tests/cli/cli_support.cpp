// The CLI tests' runner (cli_support.hpp).
#include "cli_support.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace nut::testing {

CliRun runNut(const std::string& args, const std::string& group) {
  const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
  const std::string out = outputPath(group, test + ".stdout.txt"), err = outputPath(group, test + ".stderr.txt");
  const int status = std::system((std::string(NUT_CLI_PATH) + " > " + out + " 2> " + err + " " + args).c_str());
  CliRun r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.stdoutText = fileText(out);
  r.stderrText = fileText(err);
  return r;
}

std::string outputPath(const std::string& group, const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(NUT_TEST_OUTPUT_DIR) / group;
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

std::string fileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace nut::testing
