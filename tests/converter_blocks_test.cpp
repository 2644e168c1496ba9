// Hierarchy assembly of the converter: blocks split to the format's limits and blocks extracted
// from repeats must show exactly what the solid grid G0 showed. The check samples points (cell
// centres and random points) of G0 and of the hierarchy with a point lookup that follows
// redirections as docs/FORMAT.md defines them (offset, rotation, wrap, clipping by the cell).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <converter/assemble.hpp>
#include <converter/blocks.hpp>
#include <nut/hni.hpp>

#include "redirected_point.hpp"

namespace nut::converter {
namespace {

// What a point of block `id` (block-local metres) holds: the solid cell's material and solid, or
// nothing. Points within `margin` of a boundary are skipped by the callers, so which cell a point
// on a boundary belongs to never matters.
struct Sample {
  bool solid = false;
  std::uint16_t material = 0;
  std::uint8_t shape = 0;
  friend bool operator==(const Sample&, const Sample&) = default;
};

Sample lookup(const Hierarchy& h, BlockId id, glm::dvec3 p, int depth = 0) {
  const Block& b = h.blocks[id];
  std::array<int, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
    if (p[a] < 0 || p[a] >= bounds.back()) return {};
    c[static_cast<std::size_t>(a)] = static_cast<int>(std::upper_bound(bounds.begin(), bounds.end(), p[a]) - bounds.begin()) - 1;
  }
  const Cell& cell = b.cell(c[0], c[1], c[2]);
  if (cell.kind == CellKind::Empty) return {};
  if (cell.kind == CellKind::Solid) return {true, cell.material, cell.solid.index};
  if (depth > 32) return {};
  const Redirection& r = b.redirections[cell.redirection];
  return lookup(h, r.target, testing::redirectedPoint(h, b, c, r, p), depth + 1);
}

// Whether p is at least `margin` away from every boundary of G0.
bool awayFromBoundaries(const Block& g0, const glm::dvec3& p, double margin) {
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = g0.boundsM[static_cast<std::size_t>(a)];
    const auto it = std::lower_bound(bounds.begin(), bounds.end(), p[a]);
    if (it != bounds.end() && *it - p[a] < margin) return false;
    if (it != bounds.begin() && p[a] - *(it - 1) < margin) return false;
  }
  return true;
}

// Every cell centre and `randomPoints` random points of g0 hold the same in h.
void expectSameContent(const Block& g0, const Hierarchy& h, int randomPoints, std::uint32_t seed) {
  Hierarchy reference;
  reference.addBlock(g0);
  long long checked = 0;
  for (int z = 0; z < g0.cellCount(2); ++z)
    for (int y = 0; y < g0.cellCount(1); ++y)
      for (int x = 0; x < g0.cellCount(0); ++x) {
        const glm::dvec3 p(0.5 * (g0.boundsM[0][static_cast<std::size_t>(x)] + g0.boundsM[0][static_cast<std::size_t>(x + 1)]),
                           0.5 * (g0.boundsM[1][static_cast<std::size_t>(y)] + g0.boundsM[1][static_cast<std::size_t>(y + 1)]),
                           0.5 * (g0.boundsM[2][static_cast<std::size_t>(z)] + g0.boundsM[2][static_cast<std::size_t>(z + 1)]));
        ASSERT_EQ(lookup(reference, 0, p), lookup(h, h.root, p)) << "cell " << x << "," << y << "," << z;
        ++checked;
      }
  std::mt19937 rng(seed);
  const glm::dvec3 size = g0.sizeM();
  for (int i = 0; i < randomPoints; ++i) {
    std::uniform_real_distribution<double> d(0.0, 1.0);
    const glm::dvec3 p(d(rng) * size.x, d(rng) * size.y, d(rng) * size.z);
    if (!awayFromBoundaries(g0, p, 0.002)) continue;
    ASSERT_EQ(lookup(reference, 0, p), lookup(h, h.root, p)) << "point " << p.x << "," << p.y << "," << p.z;
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

// A block of n cells per axis with widths from `widths` (cycled) and seeded random content.
Block randomBlock(std::array<int, 3> n, const std::vector<double>& widths, std::uint32_t seed, double fill) {
  std::mt19937 rng(seed);
  std::array<std::vector<double>, 3> sizes;
  for (int a = 0; a < 3; ++a)
    for (int i = 0; i < n[static_cast<std::size_t>(a)]; ++i) sizes[static_cast<std::size_t>(a)].push_back(widths[static_cast<std::size_t>(i) % widths.size()]);
  Block b = Block::fromSizes(sizes);
  std::uniform_real_distribution<double> d(0.0, 1.0);
  for (Cell& c : b.cells)
    if (d(rng) < fill) c = Cell::box(static_cast<std::uint16_t>(rng() % 3));
  return b;
}

TEST(SplitBlocks, AxisWithMoreThan256CellsIsSplitAndKeepsItsContent) {
  const Block g0 = randomBlock({600, 3, 2}, {0.25, 0.5, 0.1}, 1, 0.4);
  Hierarchy h;
  h.materials = {Material{}, Material{10, 20, 30}, Material{90, 80, 70}};
  h.addBlock(g0);
  EXPECT_FALSE(blockFits(h.blocks[0]));
  auto added = splitBlocks(h);
  ASSERT_TRUE(added.ok()) << added.error().message;
  EXPECT_GE(*added, 3);
  for (const Block& b : h.blocks) EXPECT_TRUE(blockFits(b));
  expectSameContent(g0, h, 2000, 2);
  EXPECT_TRUE(compile(h).ok());
}

TEST(SplitBlocks, ThinCellsInALongBlockAreSplitOff) {
  // 1 cm cells in a 200 m block: each boundary needs its own metadata pixel of D / M, impossible
  // with M <= 256.
  std::vector<double> widths(40, 0.01);
  widths.push_back(200.0);
  const Block g0 = randomBlock({41, 2, 2}, widths, 3, 0.5);
  Hierarchy h;
  h.materials = {Material{}, Material{10, 20, 30}, Material{90, 80, 70}};
  h.addBlock(g0);
  EXPECT_FALSE(blockFits(h.blocks[0]));
  ASSERT_TRUE(splitBlocks(h).ok());
  for (const Block& b : h.blocks) EXPECT_TRUE(blockFits(b));
  expectSameContent(g0, h, 2000, 4);
  EXPECT_TRUE(compile(h).ok());
}

TEST(SplitBlocks, WideDataComponentIsSplit) {
  const Block g0 = randomBlock({100, 4, 90}, {0.3, 0.7}, 5, 0.3);
  Hierarchy h;
  h.materials = {Material{}, Material{10, 20, 30}, Material{90, 80, 70}};
  h.addBlock(g0);
  EXPECT_FALSE(blockFits(h.blocks[0]));
  ASSERT_TRUE(splitBlocks(h).ok());
  for (const Block& b : h.blocks) EXPECT_TRUE(blockFits(b));
  expectSameContent(g0, h, 2000, 6);
  EXPECT_TRUE(compile(h).ok());
}

}  // namespace
}  // namespace nut::converter
