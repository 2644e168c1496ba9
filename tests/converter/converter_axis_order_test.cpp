// Axis orders (converter/axis_order.hpp): a grid turned into another axis order, under a root that
// turns it back, must hold at every point what the grid held, solids and redirections included. The check looks
// points up through the redirection as docs/FORMAT.md defines it and tests solid containment in
// each cell's unit cube, so a wrong solid orientation, a wrong mirror or a wrong offset shows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include <glm/geometric.hpp>


#include <converter/axis_order.hpp>
#include <nut/format.hpp>
#include <nut/hierarchy.hpp>

#include "redirected_point.hpp"

namespace nut::converter {
namespace {

using testing::contentAt;

// Cells of uneven millimetre widths holding every kind of solid in random orientations, plane cells
// cut by planes at random angles, and cells redirecting to block 0 (a small target of solids)
// turned by random cube rotations, shifted, some tiled.
Block randomGrid(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::array<std::vector<double>, 3> sizes;
  const std::array<int, 3> n{7, 5, 6};
  for (std::size_t a = 0; a < 3; ++a)
    for (int i = 0; i < n[a]; ++i) sizes[a].push_back(0.1 + 0.001 * static_cast<double>(rng() % 2000));
  Block b = Block::fromSizes(sizes);
  std::normal_distribution<double> normal;
  for (int k = 0; k < 3; ++k) {
    const glm::dvec3 through = b.sizeM() * glm::dvec3(0.2 + 0.3 * k, 0.5, 0.7 - 0.2 * k);
    PlaneCut cut{{}, static_cast<PlaneCombine>(1 + k)};
    for (CutPlane& plane : cut.planes) {
      plane.normal = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
      plane.offsetM = glm::dot(plane.normal, through);
    }
    b.cuts.push_back(cut);
  }
  for (Cell& c : b.cells) {
    if (rng() % 7 == 0) {
      c = Cell::planeCell(static_cast<std::uint32_t>(rng() % 3), static_cast<std::uint16_t>(rng() % 5));
    } else if (rng() % 5 == 0) {
      c = Cell::redirect(static_cast<std::uint32_t>(b.redirections.size()));
      const glm::dvec3 offset(0.001 * static_cast<double>(rng() % 200), 0.001 * static_cast<double>(rng() % 200), -0.001 * static_cast<double>(rng() % 200));
      b.redirections.push_back(Redirection{0, offset, Rotation{static_cast<std::uint8_t>(rng() % format::kCubeRotationCount), 0},
                                           {rng() % 2 == 0, false, rng() % 2 == 0}});
    } else if (rng() % 4 != 0) {
      c = Cell::solidCell(Solid{static_cast<std::uint8_t>(rng() % kSolidCount)}, static_cast<std::uint16_t>(rng() % 5));
    }
  }
  return b;
}

// The redirection target: 3 x 2 x 2 cells of solids.
Block targetBlock() {
  Block t = Block::fromSizes({{{0.05, 0.11, 0.07}, {0.09, 0.06}, {0.08, 0.1}}});
  for (std::size_t i = 0; i < t.cells.size(); ++i)
    if (i % 3 != 1) t.cells[i] = Cell::solidCell(Solid{static_cast<std::uint8_t>((7 * i) % kSolidCount)}, static_cast<std::uint16_t>(i % 5));
  return t;
}

TEST(AxisOrder, TurnedGridUnderItsRootHoldsWhatTheGridHeld) {
  const Block grid = randomGrid(7);
  Hierarchy reference;
  reference.addBlock(targetBlock());
  const BlockId gridId = reference.addBlock(grid);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int cube = 0; cube < format::kCubeRotationCount; ++cube) {
    const TurnedBlock turned = turnBlock(grid, cube);
    Hierarchy h;
    h.addBlock(targetBlock());
    h.root = h.addBlock(turned.block);
    wrapRoot(h, grid.sizeM(), cube, turned.offsetM);
    int mismatches = 0, solid = 0;
    for (int i = 0; i < 20000; ++i) {
      const glm::dvec3 p = glm::dvec3(unit(rng), unit(rng), unit(rng)) * grid.sizeM();
      const int expected = contentAt(reference, gridId, p);
      mismatches += contentAt(h, h.root, p) != expected;
      solid += expected >= 0;
    }
    EXPECT_EQ(mismatches, 0) << "rotation " << cube;
    EXPECT_GT(solid, 5000);  // the points do test solids
  }
}

// One rotation per order of the axes, the identity first.
TEST(AxisOrder, OneRotationPerOrderOfTheAxes) {
  const std::vector<int> rotations = axisOrderRotations();
  ASSERT_EQ(rotations.size(), 6u);
  EXPECT_EQ(rotations.front(), 0);
  std::set<std::array<int, 3>> orders;
  for (int r : rotations) {
    const auto m = cubeRotationMatrix(r);
    std::array<int, 3> order{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (m[i][j] != 0) order[static_cast<std::size_t>(i)] = j;
    orders.insert(order);
  }
  EXPECT_EQ(orders.size(), 6u);
}

}  // namespace
}  // namespace nut::converter
