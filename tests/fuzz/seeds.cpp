// `fuzz_seeds DIR`: writes every fuzz target's generated seeds (seed_inputs.hpp) as a libFuzzer
// corpus, one folder per target: DIR/hni_fuzz, DIR/render_fuzz, DIR/obj_fuzz, DIR/glb_fuzz, DIR/city_fuzz,
// DIR/grammar_fuzz.
// Seeds over kMaxSeedBytes (the larger sample OBJs) are left to the plain corpus test: libFuzzer
// mutates small inputs faster, and the Makefile caps obj_fuzz inputs at that size.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "seed_inputs.hpp"

namespace {

constexpr std::size_t kMaxSeedBytes = 65536;

bool writeSeeds(const std::filesystem::path& folder, const std::vector<nut::fuzz::SeedInput>& seeds) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  for (const auto& seed : seeds) {
    if (seed.bytes.size() > kMaxSeedBytes) continue;
    std::ofstream out(folder / seed.name, std::ios::binary);
    out.write(reinterpret_cast<const char*>(seed.bytes.data()), static_cast<std::streamsize>(seed.bytes.size()));
    if (!out) {
      std::fprintf(stderr, "error: %s: cannot write\n", (folder / seed.name).c_str());
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds DIR\n");
    return 2;
  }
  const std::filesystem::path dir = argv[1];
  auto hni = nut::fuzz::hniSeeds();
  if (!hni) {
    std::fprintf(stderr, "error: %s\n", hni.error().message.c_str());
    return 1;
  }
  const bool ok = writeSeeds(dir / "hni_fuzz", *hni) && writeSeeds(dir / "render_fuzz", *hni) &&
                  writeSeeds(dir / "obj_fuzz", nut::fuzz::objSeeds()) &&
                  writeSeeds(dir / "glb_fuzz", nut::fuzz::glbSeeds()) &&
                  writeSeeds(dir / "city_fuzz", nut::fuzz::citySeeds()) &&
                  writeSeeds(dir / "grammar_fuzz", nut::fuzz::grammarSeeds());
  return ok ? 0 : 1;
}
