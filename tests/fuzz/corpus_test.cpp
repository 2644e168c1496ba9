// The fuzz targets as a plain test: every target over its generated seeds (seed_inputs.hpp), its
// hand-made inputs (tests/fuzz/corpus/<target>/) and every input kept under
// tests/fuzz/regressions/<target>/, plus byte-level mutations of the seeds, on every `make test`.
// A target calls abort() on an input that breaks what it checks, which fails the test run.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "seed_inputs.hpp"
#include "targets.hpp"

namespace nut::fuzz {
namespace {

using Target = int (*)(const std::uint8_t*, std::size_t);

void runAll(Target target, const std::vector<SeedInput>& inputs) {
  for (const SeedInput& input : inputs) {
    SCOPED_TRACE(input.name);
    EXPECT_EQ(target(input.bytes.data(), input.bytes.size()), 0);
  }
}

// Every `stride`-th prefix, and `count` copies each with one byte replaced, from byte `from` on.
void runMutations(Target target, const std::vector<SeedInput>& inputs, std::size_t from, int count) {
  std::mt19937_64 rng(11);
  for (const SeedInput& input : inputs) {
    const std::vector<std::uint8_t>& bytes = input.bytes;
    for (std::size_t prefix = 0; prefix < bytes.size(); prefix += 1 + bytes.size() / 97) target(bytes.data(), prefix);
    if (bytes.size() <= from) continue;
    for (int m = 0; m < count; ++m) {
      auto mutant = bytes;
      const std::size_t at = std::uniform_int_distribution<std::size_t>(from, mutant.size() - 1)(rng);
      mutant[at] = static_cast<std::uint8_t>(rng());
      target(mutant.data(), mutant.size());
    }
  }
}

std::vector<SeedInput> committed(const std::string& target) {
  std::vector<SeedInput> inputs = committedInputs("corpus/" + target);
  const std::vector<SeedInput> regressions = committedInputs("regressions/" + target);
  inputs.insert(inputs.end(), regressions.begin(), regressions.end());
  return inputs;
}

TEST(FuzzCorpus, HniSeedsAndMutationsRunClean) {
  auto seeds = hniSeeds();
  ASSERT_TRUE(seeds.ok()) << seeds.error().message;
  runAll(hniInput, *seeds);
  runMutations(hniInput, *seeds, 2, 200);  // the width (bytes 0-1) kept
  runAll(hniInput, committed("hni_fuzz"));
}

TEST(FuzzCorpus, RenderSeedsAndMutationsRunClean) {
  auto seeds = hniSeeds();
  ASSERT_TRUE(seeds.ok()) << seeds.error().message;
  runAll(renderInput, *seeds);
  runMutations(renderInput, *seeds, 2, 50);
  runAll(renderInput, committed("render_fuzz"));
}

TEST(FuzzCorpus, ObjSeedsAndMutationsRunClean) {
  runAll(objInput, objSeeds());
  const std::vector<SeedInput> handMade = committed("obj_fuzz");
  EXPECT_GE(handMade.size(), 10u);  // the folder is found
  runAll(objInput, handMade);
  runMutations(objInput, handMade, 0, 100);
}

TEST(FuzzCorpus, GlbSeedsAndMutationsRunClean) {
  std::vector<SeedInput> seeds = glbSeeds();
  EXPECT_GE(seeds.size(), 1u);  // gltfpack's cube is found
  const std::vector<SeedInput> regressions = committed("glb_fuzz");
  seeds.insert(seeds.end(), regressions.begin(), regressions.end());
  runAll(glbInput, seeds);
  runMutations(glbInput, seeds, 0, 2000);
}

TEST(FuzzCorpus, GrammarSeedsAndMutationsRunClean) {
  const std::vector<SeedInput> seeds = grammarSeeds();
  EXPECT_GE(seeds.size(), 4u);  // the samples are found
  runAll(grammarInput, seeds);
  runMutations(grammarInput, seeds, 0, 100);
}

TEST(FuzzCorpus, CitySeedsAndMutationsRunClean) {
  runAll(cityInput, citySeeds());
  const std::vector<SeedInput> handMade = committed("city_fuzz");
  EXPECT_GE(handMade.size(), 5u);
  runAll(cityInput, handMade);
  runMutations(cityInput, handMade, 0, 100);
}

}  // namespace
}  // namespace nut::fuzz
