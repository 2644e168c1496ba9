// tests/test_files.hpp — where tests write their files: a folder per group under the build's
// test output folder (NUT_TEST_OUTPUT_DIR), and small text files written into it.
#pragma once

#include <filesystem>
#include <fstream>
#include <string>

namespace nut::testing {

// NUT_TEST_OUTPUT_DIR/group, created if it is missing.
inline std::filesystem::path testOutputDir(const std::string& group) {
  const std::filesystem::path dir = std::filesystem::path(NUT_TEST_OUTPUT_DIR) / group;
  std::filesystem::create_directories(dir);
  return dir;
}

// Writes `text` to testOutputDir(group)/name (its folders created) and returns the path.
inline std::string writeTestFile(const std::string& group, const std::string& name, const std::string& text) {
  const std::filesystem::path path = testOutputDir(group) / name;
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
  return path.string();
}

}  // namespace nut::testing
