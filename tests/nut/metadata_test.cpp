// Metadata arrays (paper 3.2): the rules of M, the heuristic error bound E <= D / (512 M), exact
// lookups with zero error, and traversal through the j numbers, on seeded random boundary lists.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <nut/metadata.hpp>

namespace nut {
namespace {

struct EncodedAxis {
  AxisIndex index;
  std::vector<std::uint8_t> meta, exact;
  AxisView view() const {
    return AxisView::make(meta.data(), exact.data(), index.pixels(), index.cells, static_cast<float>(index.sizeUnits));
  }
};

EncodedAxis encode(const std::vector<std::int64_t>& bounds) {
  auto index = buildAxisIndex(bounds);
  EXPECT_TRUE(index.ok()) << (index.ok() ? "" : index.error().message);
  EncodedAxis e{std::move(*index), {}, {}};
  e.meta.resize(static_cast<std::size_t>(e.index.pixels()) * 4);
  e.exact.resize(e.meta.size());
  encodeAxisIndex(e.index, e.meta.data(), e.exact.data());
  return e;
}

// Random boundaries: n cells of integer mm widths within a factor `spread` of each other.
std::vector<std::int64_t> randomBounds(std::mt19937_64& rng, int n, int spread) {
  const int base = std::uniform_int_distribution<int>(1, 5000)(rng);
  std::uniform_int_distribution<int> width(base, base * spread);
  std::vector<std::int64_t> b{0};
  for (int i = 0; i < n; ++i) b.push_back(b.back() + width(rng));
  return b;
}

// The cell holding x by binary search over the true boundaries: the reference for lookups.
int trueCell(const std::vector<std::int64_t>& bounds, float x) {
  const auto it = std::upper_bound(bounds.begin() + 1, bounds.end() - 1, static_cast<double>(x),
                                   [](double v, std::int64_t b) { return v < static_cast<double>(b); });
  return static_cast<int>(it - bounds.begin()) - 1;
}

TEST(Metadata, PaperFigure6ExampleFitsInFewPixels) {
  // Five cells of unequal width (paper Figure 6 uses W = 5, w = 4).
  const EncodedAxis e = encode({0, 300, 500, 1300, 1500, 2000});
  EXPECT_EQ(e.index.cells, 5);
  EXPECT_GE(e.index.pixels(), 5);
  EXPECT_LE(e.index.pixels(), 12);
}

TEST(Metadata, UniformGridNeedsOneExtraPixel) {
  // Boundaries on pixel edges are not allowed (f = 0 means "no boundary"), so M = W + 1.
  std::vector<std::int64_t> bounds;
  for (int i = 0; i <= 10; ++i) bounds.push_back(i * 1000);
  EXPECT_EQ(encode(bounds).index.pixels(), 11);
}

TEST(Metadata, SingleCellAxis) {
  const EncodedAxis e = encode({0, 1234});
  ASSERT_EQ(e.index.pixels(), 1);
  const AxisView v = e.view();
  EXPECT_EQ(v.cellHeuristic(0.0f), 0);
  EXPECT_EQ(v.cellExact(1233.0f), 0);
}

TEST(Metadata, RefusesAxesThatCannotBeIndexed) {
  // A 1 mm cell next to a 500 m cell: no M <= 256 separates the boundaries.
  auto r = buildAxisIndex(std::vector<std::int64_t>{0, 1, 2, 500000});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("split the block"), std::string::npos) << r.error().message;
  std::vector<std::int64_t> tooMany;
  for (int i = 0; i <= 257; ++i) tooMany.push_back(i * 10);
  ASSERT_FALSE(buildAxisIndex(tooMany).ok());
}

TEST(Metadata, HeuristicBoundaryErrorWithinPaperBound) {
  std::mt19937_64 rng(1);
  int checked = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = std::uniform_int_distribution<int>(1, 64)(rng);
    const auto bounds = randomBounds(rng, n, std::uniform_int_distribution<int>(1, 4)(rng));
    const EncodedAxis e = encode(bounds);
    const AxisView v = e.view();
    const double D = static_cast<double>(bounds.back());
    const double bound = D / (512.0 * v.pixels);
    int m = 1;
    for (int k = 0; k < v.pixels; ++k) {
      if (v.meta[4 * k + 1] == 0) continue;
      const double truth = static_cast<double>(bounds[static_cast<std::size_t>(m)]);
      // f is exact integer arithmetic; evaluate the pixel's position in double, then the float path.
      const double heuristic = (k + v.meta[4 * k + 1] / 256.0) * D / v.pixels;
      ASSERT_LE(std::abs(heuristic - truth), bound * (1 + 1e-12)) << "trial " << trial << " boundary " << m;
      ASSERT_LE(std::abs(v.boundaryHeuristic(k) - truth), bound + truth * 2e-7) << "float path";
      ASSERT_EQ(v.exactPosition(k), static_cast<float>(truth)) << "exact row";
      ++m;
      ++checked;
    }
    ASSERT_EQ(m, n) << "every interior boundary has a pixel";
  }
  EXPECT_GT(checked, 10000);
}

TEST(Metadata, LookupsAgreeWithBinarySearch) {
  std::mt19937_64 rng(2);
  for (int trial = 0; trial < 500; ++trial) {
    const int n = std::uniform_int_distribution<int>(1, 100)(rng);
    const auto bounds = randomBounds(rng, n, 3);
    const EncodedAxis e = encode(bounds);
    const AxisView v = e.view();
    const double bound = static_cast<double>(bounds.back()) / (512.0 * v.pixels);
    std::uniform_real_distribution<float> coordinate(0.0f, static_cast<float>(bounds.back()));
    for (int s = 0; s < 200; ++s) {
      const float x = coordinate(rng);
      const int truth = trueCell(bounds, x);
      ASSERT_EQ(v.cellExact(x), truth) << "x = " << x << " trial " << trial;
      const int heuristic = v.cellHeuristic(x);
      if (heuristic != truth) {
        // Only within the error bound of the boundary between the two cells.
        const std::int64_t between = bounds[static_cast<std::size_t>(std::max(heuristic, truth))];
        ASSERT_EQ(std::abs(heuristic - truth), 1);
        ASSERT_LE(std::abs(x - static_cast<double>(between)), bound * 1.001 + 1.0) << "x = " << x;
      }
    }
    // Exactly on each boundary and one unit before it.
    for (int m = 1; m < n; ++m) {
      const auto b = static_cast<float>(bounds[static_cast<std::size_t>(m)]);
      ASSERT_EQ(v.cellExact(b), m);
      ASSERT_EQ(v.cellExact(b - 1.0f), m - 1);
    }
  }
}

TEST(Metadata, PixelEdgesBoundariesAndOutOfRangeCoordinates) {
  std::mt19937_64 rng(4);
  for (int trial = 0; trial < 300; ++trial) {
    const int n = std::uniform_int_distribution<int>(1, 80)(rng);
    const auto bounds = randomBounds(rng, n, 4);
    const EncodedAxis e = encode(bounds);
    const AxisView v = e.view();
    // On every metadata pixel edge, and one float step either side of it.
    for (int k = 0; k <= v.pixels; ++k) {
      const float edge = static_cast<float>(static_cast<double>(k) * static_cast<double>(bounds.back()) / v.pixels);
      for (float x : {std::nextafter(edge, -1e30f), edge, std::nextafter(edge, 1e30f)}) {
        if (x < 0 || x >= static_cast<float>(bounds.back())) continue;
        ASSERT_EQ(v.cellExact(x), trueCell(bounds, x)) << "x = " << x << " near pixel edge " << k;
      }
    }
    // One float step either side of every boundary.
    for (int m = 1; m < n; ++m) {
      const auto b = static_cast<float>(bounds[static_cast<std::size_t>(m)]);
      ASSERT_EQ(v.cellExact(std::nextafter(b, 0.0f)), m - 1);
      ASSERT_EQ(v.cellExact(b), m);
    }
    // Outside the block, and non-finite input, clamp to the end cells instead of reading outside.
    for (float x : {-1.0f, -1e30f, -std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
      ASSERT_EQ(v.cellHeuristic(x), 0);
      ASSERT_EQ(v.cellExact(x), 0);
    }
    for (float x : {static_cast<float>(bounds.back()), 1e30f, std::numeric_limits<float>::infinity()}) {
      ASSERT_EQ(v.cellHeuristic(x), n - 1);
      ASSERT_EQ(v.cellExact(x), n - 1);
    }
  }
}

TEST(Metadata, JNumbersWalkEveryBoundaryInBothDirections) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 1000; ++trial) {
    const int n = std::uniform_int_distribution<int>(2, 120)(rng);
    const auto bounds = randomBounds(rng, n, 4);
    const EncodedAxis e = encode(bounds);
    const AxisView v = e.view();
    // Land in the middle of every cell; the boundary ahead must be the cell's own boundary.
    for (int c = 0; c < n; ++c) {
      const float mid = static_cast<float>(bounds[static_cast<std::size_t>(c)] + bounds[static_cast<std::size_t>(c) + 1]) / 2;
      const int k = v.pixelOf(mid);
      ASSERT_EQ(v.cellExact(mid), c);
      if (c + 1 < n) {
        ASSERT_EQ(v.exactPosition(v.boundaryPixelAhead(k, c, +1)), static_cast<float>(bounds[static_cast<std::size_t>(c) + 1]));
      }
      if (c > 0) {
        ASSERT_EQ(v.exactPosition(v.boundaryPixelAhead(k, c, -1)), static_cast<float>(bounds[static_cast<std::size_t>(c)]));
      }
    }
    // From boundary 1 forwards to boundary n - 1 and back, one j step each.
    int k = v.boundaryPixelAhead(0, 0, +1);
    for (int m = 1; m < n; ++m) {
      ASSERT_EQ(v.exactPosition(k), static_cast<float>(bounds[static_cast<std::size_t>(m)])) << "forward " << m;
      if (m + 1 < n) k = v.nextBoundaryPixel(k, +1);
    }
    for (int m = n - 1; m >= 1; --m) {
      ASSERT_EQ(v.exactPosition(k), static_cast<float>(bounds[static_cast<std::size_t>(m)])) << "backward " << m;
      if (m > 1) k = v.nextBoundaryPixel(k, -1);
    }
  }
}

}  // namespace
}  // namespace nut
