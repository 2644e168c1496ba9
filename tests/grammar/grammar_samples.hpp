// The sample grammars the grammar tests run over: samples/grammars/*.grammar.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace nut::testing {

inline std::string sampleGrammarPath(const std::string& name) {
  return std::string(NUT_SOURCE_DIR) + "/samples/grammars/" + name + ".grammar";
}

// The samples' names (file stems), sorted.
inline std::vector<std::string> sampleGrammarNames() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(std::string(NUT_SOURCE_DIR) + "/samples/grammars"))
    if (e.path().extension() == ".grammar") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace nut::testing
