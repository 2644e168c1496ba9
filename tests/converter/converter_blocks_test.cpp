// Hierarchy assembly of the converter: blocks split to the format's limits and blocks extracted
// from repeats must show exactly what the solid grid G0 showed. The check samples points (cell
// centres and random points) of G0 and of the hierarchy with a point lookup that follows
// redirections as docs/FORMAT.md defines them (offset, rotation, wrap, clipping by the cell).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include <glm/geometric.hpp>

#include <converter/assemble.hpp>
#include <converter/blocks.hpp>
#include <converter/share_axes.hpp>
#include <nut/format.hpp>
#include <nut/hni.hpp>
#include <nut/solids.hpp>

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
  if (cell.kind == CellKind::Plane)
    return cutContains(b.cuts[cell.cut], p) ? Sample{true, cell.material, format::kCellPlane} : Sample{};
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

// g0 does not fit the format; splitBlocks makes every block fit, keeps g0's content (probed at
// 2000 points with `seed`) and the result compiles. Returns how many blocks it added.
int expectSplitToFit(const Block& g0, std::uint32_t seed) {
  Hierarchy h;
  h.materials = {Material{}, Material{10, 20, 30}, Material{90, 80, 70}};
  h.addBlock(g0);
  EXPECT_FALSE(blockFits(h.blocks[0]));
  auto added = splitBlocks(h);
  EXPECT_TRUE(added.ok()) << added.error().message;
  if (!added.ok()) return 0;
  for (const Block& b : h.blocks) EXPECT_TRUE(blockFits(b));
  expectSameContent(g0, h, 2000, seed);
  EXPECT_TRUE(compile(h).ok());
  return *added;
}

// randomBlock with a share of its cells made plane cells of three cuts at odd angles through it.
Block withPlaneCells(Block b, std::uint32_t seed, double share) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 3; ++k) {
    PlaneCut cut{{}, static_cast<PlaneCombine>(1 + k)};
    for (CutPlane& plane : cut.planes) {
      plane.normal = glm::normalize(glm::dvec3(normal(rng), normal(rng), normal(rng)));
      plane.offsetM = glm::dot(plane.normal, b.sizeM() * glm::dvec3(unit(rng), unit(rng), unit(rng)));
    }
    b.cuts.push_back(cut);
  }
  for (Cell& c : b.cells)
    if (unit(rng) < share) c = Cell::planeCell(static_cast<std::uint32_t>(rng() % 3), static_cast<std::uint16_t>(rng() % 3));
  return b;
}

TEST(SplitBlocks, AxisWithMoreThan256CellsIsSplitAndKeepsItsContent) {
  EXPECT_GE(expectSplitToFit(randomBlock({600, 3, 2}, {0.25, 0.5, 0.1}, 1, 0.4), 2), 3);
}

TEST(SplitBlocks, ThinCellsInALongBlockAreSplitOff) {
  // 1 cm cells in a 200 m block: each boundary needs its own metadata pixel of D / M, impossible
  // with M <= 256.
  std::vector<double> widths(40, 0.01);
  widths.push_back(200.0);
  expectSplitToFit(randomBlock({41, 2, 2}, widths, 3, 0.5), 4);
}

TEST(SplitBlocks, WideDataComponentIsSplit) {
  expectSplitToFit(randomBlock({100, 4, 90}, {0.3, 0.7}, 5, 0.3), 6);
}

// --- Manual blocks (`nut convert --block`): the paper's one-to-many cell matching ---------------

// A block with the given boundaries per axis, every cell set by `content` from its centre.
template <typename F>
Block blockFromBounds(const std::array<std::vector<double>, 3>& bounds, F content) {
  Block b;
  b.boundsM = bounds;
  b.cells.assign(static_cast<std::size_t>(b.cellCount(0)) * static_cast<std::size_t>(b.cellCount(1)) * static_cast<std::size_t>(b.cellCount(2)),
                 Cell::empty());
  for (int z = 0; z < b.cellCount(2); ++z)
    for (int y = 0; y < b.cellCount(1); ++y)
      for (int x = 0; x < b.cellCount(0); ++x) {
        const glm::dvec3 c(0.5 * (bounds[0][static_cast<std::size_t>(x)] + bounds[0][static_cast<std::size_t>(x + 1)]),
                           0.5 * (bounds[1][static_cast<std::size_t>(y)] + bounds[1][static_cast<std::size_t>(y + 1)]),
                           0.5 * (bounds[2][static_cast<std::size_t>(z)] + bounds[2][static_cast<std::size_t>(z + 1)]));
        b.cell(x, y, z) = content(c);
      }
  return b;
}

std::vector<double> sortedUnique(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// A facade (x along it, y into the wall, z up) of 2 floors of 6 bays, 3 m by 3 m each, with a
// window 1.2 m wide and 1.4 m high in every bay: a 0.1 m recess in front of glass (material 2) in a
// wall of material 1. Two things elsewhere cut some of the windows in the global grid:
//   - a sign (material 3) on the wall above the ground-floor windows from x = 4.6 to 10.9 cuts the
//     windows of bays 1 (0.6 m in) and 3 (0.9 m in) on both floors;
//   - a bracket on a pipe beside the facade (x 18 to 18.3) at z 4.3 to 4.4 cuts all first-floor
//     windows.
// Only the ground-floor windows of bays 0, 2, 4 and 5 are whole cells.
struct FacadeVariant {
  double bay1Wider = 0.0;        // bay 1's window this much wider (m)
  bool bay3GroundOdd = false;    // the glass right of the sign's cut in bay 3, ground floor, is material 4
  std::uint8_t glassSolid = 0;   // the glass cells' solid (0: box)
};
constexpr int kFloors = 2, kBays = 6;

Block facade(const FacadeVariant& v = {}) {
  std::vector<double> xs{0.0, 4.6, 10.9, 18.0, 18.3}, ys{0.0, 0.1, 0.3}, zs{0.0, 2.6, 2.9, 4.3, 4.4, 6.0};
  const auto windowX = [&](int bay) {
    const double l = 3.0 * bay + 1.0;
    return std::pair<double, double>{l, l + 1.2 + (bay == 1 ? v.bay1Wider : 0.0)};
  };
  for (int bay = 0; bay < kBays; ++bay) {
    xs.push_back(windowX(bay).first);
    xs.push_back(windowX(bay).second);
    xs.push_back(3.0 * bay + 3.0);
  }
  for (int f = 0; f < kFloors; ++f) {
    zs.push_back(3.0 * f + 1.0);
    zs.push_back(3.0 * f + 2.4);
  }
  return blockFromBounds({sortedUnique(xs), ys, sortedUnique(zs)}, [&](const glm::dvec3& c) {
    if (c.x > 18.0) return c.y < 0.1 && c.z > 4.3 && c.z < 4.4 ? Cell::box(1) : Cell::empty();  // the bracket
    const int bay = static_cast<int>(c.x / 3.0), floor = static_cast<int>(c.z / 3.0);
    const double zf = c.z - 3.0 * floor;
    const bool inWindow = c.x > windowX(bay).first && c.x < windowX(bay).second && zf > 1.0 && zf < 2.4;
    if (inWindow) {
      if (c.y < 0.1) return Cell::empty();
      const std::uint16_t glass = v.bay3GroundOdd && bay == 3 && floor == 0 && c.x > 10.9 ? 4 : 2;
      return Cell::solidCell(Solid{v.glassSolid}, glass);
    }
    if (c.y < 0.1 && c.x > 4.6 && c.x < 10.9 && c.z > 2.6 && c.z < 2.9) return Cell::box(3);  // the sign
    return Cell::box(1);
  });
}

// A box around the window of `bay` on `floor`, 1 cm inside it (snapped outwards to its cells).
WorldBox windowBox(int bay, int floor) {
  const glm::dvec3 lo(3.0 * bay + 1.0, 0.0, 3.0 * floor + 1.0);
  return {lo + glm::dvec3(0.01), lo + glm::dvec3(1.19, 0.29, 1.39)};
}

struct ManualResult {
  Hierarchy h;
  BlockStats stats;
};
ManualResult extractManualOnly(const Block& g0, const WorldBox& box, double tolerance = 0.01) {
  BlockOptions options;
  options.automatic = false;
  options.manual = {box};
  options.toleranceM = tolerance;
  ManualResult r;
  auto h = buildHierarchy(g0, {Material{}, Material{200, 200, 200}, Material{40, 60, 90}, Material{200, 30, 30}, Material{10, 90, 10}},
                          glm::dvec3(0.0), options, r.stats);
  EXPECT_TRUE(h.ok());
  if (h.ok()) r.h = std::move(*h);
  return r;
}

// Cell-for-cell matching: places of g0 whose cells match the box's cells one for one (widths
// within the tolerance, identical cells), not overlapping, found in scan order.
int cellForCellPlaces(const Block& g0, const WorldBox& box, double tolerance = 0.01) {
  std::array<int, 3> lo{}, n{};
  for (int a = 0; a < 3; ++a) {
    const auto& b = g0.boundsM[static_cast<std::size_t>(a)];
    lo[static_cast<std::size_t>(a)] = static_cast<int>(std::upper_bound(b.begin(), b.end(), box.min[a]) - b.begin()) - 1;
    n[static_cast<std::size_t>(a)] = static_cast<int>(std::lower_bound(b.begin(), b.end(), box.max[a]) - b.begin()) - lo[static_cast<std::size_t>(a)];
  }
  const auto width = [&](int a, int i) {
    return g0.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(i + 1)] - g0.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(i)];
  };
  std::vector<bool> taken(g0.cells.size(), false);
  int places = 0;
  for (int z = 0; z + n[2] <= g0.cellCount(2); ++z)
    for (int y = 0; y + n[1] <= g0.cellCount(1); ++y)
      for (int x = 0; x + n[0] <= g0.cellCount(0); ++x) {
        const std::array<int, 3> at{x, y, z};
        bool match = true;
        for (int a = 0; a < 3 && match; ++a)
          for (int i = 0; i < n[static_cast<std::size_t>(a)] && match; ++i)
            match = std::abs(width(a, at[static_cast<std::size_t>(a)] + i) - width(a, lo[static_cast<std::size_t>(a)] + i)) <= tolerance;
        for (int k = 0; k < n[2] && match; ++k)
          for (int j = 0; j < n[1] && match; ++j)
            for (int i = 0; i < n[0] && match; ++i)
              match = !taken[g0.cellIndex(x + i, y + j, z + k)] && g0.cell(x + i, y + j, z + k) == g0.cell(lo[0] + i, lo[1] + j, lo[2] + k);
        if (!match) continue;
        ++places;
        for (int k = 0; k < n[2]; ++k)
          for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i) taken[g0.cellIndex(x + i, y + j, z + k)] = true;
      }
  return places;
}

int redirectionCells(const Block& b) {
  return static_cast<int>(std::count_if(b.cells.begin(), b.cells.end(), [](const Cell& c) { return c.kind == CellKind::Redirection; }));
}

TEST(ManualBlocks, WindowCutByBoundariesFromElsewhereIsFoundEverywhere) {
  const Block g0 = facade();
  const WorldBox box = windowBox(0, 0);  // a whole window
  EXPECT_EQ(cellForCellPlaces(g0, box), 4);  // the ground-floor windows of bays 0, 2, 4 and 5
  const ManualResult r = extractManualOnly(g0, box);
  ASSERT_EQ(r.stats.found.size(), 1u);
  const ExtractedBlock& found = r.stats.found[0];
  EXPECT_TRUE(found.manual);
  EXPECT_EQ(found.instances, kFloors * kBays);
  EXPECT_EQ(found.cells, (std::array<int, 3>{1, 2, 1}));  // recess and glass
  EXPECT_NEAR(found.sizeM.x, 1.2, 1e-9);
  expectSameContent(g0, r.h, 20000, 11);
  // Every window cell redirects (4 whole windows of 2 cells, 8 cut ones of 4 or 6 or 12 cells).
  const Block& root = r.h.blocks[r.h.root];
  EXPECT_EQ(redirectionCells(root), 4 * 2 + 2 * 4 + 4 * 6 + 2 * 12);
  // One record per distinct offset: x in {0, 0.6, 0.9} (the sign's cuts), y in {0, 0.1}, z in
  // {0, 0.3, 0.4} (the bracket's cuts), all used.
  ASSERT_EQ(root.redirections.size(), 18u);
  std::set<std::array<long long, 3>> offsets;
  for (const Redirection& red : root.redirections) {
    EXPECT_EQ(red.target, found.block);
    offsets.insert({std::llround(red.offsetM.x * 1000), std::llround(red.offsetM.y * 1000), std::llround(red.offsetM.z * 1000)});
  }
  EXPECT_EQ(offsets.size(), 18u);
  EXPECT_TRUE(offsets.count({-600, -100, -400}));
  EXPECT_TRUE(offsets.count({-900, 0, -300}));
}

TEST(ManualBlocks, BlockSelectedOnACutWindowFindsTheWholeOnes) {
  const Block g0 = facade();
  const WorldBox box = windowBox(1, 1);  // cut by the sign's edge (x) and the bracket (z)
  EXPECT_EQ(cellForCellPlaces(g0, box), 1);  // only itself: bay 3 is cut elsewhere
  const ManualResult r = extractManualOnly(g0, box);
  ASSERT_EQ(r.stats.found.size(), 1u);
  EXPECT_EQ(r.stats.found[0].cells, (std::array<int, 3>{1, 2, 1}));  // simplified: the cuts are gone
  EXPECT_EQ(r.stats.found[0].instances, kFloors * kBays);
  expectSameContent(g0, r.h, 20000, 12);
}

TEST(ManualBlocks, NearMissesAreNotMatched) {
  {
    // Bay 1's window 2 cm wider: its two cells (split by the sign) sum 2 cm off, beyond 1 cm.
    const Block g0 = facade({.bay1Wider = 0.02});
    const ManualResult r = extractManualOnly(g0, windowBox(0, 0));
    ASSERT_EQ(r.stats.found.size(), 1u);
    EXPECT_EQ(r.stats.found[0].instances, kFloors * kBays - 2);
    expectSameContent(g0, r.h, 5000, 13);
  }
  {
    // 5 mm wider is within the tolerance: matched.
    const ManualResult r = extractManualOnly(facade({.bay1Wider = 0.005}), windowBox(0, 0));
    ASSERT_EQ(r.stats.found.size(), 1u);
    EXPECT_EQ(r.stats.found[0].instances, kFloors * kBays);
  }
  {
    // The part of bay 3's ground-floor glass right of the sign's cut has another material.
    const Block g0 = facade({.bay3GroundOdd = true});
    const ManualResult r = extractManualOnly(g0, windowBox(0, 0));
    ASSERT_EQ(r.stats.found.size(), 1u);
    EXPECT_EQ(r.stats.found[0].instances, kFloors * kBays - 1);
    expectSameContent(g0, r.h, 5000, 14);
  }
  {
    // Glass that is not a box (a wedge) does not look the same cut in two: only whole windows match.
    const Block g0 = facade({.glassSolid = makeSolid(SolidGroup::Wedge, 0).index});
    const ManualResult r = extractManualOnly(g0, windowBox(0, 0));
    ASSERT_EQ(r.stats.found.size(), 1u);
    EXPECT_EQ(r.stats.found[0].instances, 4);
    expectSameContent(g0, r.h, 5000, 15);
  }
}

TEST(ManualBlocks, PlacesMatchingCellForCellStillMatch) {
  // Three pairs of box cells with gaps; the pair selected merges into one 2 m cell of S. The last
  // pair is 8 mm too wide per cell: each within the 1 cm tolerance, the pair's sum not, so only
  // matching the selection cell for cell (against the unsimplified selection) finds it.
  const std::vector<double> xs{0.0, 1.0, 2.0, 2.5, 3.5, 4.5, 5.0, 6.008, 7.016, 7.5};
  const Block g0 = blockFromBounds({xs, {0.0, 1.0}, {0.0, 1.0}}, [](const glm::dvec3& c) {
    const bool gap = (c.x > 2.0 && c.x < 2.5) || (c.x > 4.5 && c.x < 5.0) || c.x > 7.016;
    return gap ? Cell::empty() : Cell::box(1);
  });
  const WorldBox box{{0.01, 0.01, 0.01}, {1.99, 0.99, 0.99}};
  EXPECT_EQ(cellForCellPlaces(g0, box), 3);
  const ManualResult r = extractManualOnly(g0, box);
  ASSERT_EQ(r.stats.found.size(), 1u);
  EXPECT_EQ(r.stats.found[0].cells, (std::array<int, 3>{1, 1, 1}));
  EXPECT_EQ(r.stats.found[0].instances, 3);
  // The two cells of each exact place show S at one place and merge into one cell; the last
  // place's second cell starts 8 mm past S's middle, so its two cells stay apart.
  EXPECT_EQ(redirectionCells(r.h.blocks[r.h.root]), 1 + 1 + 2);
}


// Three cells along x, each redirecting to block 0 with the given x offsets (metres).
Block threeRedirectingCells(const std::array<double, 3>& offsetsX, const std::array<BlockId, 3>& targets = {0, 0, 0}) {
  Block b = blockFromBounds(std::array<std::vector<double>, 3>{{{0.0, 0.4, 1.0, 2.5}, {0.0, 1.0}, {0.0, 1.0}}}, [](const glm::dvec3&) { return Cell::empty(); });
  for (int x = 0; x < 3; ++x) {
    b.cell(x, 0, 0) = Cell::redirect(static_cast<std::uint32_t>(x));
    b.redirections.push_back(Redirection{targets[static_cast<std::size_t>(x)], glm::dvec3(offsetsX[static_cast<std::size_t>(x)], 0.0, 0.0), Rotation{}, {false, false, false}});
  }
  return b;
}

TEST(Simplify, CellsPlacingABlockAtOnePlaceMerge) {
  // The target's origin is at x = 0.1 for all three cells: they show one placement of it.
  Block b = threeRedirectingCells({0.1, -0.3, -0.9});
  simplify(b);
  ASSERT_EQ(b.cellCount(0), 1);
  ASSERT_EQ(b.cells[0].kind, CellKind::Redirection);
  EXPECT_NEAR(b.redirections[b.cells[0].redirection].offsetM.x, 0.1, 1e-12);
}

TEST(Simplify, CellsPlacingABlockAtDifferentPlacesStayApart) {
  Block shifted = threeRedirectingCells({0.1, -0.3, -0.8});  // the third places it 0.1 m further
  simplify(shifted);
  EXPECT_EQ(shifted.cellCount(0), 2);
  Block otherTarget = threeRedirectingCells({0.1, -0.3, -0.9}, {0, 1, 0});
  simplify(otherTarget);
  EXPECT_EQ(otherTarget.cellCount(0), 3);
}

// Whether point p of block `id` is inside a solid, and its material: follows redirections and
// tests the point against the cell's solid (a plain box and a quarter cylinder holding the same
// point agree).
std::optional<std::uint16_t> materialAt(const Hierarchy& h, BlockId id, glm::dvec3 p, int depth = 0) {
  const Block& b = h.blocks[id];
  std::array<int, 3> c{};
  glm::dvec3 unit;
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
    if (p[a] < 0 || p[a] >= bounds.back()) return std::nullopt;
    const auto i = static_cast<std::size_t>(std::upper_bound(bounds.begin(), bounds.end(), p[a]) - bounds.begin()) - 1;
    c[static_cast<std::size_t>(a)] = static_cast<int>(i);
    unit[a] = (p[a] - bounds[i]) / (bounds[i + 1] - bounds[i]);
  }
  const Cell& cell = b.cell(c[0], c[1], c[2]);
  if (cell.kind == CellKind::Solid) return solidContains(cell.solid, unit) ? std::optional(cell.material) : std::nullopt;
  if (cell.kind == CellKind::Empty || depth > 32) return std::nullopt;
  const Redirection& r = b.redirections[cell.redirection];
  return materialAt(h, r.target, testing::redirectedPoint(h, b, c, r, p), depth + 1);
}

// A quarter cylinder of radius 1 m along y, its edge at x = z = 1 (sub-block 0, one cell 2 m tall).
Block quarterCylinderPiece() {
  return blockFromBounds(std::array<std::vector<double>, 3>{{{0.0, 1.0}, {0.0, 2.0}, {0.0, 1.0}}}, [](const glm::dvec3&) {
    return Cell::solidCell(makeSolid(SolidGroup::QuarterCylinder, 1 * 4 + 3), 1);
  });
}

// Redirects the cells of g0's bottom layer within the corner box [0, 1) x [0, 1) (the first n
// cells along x and z) to the piece, each offset by minus its place in the box.
void redirectCornerBox(Block& g0, int n) {
  for (int z = 0; z < n; ++z)
    for (int x = 0; x < n; ++x) {
      g0.cell(x, 0, z) = Cell::redirect(static_cast<std::uint32_t>(g0.redirections.size()));
      g0.redirections.push_back(Redirection{0, -glm::dvec3(g0.boundsM[0][static_cast<std::size_t>(x)], 0.0, g0.boundsM[2][static_cast<std::size_t>(z)]),
                                            Rotation{}, {false, false, false}});
    }
}

Hierarchy referenceOf(const Block& piece, const Block& g0) {
  Hierarchy reference;
  reference.addBlock(piece);
  reference.root = reference.addBlock(g0);
  reference.materials = {Material{}, Material{200, 200, 200}, Material{40, 60, 90}};
  return reference;
}

long long redirectionCellsToPiece(const Hierarchy& h) {
  long long count = 0;
  for (const Block& b : h.blocks)
    for (const Cell& c : b.cells) count += c.kind == CellKind::Redirection && b.redirections[c.redirection].target == 0;
  return count;
}

// Random points of the 3 x 2 x 3 m scene are inside the same material in both hierarchies.
void expectSameOccupancy(const Hierarchy& reference, const Hierarchy& h, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 p(3.0 * d(rng), 2.0 * d(rng), 3.0 * d(rng));
    ASSERT_EQ(materialAt(reference, reference.root, p), materialAt(h, h.root, p)) << p.x << "," << p.y << "," << p.z;
  }
}

TEST(RoundPieces, CellsOnOneSideOfTheArcBecomePlainCells) {
  // A wall 3 m thick whose corner is the quarter cylinder, its box cut at 0.2 and 0.5 m along x
  // and z by boundaries that a strip in the layer above needs.
  const std::vector<double> xs{0.0, 0.2, 0.5, 1.0, 3.0};
  const Block piece = quarterCylinderPiece();
  Block g0 = blockFromBounds(std::array<std::vector<double>, 3>{xs, {0.0, 1.0, 2.0}, xs}, [](const glm::dvec3& c) {
    if (c.y > 1.0) return c.x < 0.2 || c.z < 0.2 ? Cell::box(2) : Cell::empty();
    return Cell::box(1);
  });
  redirectCornerBox(g0, 3);
  const Hierarchy reference = referenceOf(piece, g0);
  BlockOptions options;
  options.automatic = false;
  BlockStats stats;
  auto h = buildHierarchy(g0, reference.materials, glm::dvec3(0.0), options, stats, {piece});
  ASSERT_TRUE(h.ok());
  // Plain now: inside the arc the cells within [0.5, 1) m on both axes and the two beside it
  // reaching to 0.2 m on one axis, outside it the one within [0, 0.2) on both. The arc passes
  // through the other five, which still redirect.
  EXPECT_EQ(redirectionCellsToPiece(*h), 5);
  expectSameOccupancy(reference, *h, 21);
}

// Twenty strips above the corner cut its box into 20 x 20 cells: in one block its 39 cells on the
// arc cost a record each, so the search cuts the corner's layer off (the cells that saves alone
// would not pay for a block at this threshold), and there the box is one cell.
TEST(RoundPieces, ACutSeparatesAPieceFromTheBoundariesThatCutItsBox) {
  std::vector<double> xs;
  for (int i = 0; i <= 20; ++i) xs.push_back(0.05 * i);
  xs.push_back(3.0);
  const Block piece = quarterCylinderPiece();
  Block g0 = blockFromBounds(std::array<std::vector<double>, 3>{xs, {0.0, 1.0, 2.0}, xs}, [](const glm::dvec3& c) {
    if (c.y < 1.0) return Cell::box(1);
    const bool strip = (c.x < 1.0 && static_cast<int>(c.x * 20) % 2 == 0) || (c.z < 1.0 && static_cast<int>(c.z * 20) % 2 == 0);
    return strip ? Cell::box(2) : Cell::empty();
  });
  redirectCornerBox(g0, 20);
  const Hierarchy reference = referenceOf(piece, g0);
  for (const bool cuts : {false, true}) {
    BlockOptions options;
    options.cuts = cuts;
    options.minSavedCells = 2048;
    BlockStats stats;
    auto h = buildHierarchy(g0, reference.materials, glm::dvec3(0.0), options, stats, {piece});
    ASSERT_TRUE(h.ok());
    if (cuts) {
      EXPECT_EQ(redirectionCellsToPiece(*h), 1);
    } else {
      EXPECT_GT(redirectionCellsToPiece(*h), 30);
    }
    expectSameOccupancy(reference, *h, 22);
  }
}

// Two storeys of one facade, 10 m long, whose x boundaries differ by a door (7 to 7.02 m in one)
// and a window frame (1 to 1.05 m in the other): after shareAxes both have every boundary, so
// compile() stores one x item for both, and both show what they showed. A redirection cell cut
// by a new boundary shows the rest of its target from the right place.
TEST(ShareAxes, StoreysOfAFacadeShareOneItemAndShowTheSame) {
  Hierarchy h;
  h.materials = {Material{}, Material{200, 200, 200}, Material{40, 60, 90}};
  const BlockId target = h.addBlock(blockFromBounds(std::array<std::vector<double>, 3>{{{0.0, 3.0, 6.0}, {0.0, 1.0}, {0.0, 1.0}}},
                                                    [](const glm::dvec3& c) { return Cell::box(c.x < 3.0 ? 1 : 2); }));
  const std::vector<double> lower{0.0, 1.0, 4.0, 7.0, 7.02, 10.0}, upper{0.0, 1.0, 1.05, 4.0, 10.0};
  Block a = blockFromBounds(std::array<std::vector<double>, 3>{lower, {0.0, 3.0}, {0.0, 0.3}},
                            [](const glm::dvec3& c) { return c.x > 7.0 && c.x < 7.02 ? Cell::empty() : Cell::box(1); });
  Block b = blockFromBounds(std::array<std::vector<double>, 3>{upper, {0.0, 3.0}, {0.0, 0.3}},
                            [](const glm::dvec3& c) { return c.x > 1.0 && c.x < 1.05 ? Cell::box(2) : Cell::box(1); });
  // b's last cell, [4, 10), shows the target from 1 m into it: cut at 7 and 7.02 it must go on.
  b.cell(3, 0, 0) = Cell::redirect(0);
  b.redirections.push_back(Redirection{target, glm::dvec3(-1.0, 0.0, 0.0), Rotation{}, {false, false, false}});
  const BlockId ia = h.addBlock(a), ib = h.addBlock(b);
  Block root = blockFromBounds(std::array<std::vector<double>, 3>{{{0.0, 10.0}, {0.0, 3.0, 6.0}, {0.0, 0.3}}}, [](const glm::dvec3&) { return Cell::empty(); });
  for (int y = 0; y < 2; ++y) {
    root.cell(0, y, 0) = Cell::redirect(static_cast<std::uint32_t>(y));
    root.redirections.push_back(Redirection{y == 0 ? ia : ib, glm::dvec3(0.0), Rotation{}, {false, false, false}});
  }
  h.root = h.addBlock(root);
  const Hierarchy before = h;

  EXPECT_EQ(shareAxes(h, 0.002), 2);
  EXPECT_EQ(h.blocks[ia].boundsM[0], h.blocks[ib].boundsM[0]);
  EXPECT_EQ(h.blocks[ia].cellCount(0), 6);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> d(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 p(10.0 * d(rng), 6.0 * d(rng), 0.3 * d(rng));
    ASSERT_EQ(lookup(before, before.root, p), lookup(h, h.root, p)) << p.x << "," << p.y << "," << p.z;
  }
  // The two x items are one in the HNI.
  const auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  EXPECT_LT(computeStats(*image).usedPixels, computeStats(*compile(before)).usedPixels);
}

TEST(ShareAxes, ACellThatLooksDifferentCutIsNotCut) {
  // The same storeys, but the lower one's cell [1, 4) a wedge sloping along x: cut at 1.05 it
  // would show another slope, so neither axis is refined.
  Hierarchy h;
  h.materials = {Material{}, Material{200, 200, 200}};
  const std::vector<double> lower{0.0, 1.0, 4.0, 7.0, 7.02, 10.0}, upper{0.0, 1.0, 1.05, 4.0, 10.0};
  h.addBlock(blockFromBounds(std::array<std::vector<double>, 3>{lower, {0.0, 3.0}, {0.0, 0.3}}, [](const glm::dvec3& c) {
    return c.x > 1.0 && c.x < 4.0 ? Cell::solidCell(makeSolid(SolidGroup::Wedge, 2 * 4), 1) : Cell::box(1);  // extruded along z
  }));
  h.addBlock(blockFromBounds(std::array<std::vector<double>, 3>{upper, {0.0, 3.0}, {0.0, 0.3}}, [](const glm::dvec3&) { return Cell::box(1); }));
  EXPECT_EQ(shareAxes(h, 0.002), 0);
}

TEST(SplitBlocks, PlaneCellsKeepTheirPlanesInEveryPiece) {
  expectSplitToFit(withPlaneCells(randomBlock({600, 3, 2}, {0.25, 0.5, 0.1}, 7, 0.4), 8, 0.3), 9);
}

// Plane cells in grids whose layers repeat: the search must not tile a period holding plane cells
// (their planes cut each place differently) and must move the planes with every sub-block it cuts.
TEST(Blocks, PlaneCellsShowTheSameThroughTheSearch) {
  for (std::uint32_t seed = 1; seed <= 6; ++seed) {
    const Block g0 = withPlaneCells(randomBlock({16, 6, 12}, {0.3, 0.05, 1.2}, seed, 0.5), 100 + seed, 0.05);
    for (const bool priced : {false, true}) {
      BlockOptions options;
      options.priced = priced;
      BlockStats stats;
      auto h = buildHierarchy(g0, {Material{}, Material{200, 200, 200}, Material{40, 60, 90}}, glm::dvec3(0.0),
                              options, stats);
      ASSERT_TRUE(h.ok()) << h.error().message;
      expectSameContent(g0, *h, 5000, 60 + seed);
      EXPECT_TRUE(compile(*h).ok());
    }
  }
}

// Layers repeating with period 3 along x (widths and content), a fifth of the cells plane cells
// of the same cut in every period: equal cells, different surfaces. Tiling a period would show
// the first period's planes in the others.
TEST(Blocks, PlaneCellsInRepeatedLayersAreNotTiled) {
  Block period = withPlaneCells(randomBlock({3, 4, 5}, {0.5, 0.3, 0.8}, 18, 0.6), 19, 0.2);
  Block g0 = randomBlock({18, 4, 5}, {0.5, 0.3, 0.8}, 20, 0.0);
  g0.cuts = period.cuts;
  for (int z = 0; z < 5; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 18; ++x) g0.cell(x, y, z) = period.cell(x % 3, y, z);
  BlockStats stats;
  auto h = buildHierarchy(g0, {Material{}, Material{200, 200, 200}, Material{40, 60, 90}}, glm::dvec3(0.0), {}, stats);
  ASSERT_TRUE(h.ok()) << h.error().message;
  expectSameContent(g0, *h, 20000, 21);
}

TEST(PricedBlocks, RandomGridsShowTheSame) {
  for (std::uint32_t seed = 1; seed <= 4; ++seed) {
    const Block g0 = randomBlock({12, 8, 10}, {0.3, 0.05, 1.2}, seed, 0.5);
    BlockOptions options;
    options.priced = true;
    BlockStats stats;
    auto h = buildHierarchy(g0, {Material{}, Material{200, 200, 200}, Material{40, 60, 90}, Material{200, 30, 30}, Material{10, 90, 10}},
                            glm::dvec3(0.0), options, stats);
    ASSERT_TRUE(h.ok()) << h.error().message;
    expectSameContent(g0, *h, 5000, 40 + seed);
  }
}

// A 20 m wall whose front 0.3 m holds forty 2 cm mullions: in one block every layer of the wall
// needs their 80 boundaries along x, and the x item ~250 pixels. Priced, the search cuts the strip
// off (the thick wall behind it keeps two cells along x), which the estimate says is smaller.
TEST(PricedBlocks, AStripOfNarrowCellsIsCutOff) {
  std::vector<double> xs{0.0};
  for (int i = 0; i < 40; ++i) {
    xs.push_back(0.5 * i + 0.24);
    xs.push_back(0.5 * i + 0.26);
  }
  xs.push_back(20.0);
  const Block g0 = blockFromBounds(std::array<std::vector<double>, 3>{xs, {0.0, 3.0}, {0.0, 4.0, 4.3}}, [](const glm::dvec3& c) {
    if (c.z < 4.0) return Cell::box(1);
    const double inBay = c.x - 0.5 * std::floor(c.x / 0.5);
    return inBay > 0.24 && inBay < 0.26 ? Cell::box(2) : Cell::empty();
  });
  const std::vector<Material> materials{Material{}, Material{200, 200, 200}, Material{40, 60, 90}};
  const auto totalEstimate = [](const Hierarchy& h) {
    double sum = 0;
    for (const Block& b : h.blocks) sum += pngBytesEstimate(b, CompileOptions{}.heuristicToleranceM);
    return sum;
  };
  BlockOptions plain;
  plain.minSavedCells = 1'000'000'000;  // nothing pays: one block
  BlockStats stats;
  auto one = buildHierarchy(g0, materials, glm::dvec3(0.0), plain, stats);
  ASSERT_TRUE(one.ok());
  EXPECT_EQ(one->blocks.size(), 1u);
  BlockOptions priced;
  priced.priced = true;
  auto cut = buildHierarchy(g0, materials, glm::dvec3(0.0), priced, stats);
  ASSERT_TRUE(cut.ok());
  EXPECT_GT(cut->blocks.size(), 1u);
  EXPECT_LT(totalEstimate(*cut), totalEstimate(*one));
  // The mullions' boundaries stay with the strip: no block deeper than it holds them.
  for (const Block& b : cut->blocks) EXPECT_FALSE(b.cellCount(0) >= 80 && b.sizeM().z > 0.31) << b.cellCount(0) << " " << b.sizeM().z;
  expectSameContent(g0, *cut, 5000, 50);
}

}  // namespace
}  // namespace nut::converter
