// `fuzz_seeds DIR`: writes framed HNIs of seeded random hierarchies as a starting corpus.
#include <cstdio>
#include <fstream>
#include <string>

#include <nut/hni.hpp>

#include "../random_hierarchy.hpp"
#include "frame.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: fuzz_seeds DIR\n");
    return 1;
  }
  for (std::uint64_t seed = 0; seed < 32; ++seed) {
    auto image = nut::compile(nut::testing::randomHierarchy(seed));
    if (!image) {
      std::fprintf(stderr, "error: seed %llu: %s\n", static_cast<unsigned long long>(seed), image.error().message.c_str());
      return 1;
    }
    const auto bytes = nut::fuzz::frame(*image);
    std::ofstream(std::string(argv[1]) + "/seed" + std::to_string(seed), std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  }
  return 0;
}
