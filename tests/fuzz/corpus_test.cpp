// The fuzz target as a plain test: the seed corpus, its byte-level mutations, and every input
// kept under tests/fuzz/regressions/ run through LLVMFuzzerTestOneInput on every `make test`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>

#include <nut/hni.hpp>

#include "../random_hierarchy.hpp"
#include "frame.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace nut {
namespace {

TEST(FuzzCorpus, SeedsAndMutationsRunClean) {
  std::mt19937_64 rng(11);
  for (std::uint64_t seed = 0; seed < 32; ++seed) {
    auto image = compile(testing::randomHierarchy(seed));
    ASSERT_TRUE(image.ok());
    const auto bytes = fuzz::frame(*image);
    EXPECT_EQ(LLVMFuzzerTestOneInput(bytes.data(), bytes.size()), 0);
    for (std::size_t prefix = 0; prefix < bytes.size(); prefix += 1 + bytes.size() / 97)
      LLVMFuzzerTestOneInput(bytes.data(), prefix);
    for (int m = 0; m < 200; ++m) {
      auto mutant = bytes;
      mutant[std::uniform_int_distribution<std::size_t>(2, mutant.size() - 1)(rng)] = static_cast<std::uint8_t>(rng());
      LLVMFuzzerTestOneInput(mutant.data(), mutant.size());
    }
  }
}

TEST(FuzzCorpus, Regressions) {
  const std::filesystem::path dir = std::filesystem::path(NUT_SOURCE_DIR) / "tests/fuzz/regressions";
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() == ".md") continue;
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(in), {}};
    SCOPED_TRACE(entry.path().string());
    EXPECT_EQ(LLVMFuzzerTestOneInput(bytes.data(), bytes.size()), 0);
  }
}

}  // namespace
}  // namespace nut
