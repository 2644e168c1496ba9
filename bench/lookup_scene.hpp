// bench/lookup_scene.hpp — the NUT of the lookup benchmarks, shared by lookup_bench.cpp (the CPU
// analogue of the paper's Table 1) and gl_lookup_bench.cpp (the same lookups in GLSL), so that
// both measure the same metadata and the same data image.
//
// One size n: an n x n x n NUT whose cells have random integer-mm widths in [kMinWidth, kMaxWidth]
// per axis (mt19937, fixed seeds; a new draw in the rare case that no metadata array of <= 256
// pixels fits). Its metadata is built with nut::buildAxisIndex + nut::encodeAxisIndex and laid out
// like the HNI's metadata region (kRegionWidth pixels wide, RGBA8): axis a's metadata row at
// v = 2a, its exact row at v = 2a + 1. The data image is (n n) x n RGBA8 random bytes, z tiled
// along x: texel (cx + cz n, cy). The native grid spans the same D per axis.
#pragma once

#include <nut/error.hpp>
#include <nut/format.hpp>
#include <nut/metadata.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace nut::bench {

constexpr int kSizes[] = {4, 8, 16, 32, 64};
constexpr std::uint32_t kSeed = 20130721;
constexpr int kMinWidth = 250;  // cell widths in mm: within a factor 4 of each other
constexpr int kMaxWidth = 1000;
constexpr int kRegionWidth = nut::format::kMetadataRegion;
constexpr int kRegionRows = 6;  // a metadata row and an exact row per axis

// mt19937's output sequence is fixed by the standard (the distributions' is not).
inline int randomInt(std::mt19937& rng, int lo, int hi) {
  return lo + static_cast<int>(rng() % static_cast<std::uint32_t>(hi - lo + 1));
}
inline float randomUnit(std::mt19937& rng) {  // [0, 1) in steps of 2^-24
  return static_cast<float>(rng() >> 8) * (1.0f / 16777216.0f);
}

// The one texel fetch every method ends with: RGBA8 texel (u, v) of an image `width` texels wide.
inline std::uint32_t fetchTexel(const std::uint8_t* image, int width, int u, int v) {
  std::uint32_t texel;
  const auto offset = static_cast<std::size_t>(static_cast<std::uint32_t>(v * width + u));
  std::memcpy(&texel, image + 4 * offset, sizeof texel);
  return texel;
}

// Native uniform grid, the same arithmetic as AxisView::pixelOf: x * (n / D) clamped in float
// to [0, n) (max first, so a NaN coordinate lands on cell 0), then truncated.
struct UniformAxis {
  float scale = 0;     // n / D
  float lastCell = 0;  // the largest float below n
  int cell(float x) const { return static_cast<int>(std::min(lastCell, std::max(0.0f, x * scale))); }
};

// Binary search: the cell holding x is the number of interior boundaries b_1..b_{W-1} <= x
// (clamped by construction).
struct BoundaryAxis {
  const float* interior = nullptr;
  int count = 0;  // W - 1
  int cell(float x) const {
    return static_cast<int>(std::upper_bound(interior, interior + count, x) - interior);
  }
};

// The scene of one size n. Not copyable: the views point into metaRegion.
struct LookupScene {
  LookupScene() = default;
  LookupScene(const LookupScene&) = delete;
  LookupScene& operator=(const LookupScene&) = delete;

  int n = 0;
  std::array<float, 3> size{};                // D per axis, mm
  std::array<int, 3> pixels{};                // M per axis
  std::vector<std::uint8_t> metaRegion;       // kRegionWidth x kRegionRows RGBA8
  std::array<std::vector<float>, 3> interior; // b_1 .. b_{n-1} per axis
  std::array<nut::AxisView, 3> views{};       // the library's lookups over metaRegion
  std::array<UniformAxis, 3> native{};
  std::vector<std::uint8_t> data;             // (n n) x n RGBA8
  // The generator that drew `data`, positioned after it: lookup_bench draws its query points
  // from it.
  std::mt19937 rng;
};

// Fills `s` with the scene of size n; fails only when no metadata array fits in 100 draws.
inline nut::Status buildLookupScene(int n, LookupScene& s) {
  s.n = n;
  s.metaRegion.assign(static_cast<std::size_t>(4 * kRegionWidth * kRegionRows), 0);
  for (std::size_t a = 0; a < 3; ++a) {
    std::mt19937 rng(kSeed + static_cast<std::uint32_t>(3 * n) + static_cast<std::uint32_t>(a));
    std::vector<std::int64_t> bounds;
    nut::Result<nut::AxisIndex> index = nut::Error{"not built"};
    for (int attempt = 0; attempt < 100 && !index; ++attempt) {
      bounds.assign(1, 0);
      for (int c = 0; c < n; ++c)
        bounds.push_back(bounds.back() + randomInt(rng, kMinWidth, kMaxWidth));
      index = nut::buildAxisIndex(bounds);
    }
    if (!index) return index.error();
    const nut::AxisIndex& ix = *index;
    std::uint8_t* metaRow = s.metaRegion.data() + 4 * kRegionWidth * (2 * a);
    std::uint8_t* exactRow = metaRow + 4 * kRegionWidth;
    nut::encodeAxisIndex(ix, metaRow, exactRow);
    const float size = static_cast<float>(bounds.back());
    s.size[a] = size;
    s.pixels[a] = ix.pixels();
    auto& inner = s.interior[a];
    inner.clear();
    for (int m = 1; m < n; ++m) inner.push_back(static_cast<float>(bounds[static_cast<std::size_t>(m)]));
    s.views[a] = nut::AxisView::make(metaRow, exactRow, ix.pixels(), n, size);
    s.native[a] = {.scale = static_cast<float>(n) / size, .lastCell = std::nextafter(static_cast<float>(n), 0.0f)};
  }
  s.rng.seed(kSeed);
  s.data.resize(static_cast<std::size_t>(4) * n * n * n);
  for (auto& byte : s.data) byte = static_cast<std::uint8_t>(s.rng() >> 24);
  return nut::Ok{};
}

}  // namespace nut::bench
