#include "random_hierarchy.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

namespace nut::testing {

Hierarchy randomHierarchy(std::uint64_t seed, const RandomHierarchyOptions& o) {
  std::mt19937_64 rng(seed);
  std::mt19937_64 surfaceRng(~seed);
  const auto uniformInt = [&](int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng); };
  const auto uniformReal = [&](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  const auto length = [&](double lo, double hi) {
    // Log-uniform sizes: both centimetre details and storey-sized cells.
    return std::exp(uniformReal(std::log(lo), std::log(hi)));
  };

  Hierarchy h;
  const int materials = uniformInt(1, 12);
  for (int m = 0; m < materials; ++m)
    h.materials.push_back({static_cast<std::uint8_t>(uniformInt(0, 255)), static_cast<std::uint8_t>(uniformInt(0, 255)),
                           static_cast<std::uint8_t>(uniformInt(0, 255)),
                           static_cast<std::uint8_t>(uniformInt(0, 3) == 0 ? uniformInt(0, 255) : 255),
                           static_cast<std::uint8_t>(uniformInt(0, 255))});
  const int textures = uniformInt(0, 3);
  for (int t = 0; t < textures; ++t)
    h.textures.push_back({{uniformReal(-50, 50), uniformReal(-50, 50), uniformReal(-50, 50)},
                          static_cast<std::uint16_t>(uniformInt(0, 65535))});

  const int blocks = uniformInt(o.minBlocks, o.maxBlocks);
  for (int b = 0; b < blocks; ++b) {
    // Cells within a factor of 16 of each other on an axis, so that the block can be indexed
    // (paper 3.2: the widest / narrowest ratio bounds W + w).
    std::array<std::vector<double>, 3> sizes;
    for (auto& axis : sizes) {
      const double base = length(o.minCellM, o.maxCellM);
      const int n = uniformInt(1, o.maxCellsPerAxis);
      for (int i = 0; i < n; ++i) axis.push_back(std::max(0.002, length(base / 4, base * 4)));
    }
    Block block = Block::fromSizes(sizes);
    const bool canRedirect = b + 1 < blocks;
    if (canRedirect) {
      const int count = uniformInt(1, 3);
      for (int r = 0; r < count; ++r) {
        Redirection red;
        red.target = static_cast<BlockId>(uniformInt(b + 1, blocks - 1));
        red.offsetM = {uniformReal(-5, 5), uniformReal(-5, 5), uniformReal(-5, 5)};
        red.rotation.cube = static_cast<std::uint8_t>(uniformInt(0, 23));
        red.rotation.yaw = static_cast<std::uint16_t>(uniformInt(0, 3) == 0 ? uniformInt(0, 65535) : 0);
        red.wrap = {uniformInt(0, 1) == 1, uniformInt(0, 1) == 1, uniformInt(0, 1) == 1};
        block.redirections.push_back(red);
      }
    }
    if (o.planeCellShare > 0) {
      const glm::dvec3 size = block.sizeM();
      const auto randomPlane = [&] {
        glm::dvec3 n;
        do n = {uniformReal(-1, 1), uniformReal(-1, 1), uniformReal(-1, 1)};
        while (glm::length(n) < 0.1 || glm::length(n) > 1);
        n = glm::normalize(n);
        // Some planes nearly along an axis, where a ray grazes many cells.
        if (uniformInt(0, 3) == 0) n = glm::normalize(glm::dvec3(n.x, n.y * 1e-3, n.z * 1e-4));
        const glm::dvec3 through{uniformReal(0, size.x), uniformReal(0, size.y), uniformReal(0, size.z)};
        return CutPlane{n, glm::dot(n, through)};
      };
      const int cuts = uniformInt(1, 4);
      for (int k = 0; k < cuts; ++k) {
        PlaneCut cut{{randomPlane(), randomPlane()}, static_cast<PlaneCombine>(uniformInt(1, 3)), {}};
        // Some planes show a material of their own, drawn from a stream of their own so that a
        // seed's geometry does not depend on them.
        for (auto& surface : cut.surfaceMaterials)
          if (std::uniform_int_distribution<int>(0, 1)(surfaceRng) == 1)
            surface = static_cast<std::uint16_t>(std::uniform_int_distribution<int>(0, materials - 1)(surfaceRng));
        block.cuts.push_back(cut);
      }
    }
    for (Cell& c : block.cells) {
      const int kind = uniformInt(0, 9);
      if (kind < 3) continue;  // empty
      if (kind < 5 && canRedirect) {
        c = Cell::redirect(static_cast<std::uint32_t>(uniformInt(0, static_cast<int>(block.redirections.size()) - 1)));
      } else if (o.planeCellShare > 0 && uniformReal(0, 1) < o.planeCellShare) {
        c = Cell::planeCell(static_cast<std::uint32_t>(uniformInt(0, static_cast<int>(block.cuts.size()) - 1)),
                            static_cast<std::uint16_t>(uniformInt(0, materials - 1)),
                            static_cast<std::uint8_t>(uniformInt(0, textures)));
      } else {
        c = Cell::solidCell(Solid{static_cast<std::uint8_t>(uniformInt(0, kSolidCount - 1))},
                            static_cast<std::uint16_t>(uniformInt(0, materials - 1)),
                            static_cast<std::uint8_t>(uniformInt(0, textures)));
      }
    }
    h.addBlock(std::move(block));
  }
  return h;
}

}  // namespace nut::testing
