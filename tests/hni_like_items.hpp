// The rectangles an HNI of `blocks` blocks packs, for the packer's test and benchmark (one
// generator, so that the benchmark's waste matches the test's): per block a 12x1 header, three
// Mx2 metadata items and an (nx*nz) x ny data component; plus a few redirection runs (4 texels
// per redirection) and a material row.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <packer/maxrects.hpp>

namespace packer::testing {

inline int randomInt(std::mt19937& rng, int lo, int hi) {
  return lo + static_cast<int>(rng() % static_cast<std::uint32_t>(hi - lo + 1));
}

inline std::vector<Item> hniLikeItems(std::uint32_t seed, int blocks) {
  std::mt19937 rng(seed);
  std::vector<Item> items;
  auto add = [&](int width, int height) {
    items.push_back({.id = static_cast<int>(items.size()), .width = width, .height = height});
  };
  for (int b = 0; b < blocks; ++b) {
    add(12, 1);
    for (int k = 0; k < 3; ++k) add(randomInt(rng, 2, 40), 2);
    const int nx = randomInt(rng, 1, 12), ny = randomInt(rng, 1, 12), nz = randomInt(rng, 1, 12);
    add(nx * nz, ny);
  }
  for (int r = randomInt(rng, 1, 4); r > 0; --r) add(4 * randomInt(rng, 1, 8), 1);
  add(randomInt(rng, 8, 64), 1);
  return items;
}

}  // namespace packer::testing
