// tests/packer_test.cpp — the MaxRects packer: seeded property tests (every item placed once,
// inside the bin, disjoint, within its region limit, deterministic) for every heuristic and both
// modes, edge cases, the free list's invariants, and the waste target of the HNI width search.
#include <packer/maxrects.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <iostream>
#include <iterator>
#include <optional>
#include <random>
#include <set>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "hni_like_items.hpp"

namespace {

using packer::Heuristic;
using packer::Item;
using packer::Layout;
using packer::MaxRectsBin;
using packer::Mode;
using packer::Options;
using packer::Rect;

constexpr Heuristic kHeuristics[] = {Heuristic::BestAreaFit, Heuristic::BestShortSideFit,
                                     Heuristic::BestLongSideFit, Heuristic::BottomLeft,
                                     Heuristic::ContactPoint};
constexpr std::uint32_t kSeeds[] = {1, 2, 3, 4, 5};
constexpr int kMetadataRegion = 256;  // HNI headers and metadata stay in the 256x256 corner

std::string name(Heuristic h) {
  switch (h) {
    case Heuristic::BestAreaFit: return "BAF";
    case Heuristic::BestShortSideFit: return "BSSF";
    case Heuristic::BestLongSideFit: return "BLSF";
    case Heuristic::BottomLeft: return "BL";
    case Heuristic::ContactPoint: return "CP";
  }
  return "?";
}

std::string name(Mode m) { return m == Mode::Online ? "Online" : "Global"; }

// mt19937's output sequence is fixed by the standard (the distributions' is not), so the seeded
// inputs are the same with every standard library.
using packer::testing::hniLikeItems;
using packer::testing::randomInt;

// Sizes like an HNI's records: 12x1 headers and Mx2 metadata arrays (which must stay inside the
// metadata region) mixed with data blocks from 1x1 up to 120x40.
std::vector<Item> randomItems(std::uint32_t seed, int count) {
  std::mt19937 rng(seed);
  std::vector<Item> items;
  for (int i = 0; i < count; ++i) {
    Item item{.id = 1000 + i};
    switch (randomInt(rng, 0, 2)) {
      case 0: item.width = 12, item.height = 1; break;
      case 1: item.width = randomInt(rng, 2, 40), item.height = 2; break;
      default: item.width = randomInt(rng, 1, 120), item.height = randomInt(rng, 1, 40); break;
    }
    if (item.height <= 2) item.maxRight = item.maxBottom = kMetadataRegion;
    items.push_back(item);
  }
  return items;
}


bool overlaps(const Rect& a, const Rect& b) {
  return a.x < b.right() && b.x < a.right() && a.y < b.bottom() && b.y < a.bottom();
}

// Checks everything a layout promises: placements in input order with their item's id and size,
// inside the bin and the item's region limit, disjoint from each other and from the reserved
// rectangles, and a bounding box and used area that match.
void expectValidLayout(const Layout& layout, std::span<const Item> items,
                       std::span<const Rect> reserved, int binWidth, int binHeight) {
  ASSERT_EQ(layout.placements.size(), items.size());
  std::set<int> ids;
  int right = 0, bottom = 0;
  long long usedArea = 0;
  for (const Rect& r : reserved) {
    right = std::max(right, r.right());
    bottom = std::max(bottom, r.bottom());
    usedArea += r.area();
  }
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Item& item = items[i];
    const Rect& r = layout.placements[i].rect;
    SCOPED_TRACE("item " + std::to_string(item.id));
    EXPECT_EQ(layout.placements[i].id, item.id);
    EXPECT_TRUE(ids.insert(layout.placements[i].id).second) << "placed twice";
    EXPECT_EQ(r.width, item.width);
    EXPECT_EQ(r.height, item.height);
    EXPECT_GE(r.x, 0);
    EXPECT_GE(r.y, 0);
    EXPECT_LE(r.right(), binWidth);
    EXPECT_LE(r.bottom(), binHeight);
    EXPECT_LE(r.right(), item.maxRight);
    EXPECT_LE(r.bottom(), item.maxBottom);
    for (const Rect& other : reserved) EXPECT_FALSE(overlaps(r, other));
    for (std::size_t j = i + 1; j < items.size(); ++j) {
      EXPECT_FALSE(overlaps(r, layout.placements[j].rect)) << "overlaps item " << items[j].id;
    }
    right = std::max(right, r.right());
    bottom = std::max(bottom, r.bottom());
    usedArea += r.area();
  }
  EXPECT_EQ(layout.width, right);
  EXPECT_EQ(layout.height, bottom);
  EXPECT_EQ(layout.usedArea, usedArea);
}

void expectSameLayout(const Layout& a, const Layout& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  ASSERT_EQ(a.placements.size(), b.placements.size());
  for (std::size_t i = 0; i < a.placements.size(); ++i) {
    EXPECT_EQ(a.placements[i].id, b.placements[i].id);
    EXPECT_EQ(a.placements[i].rect, b.placements[i].rect);
  }
}

// --- Seeded properties, for every heuristic in both modes ---

class PackerProperty : public testing::TestWithParam<std::tuple<Heuristic, Mode>> {
 protected:
  Options options() const {
    return {.heuristic = std::get<0>(GetParam()), .mode = std::get<1>(GetParam()),
            .reserved = reserved_};
  }
  // Waste over the bounding box, as a test property (in the XML report) and on stdout.
  void reportMeanWaste(double wastePct) {
    RecordProperty("mean_waste_pct", std::to_string(wastePct));
    std::cout << testing::UnitTest::GetInstance()->current_test_info()->name()
              << ": mean waste " << wastePct << "%\n";
  }
  const Rect reserved_[1] = {{0, 0, 6, 1}};  // like the HNI's fixed version/magic record
};

TEST_P(PackerProperty, FixedBinLayoutsAreValidAndDeterministic) {
  // Wider than the metadata region, so the limited items' maxRight matters too.
  constexpr int kBinWidth = 320, kBinHeight = 512;
  double wasteSum = 0.0;
  for (std::uint32_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::vector<Item> items = randomItems(seed, 90);
    const std::optional<Layout> layout = packer::pack(items, kBinWidth, kBinHeight, options());
    ASSERT_TRUE(layout.has_value());
    expectValidLayout(*layout, items, reserved_, kBinWidth, kBinHeight);
    expectSameLayout(*layout, *packer::pack(items, kBinWidth, kBinHeight, options()));
    wasteSum += layout->wastePct();
  }
  reportMeanWaste(wasteSum / std::size(kSeeds));
}

TEST_P(PackerProperty, WidthSearchLayoutsAreValidAndDeterministic) {
  constexpr int kMaxWidth = kMetadataRegion, kMaxHeight = 1024;
  // Global mode scores every item at every step: fewer items keep the test quick.
  const int count = std::get<1>(GetParam()) == Mode::Online ? 90 : 40;
  double wasteSum = 0.0;
  for (std::uint32_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const std::vector<Item> items = randomItems(seed, count);
    const std::optional<Layout> layout =
        packer::packSearchWidth(items, kMaxWidth, kMaxHeight, options());
    ASSERT_TRUE(layout.has_value());
    expectValidLayout(*layout, items, reserved_, kMaxWidth, kMaxHeight);
    expectSameLayout(*layout, *packer::packSearchWidth(items, kMaxWidth, kMaxHeight, options()));
    wasteSum += layout->wastePct();
  }
  reportMeanWaste(wasteSum / std::size(kSeeds));
}

INSTANTIATE_TEST_SUITE_P(AllHeuristics, PackerProperty,
                         testing::Combine(testing::ValuesIn(kHeuristics),
                                          testing::Values(Mode::Online, Mode::Global)),
                         [](const auto& test) {
                           return name(std::get<0>(test.param)) + name(std::get<1>(test.param));
                         });

// The free list stays exactly the set of maximal free rectangles: none overlaps a used
// rectangle, none can grow by a row or column, none lies inside another, and together they
// cover every free cell.
TEST(MaxRectsBin, FreeListStaysMaximalAndComplete) {
  constexpr int kSize = 48;
  for (std::uint32_t seed : kSeeds) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    MaxRectsBin bin(kSize, kSize);
    std::vector<Rect> used;
    for (int attempt = 0; attempt < 200; ++attempt) {
      const Item item{.width = randomInt(rng, 1, 12), .height = randomInt(rng, 1, 12)};
      if (auto r = bin.insert(item, kHeuristics[seed % std::size(kHeuristics)])) {
        used.push_back(*r);
      }
      const std::vector<Rect>& freeRects = bin.freeRects();
      for (std::size_t i = 0; i < freeRects.size(); ++i) {
        const Rect& f = freeRects[i];
        ASSERT_TRUE(f.x >= 0 && f.y >= 0 && f.right() <= kSize && f.bottom() <= kSize);
        auto isUsed = [&](const Rect& r) {
          return std::any_of(used.begin(), used.end(), [&](const Rect& u) { return overlaps(u, r); });
        };
        ASSERT_FALSE(isUsed(f));
        const Rect borders[] = {{f.x - 1, f.y, 1, f.height}, {f.right(), f.y, 1, f.height},
                                {f.x, f.y - 1, f.width, 1}, {f.x, f.bottom(), f.width, 1}};
        for (const Rect& border : borders) {
          const bool insideBin = border.x >= 0 && border.y >= 0 && border.right() <= kSize &&
                                 border.bottom() <= kSize;
          ASSERT_TRUE(!insideBin || isUsed(border)) << "free rectangle " << i << " can grow";
        }
        for (std::size_t j = 0; j < freeRects.size(); ++j) {
          const Rect& g = freeRects[j];
          ASSERT_FALSE(i != j && f.x >= g.x && f.y >= g.y && f.right() <= g.right() &&
                       f.bottom() <= g.bottom())
              << "free rectangle " << i << " lies inside " << j;
        }
      }
      for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
          const Rect cell{x, y, 1, 1};
          const bool isUsed = std::any_of(used.begin(), used.end(),
                                          [&](const Rect& u) { return overlaps(u, cell); });
          const bool isFree = std::any_of(freeRects.begin(), freeRects.end(),
                                          [&](const Rect& f) { return overlaps(f, cell); });
          ASSERT_NE(isUsed, isFree) << "cell " << x << "," << y;
        }
      }
    }
  }
}

// --- Edge cases ---

TEST(Pack, EmptyInputGivesAnEmptyLayout) {
  const std::optional<Layout> layout = packer::pack({}, 16, 16);
  ASSERT_TRUE(layout.has_value());
  EXPECT_TRUE(layout->placements.empty());
  EXPECT_EQ(layout->width, 0);
  EXPECT_EQ(layout->height, 0);
  EXPECT_EQ(layout->wastePct(), 0.0);

  const std::optional<Layout> searched = packer::packSearchWidth({}, 16, 16);
  ASSERT_TRUE(searched.has_value());
  EXPECT_TRUE(searched->placements.empty());
}

TEST(Pack, ItemLargerThanTheBinFailsInEveryMode) {
  const Item items[] = {{.id = 1, .width = 4, .height = 4}, {.id = 2, .width = 17, .height = 2}};
  for (Heuristic h : kHeuristics) {
    for (Mode m : {Mode::Online, Mode::Global}) {
      EXPECT_FALSE(packer::pack(items, 16, 16, {.heuristic = h, .mode = m}).has_value());
    }
  }
  // The width search widens the bin for a wide item, but never exceeds the height.
  EXPECT_TRUE(packer::packSearchWidth(items, 16, 16).has_value());
  EXPECT_FALSE(packer::packSearchWidth(items, 16, 3).has_value());
}

TEST(Pack, ItemsThatDoNotFitTogetherFail) {
  const Item items[] = {{.id = 1, .width = 3, .height = 3}, {.id = 2, .width = 2, .height = 2}};
  for (Mode m : {Mode::Online, Mode::Global}) {
    EXPECT_FALSE(packer::pack(items, 4, 4, {.mode = m}).has_value());
  }
}

TEST(Pack, SingleItemGoesToTheOrigin) {
  const Item items[] = {{.id = 7, .width = 5, .height = 3}};
  const std::optional<Layout> layout = packer::pack(items, 16, 16);
  ASSERT_TRUE(layout.has_value());
  ASSERT_EQ(layout->placements.size(), 1u);
  EXPECT_EQ(layout->placements[0].id, 7);
  EXPECT_EQ(layout->placements[0].rect, (Rect{0, 0, 5, 3}));
  EXPECT_EQ(layout->width, 5);
  EXPECT_EQ(layout->height, 3);
  EXPECT_EQ(layout->wastePct(), 0.0);
}

TEST(Pack, ExactFitHasNoWaste) {
  // 5x2 on top, then 3x3 and 2x3 side by side fill a 5x5 bin exactly.
  const Item items[] = {{.id = 1, .width = 2, .height = 3},
                        {.id = 2, .width = 5, .height = 2},
                        {.id = 3, .width = 3, .height = 3}};
  for (Heuristic h : kHeuristics) {
    for (Mode m : {Mode::Online, Mode::Global}) {
      SCOPED_TRACE(name(h) + name(m));
      const std::optional<Layout> layout = packer::pack(items, 5, 5, {.heuristic = h, .mode = m});
      ASSERT_TRUE(layout.has_value());
      expectValidLayout(*layout, items, {}, 5, 5);
      EXPECT_EQ(layout->usedArea, 25);
      EXPECT_EQ(layout->wastePct(), 0.0);
    }
  }
}

TEST(Pack, RegionLimitSteersTheItemToTheFreeRectangleThatSatisfiesIt) {
  // After the 6x6 item, the free space is a 4x12 column at x=6 and a 10x6 row at y=6. Best area
  // fit would put the 3x3 item in the column; with maxRight = 5 it can only go into the row.
  Item items[] = {{.id = 1, .width = 6, .height = 6}, {.id = 2, .width = 3, .height = 3}};
  std::optional<Layout> layout = packer::pack(items, 10, 12);
  ASSERT_TRUE(layout.has_value());
  EXPECT_EQ(layout->placements[1].rect, (Rect{6, 0, 3, 3}));

  items[1].maxRight = 5;
  for (Heuristic h : kHeuristics) {
    SCOPED_TRACE(name(h));
    layout = packer::pack(items, 10, 12, {.heuristic = h});
    ASSERT_TRUE(layout.has_value());
    EXPECT_EQ(layout->placements[1].rect, (Rect{0, 6, 3, 3}));
    // Global mode may place the small item first, but never past its limit.
    layout = packer::pack(items, 10, 12, {.heuristic = h, .mode = Mode::Global});
    ASSERT_TRUE(layout.has_value());
    expectValidLayout(*layout, items, {}, 10, 12);
  }

  // A limit that both free rectangles break makes the packing fail.
  items[1].maxBottom = 8;
  EXPECT_FALSE(packer::pack(items, 10, 12).has_value());
}

TEST(Pack, ReservedRectanglesAreOccupiedAndCounted) {
  const Rect reserved[] = {{0, 0, 6, 1}};
  const Item items[] = {{.id = 1, .width = 2, .height = 1}, {.id = 2, .width = 8, .height = 1}};
  const std::optional<Layout> layout = packer::pack(items, 8, 4, {.reserved = reserved});
  ASSERT_TRUE(layout.has_value());
  expectValidLayout(*layout, items, reserved, 8, 4);
  EXPECT_EQ(layout->usedArea, 16);
  EXPECT_EQ(layout->wastePct(), 0.0);  // the 2x1 item completes the reserved row

  // A reserved rectangle outside the bin cannot be honoured.
  const Rect outside[] = {{4, 0, 6, 1}};
  EXPECT_FALSE(packer::pack(items, 8, 4, {.reserved = outside}).has_value());
}

TEST(Pack, MaxBoundingAreaAbandonsLargerLayouts) {
  const Item items[] = {{.id = 1, .width = 4, .height = 2}, {.id = 2, .width = 4, .height = 2}};
  // At width 4 the two items stack into a 4x4 bounding box.
  EXPECT_TRUE(packer::pack(items, 4, 8, {.maxBoundingArea = 16}).has_value());
  EXPECT_FALSE(packer::pack(items, 4, 8, {.maxBoundingArea = 15}).has_value());
}

TEST(PackSearchWidth, StopsAtTheFirstLayoutWithoutWaste) {
  const Item items[] = {{.id = 1, .width = 3, .height = 3}, {.id = 2, .width = 3, .height = 3},
                        {.id = 3, .width = 3, .height = 3}, {.id = 4, .width = 3, .height = 3}};
  const std::optional<Layout> layout = packer::packSearchWidth(items, 20, 100);
  ASSERT_TRUE(layout.has_value());
  EXPECT_EQ(layout->width, 3);
  EXPECT_EQ(layout->height, 12);
  EXPECT_EQ(layout->wastePct(), 0.0);
}

TEST(PackSearchWidth, KeepsTheWidthWithLeastWaste) {
  // In a 4-wide bin the 4x2 item leaves no room beside the 2x2 items; at width 6 all sit on one row.
  const Item items[] = {{.id = 1, .width = 4, .height = 2}, {.id = 2, .width = 2, .height = 2}};
  const std::optional<Layout> layout = packer::packSearchWidth(items, 8, 100);
  ASSERT_TRUE(layout.has_value());
  EXPECT_EQ(layout->width, 6);
  EXPECT_EQ(layout->height, 2);
}

// --- The HNI target: online best-area-fit width search wastes at most 1% on average ---

TEST(PackSearchWidth, HniLikeHierarchiesWasteAtMostOnePercent) {
  constexpr int kMaxWidth = 256, kMaxHeight = 4096;
  double sum = 0.0;
  int runs = 0;
  for (int blocks : {40, 70, 100, 150, 200}) {
    double blockSum = 0.0, blockMax = 0.0;
    for (std::uint32_t seed : kSeeds) {
      const std::vector<Item> items = hniLikeItems(seed, blocks);
      const std::optional<Layout> layout = packer::packSearchWidth(items, kMaxWidth, kMaxHeight);
      ASSERT_TRUE(layout.has_value());
      expectValidLayout(*layout, items, {}, kMaxWidth, kMaxHeight);
      blockSum += layout->wastePct();
      blockMax = std::max(blockMax, layout->wastePct());
    }
    const double blockMean = blockSum / std::size(kSeeds);
    std::cout << blocks << " blocks: mean waste " << blockMean << "%, max " << blockMax << "%\n";
    RecordProperty("mean_waste_pct_" + std::to_string(blocks), std::to_string(blockMean));
    sum += blockSum;
    runs += static_cast<int>(std::size(kSeeds));
  }
  EXPECT_LE(sum / runs, 1.0);
}

}  // namespace

namespace packer {
namespace {

// Many large unlimited items and many small region-limited ones: by area alone the limited items
// come last and find the region full; regionLimitedFirst places them first.
TEST(RegionLimitedFirst, KeepsLimitedItemsPlaceableWhenLargeItemsComeFirst) {
  std::vector<Item> items;
  for (int i = 0; i < 40; ++i) items.push_back({i, 60, 30});
  for (int i = 0; i < 60; ++i) items.push_back({40 + i, 12, 1, 64, 16});  // 60 of 80 slots
  EXPECT_FALSE(packSearchWidth(items, 128, 4096).has_value());
  Options options;
  options.regionLimitedFirst = true;
  const auto layout = packSearchWidth(items, 128, 4096, options);
  ASSERT_TRUE(layout.has_value());
  for (const Placement& p : layout->placements)
    if (p.id >= 40) {
      EXPECT_LE(p.rect.right(), 64);
      EXPECT_LE(p.rect.bottom(), 16);
    }
}

}  // namespace
}  // namespace packer
