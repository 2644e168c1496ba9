// bench/packer_bench.cpp — the HNI layout's width search on HNI-like item sets (40, 100 and 200
// blocks): online best-area-fit MaxRects against global (batch) best-area-fit, and against
// stb_rect_pack's skyline packer run through the same width search. Reports rects/s and the
// mean and worst waste over a fixed set of seeds.
#include <packer/maxrects.hpp>

#include <benchmark/benchmark.h>

#define STB_RECT_PACK_IMPLEMENTATION
#include <stb/stb_rect_pack.h>

#include <algorithm>
#include <cstdint>
#include <optional>
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

BENCHMARK(BM_MaxRectsOnlineBAF)->Arg(40)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MaxRectsGlobalBAF)->Arg(40)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StbSkylineBL)->Arg(40)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_StbSkylineBF)->Arg(40)->Arg(100)->Arg(200)->Unit(benchmark::kMillisecond);

}  // namespace
