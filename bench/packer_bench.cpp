// bench/packer_bench.cpp — packing speed and waste, MaxRects against stb_rect_pack's skyline:
// - in an HNI: the layout's width search on HNI-like item sets (40, 100 and 200 blocks), online
//   best-area-fit MaxRects against global (batch) best-area-fit and against the skyline packer
//   run through the same search; rects/s and the mean and worst waste over a fixed set of seeds;
// - in an atlas: a city's HNIs (bench/data/city_hni_sizes.txt) placed one at a time, in the order
//   the viewer streams them, into 2048^2 pages (a new page when none has room), as
//   viewer/atlas_pages.cpp does with MaxRects bottom-left; HNIs/s, pages and waste.
#include <packer/maxrects.hpp>

#include <benchmark/benchmark.h>

#define STB_RECT_PACK_IMPLEMENTATION
#include <stb/stb_rect_pack.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <random>
#include <vector>

#include "../tests/hni_like_items.hpp"

namespace {

constexpr int kMaxWidth = 256;     // the HNI width search's range
constexpr int kMaxHeight = 4096;
constexpr std::uint32_t kSeeds[] = {1, 2, 3, 4, 5};

// mt19937's output sequence is fixed by the standard (the distributions' is not).
using packer::testing::hniLikeItems;
using packer::testing::randomInt;


struct Extent {
  int width = 0, height = 0;
  long long area() const { return static_cast<long long>(width) * height; }
};

// stb_rect_pack's skyline through the same search as packSearchWidth: every width from the
// widest item to kMaxWidth, keeping the least bounding area (ties: smaller width), stopping at
// the first layout without waste. stb cannot give up midway, so each width packs to the end.
std::optional<Extent> stbSearchWidth(const std::vector<packer::Item>& items, int heuristic) {
  std::vector<stbrp_rect> rects(items.size());
  long long usedArea = 0;
  int minWidth = 1;
  for (const packer::Item& item : items) {
    minWidth = std::max(minWidth, item.width);
    usedArea += static_cast<long long>(item.width) * item.height;
  }
  std::vector<stbrp_node> nodes(kMaxWidth);
  std::optional<Extent> best;
  for (int width = minWidth; width <= kMaxWidth; ++width) {
    for (std::size_t i = 0; i < items.size(); ++i) {
      rects[i] = {};
      rects[i].id = static_cast<int>(i);
      rects[i].w = items[i].width;
      rects[i].h = items[i].height;
    }
    stbrp_context context;
    stbrp_init_target(&context, width, kMaxHeight, nodes.data(), width);
    stbrp_setup_heuristic(&context, heuristic);
    if (!stbrp_pack_rects(&context, rects.data(), static_cast<int>(rects.size()))) continue;
    Extent extent;
    for (const stbrp_rect& r : rects) {
      extent.width = std::max(extent.width, r.x + r.w);
      extent.height = std::max(extent.height, r.y + r.h);
    }
    if (best && (extent.area() > best->area() ||
                 (extent.area() == best->area() && extent.width >= best->width))) {
      continue;
    }
    best = extent;
    if (extent.area() == usedArea) break;
  }
  return best;
}

double wastePct(const Extent& extent, const std::vector<packer::Item>& items) {
  long long usedArea = 0;
  for (const packer::Item& item : items) usedArea += static_cast<long long>(item.width) * item.height;
  return 100.0 * static_cast<double>(extent.area() - usedArea) / static_cast<double>(extent.area());
}

// Runs `searchWidth` (item set -> optional bounding box) over the seeded inputs of
// state.range(0) blocks; reports rects/s and the mean and worst waste.
template <typename SearchWidth>
void runWidthSearch(benchmark::State& state, SearchWidth searchWidth) {
  std::vector<std::vector<packer::Item>> inputs;
  std::int64_t itemCount = 0;
  for (std::uint32_t seed : kSeeds) {
    inputs.push_back(hniLikeItems(seed, static_cast<int>(state.range(0))));
    itemCount += static_cast<std::int64_t>(inputs.back().size());
  }
  double wasteSum = 0.0, wasteMax = 0.0;
  for (auto _ : state) {
    wasteSum = wasteMax = 0.0;
    for (const std::vector<packer::Item>& items : inputs) {
      const std::optional<Extent> extent = searchWidth(items);
      if (!extent) {
        state.SkipWithError("a width search found no layout");
        return;
      }
      const double waste = wastePct(*extent, items);
      wasteSum += waste;
      wasteMax = std::max(wasteMax, waste);
    }
  }
  state.SetItemsProcessed(state.iterations() * itemCount);
  state.counters["waste_pct"] = wasteSum / static_cast<double>(std::size(kSeeds));
  state.counters["waste_max_pct"] = wasteMax;
}

void maxRectsBAF(benchmark::State& state, packer::Mode mode) {
  runWidthSearch(state, [mode](const std::vector<packer::Item>& items) -> std::optional<Extent> {
    const std::optional<packer::Layout> layout = packer::packSearchWidth(
        items, kMaxWidth, kMaxHeight, {.heuristic = packer::Heuristic::BestAreaFit, .mode = mode});
    if (!layout) return std::nullopt;
    return Extent{layout->width, layout->height};
  });
}

void BM_MaxRectsOnlineBAF(benchmark::State& state) { maxRectsBAF(state, packer::Mode::Online); }
void BM_MaxRectsGlobalBAF(benchmark::State& state) { maxRectsBAF(state, packer::Mode::Global); }

void BM_StbSkylineBL(benchmark::State& state) {
  runWidthSearch(state, [](const std::vector<packer::Item>& items) {
    return stbSearchWidth(items, STBRP_HEURISTIC_Skyline_BL_sortHeight);
  });
}

void BM_StbSkylineBF(benchmark::State& state) {
  runWidthSearch(state, [](const std::vector<packer::Item>& items) {
    return stbSearchWidth(items, STBRP_HEURISTIC_Skyline_BF_sortHeight);
  });
}

// ---- Atlas pages ----

constexpr int kPageSize = 2048;  // the city's 3 M texels fill one 2048^2 page about 72 %

const std::vector<packer::Item>& cityHnis() {
  static const std::vector<packer::Item> items = [] {
    const std::string path = std::string(NUT_SOURCE_DIR) + "/bench/data/city_hni_sizes.txt";
    std::ifstream in(path);
    std::vector<packer::Item> read;
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream fields(line);
      packer::Item item{static_cast<int>(read.size()), 0, 0};
      if (!(fields >> item.width >> item.height) || item.width <= 0 || item.height <= 0 || item.width > kPageSize ||
          item.height > kPageSize) {
        std::fprintf(stderr, "packer_bench: %s: bad line '%s'\n", path.c_str(), line.c_str());
        std::exit(1);
      }
      read.push_back(item);
    }
    if (read.empty()) {
      std::fprintf(stderr, "packer_bench: %s: no HNI sizes\n", path.c_str());
      std::exit(1);
    }
    return read;
  }();
  return items;
}

// Waste of a set of pages: the share of texels no HNI covers, counting every page but the last
// whole and the last up to the lowest HNI in it (the rest of it is room for the next ones).
struct PageFill {
  int pages = 0;
  int lastPageBottom = 0;
};

void reportAtlas(benchmark::State& state, const PageFill& fill) {
  const std::vector<packer::Item>& items = cityHnis();
  long long used = 0;
  for (const packer::Item& item : items) used += static_cast<long long>(item.width) * item.height;
  const long long counted = static_cast<long long>(fill.pages - 1) * kPageSize * kPageSize +
                            static_cast<long long>(fill.lastPageBottom) * kPageSize;
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(items.size()));
  state.counters["pages"] = fill.pages;
  state.counters["waste_pct"] = 100.0 * static_cast<double>(counted - used) / static_cast<double>(counted);
}

void atlasMaxRects(benchmark::State& state, packer::Heuristic heuristic) {
  PageFill fill;
  for (auto _ : state) {
    std::vector<packer::MaxRectsBin> pages;
    std::vector<int> bottoms;
    for (const packer::Item& item : cityHnis()) {
      std::optional<packer::Rect> placed;
      std::size_t page = 0;
      for (; page < pages.size() && !placed; ++page) placed = pages[page].insert(item, heuristic);
      if (!placed) {
        pages.emplace_back(kPageSize, kPageSize);
        bottoms.push_back(0);
        placed = pages.back().insert(item, heuristic);
        page = pages.size();
      }
      bottoms[page - 1] = std::max(bottoms[page - 1], placed->bottom());
    }
    fill = {static_cast<int>(pages.size()), bottoms.back()};
  }
  reportAtlas(state, fill);
}

void atlasStb(benchmark::State& state, int heuristic) {
  PageFill fill;
  for (auto _ : state) {
    // stb_rect_pack packs incrementally: each call places more rectangles in the same context.
    std::vector<std::vector<stbrp_node>> nodes;
    std::vector<stbrp_context> pages;
    pages.reserve(cityHnis().size());  // contexts are not moved once initialised
    nodes.reserve(cityHnis().size());
    std::vector<int> bottoms;
    const auto newPage = [&] {
      nodes.emplace_back(kPageSize);
      pages.emplace_back();
      stbrp_init_target(&pages.back(), kPageSize, kPageSize, nodes.back().data(), kPageSize);
      stbrp_setup_heuristic(&pages.back(), heuristic);
      bottoms.push_back(0);
    };
    for (const packer::Item& item : cityHnis()) {
      stbrp_rect rect{};
      rect.w = item.width;
      rect.h = item.height;
      std::size_t page = 0;
      for (; page < pages.size(); ++page)
        if (stbrp_pack_rects(&pages[page], &rect, 1)) break;
      if (page == pages.size()) {
        newPage();
        stbrp_pack_rects(&pages.back(), &rect, 1);  // an empty page holds any HNI (checked on reading)
      }
      bottoms[page] = std::max(bottoms[page], rect.y + rect.h);
    }
    fill = {static_cast<int>(pages.size()), bottoms.back()};
  }
  reportAtlas(state, fill);
}

void BM_AtlasMaxRectsBL(benchmark::State& state) { atlasMaxRects(state, packer::Heuristic::BottomLeft); }
void BM_AtlasMaxRectsBAF(benchmark::State& state) { atlasMaxRects(state, packer::Heuristic::BestAreaFit); }
void BM_AtlasStbSkylineBL(benchmark::State& state) { atlasStb(state, STBRP_HEURISTIC_Skyline_BL_sortHeight); }
void BM_AtlasStbSkylineBF(benchmark::State& state) { atlasStb(state, STBRP_HEURISTIC_Skyline_BF_sortHeight); }

BENCHMARK(BM_MaxRectsOnlineBAF)->Arg(40)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MaxRectsGlobalBAF)->Arg(40)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StbSkylineBL)->Arg(40)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StbSkylineBF)->Arg(40)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AtlasMaxRectsBL)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AtlasMaxRectsBAF)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AtlasStbSkylineBL)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_AtlasStbSkylineBF)->Unit(benchmark::kMillisecond);

}  // namespace
