// nut/metadata.hpp — per-axis metadata arrays (paper section 3.2) and the lookups over them.
//
// One axis of a block has W cells with integer boundaries b_0 = 0 < b_1 < ... < b_W = D (mm).
// A metadata array of M = W + w pixels (M <= 256) divides [0, D) uniformly. Each pixel holds
//   i       the cell at the pixel's left edge
//   f       where the one boundary inside the pixel lies, in 1/256 of a pixel; 0 = no boundary
//   j_left  how many pixels back the pixel holding the previous boundary is
//   j_right how many pixels ahead the pixel holding the next boundary is
// and, below it in the exact row, the exact position (24-bit mm) of the boundary it holds.
// Heuristic lookup reads one metadata pixel; its boundary error is at most D / (512 M). Exact
// lookup reads the exact pixel too and has no error.
//
// M is the smallest size for which every interior boundary has a pixel of its own and rounds to
// an f of 1..255 (never onto a pixel edge, so f = 0 unambiguously means "no boundary" and the true
// boundary lies in the same pixel as the rounded one), and every j fits in 8 bits. The j numbers of
// a pixel holding boundary m lead to the pixels of boundaries m - 1 and m + 1; those of a pixel
// inside cell c lead to the pixels of boundaries c and c + 1. Boundaries 0 and W are the block's
// faces: readers know them from the cell index, and their j numbers (to pixel 0 and to pixel M,
// clamped to 255) are never followed. docs/FORMAT.md states the rules; buildAxisIndex() implements
// them.
#pragma once

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <vector>

#include <nut/error.hpp>
#include <nut/format.hpp>

namespace nut {

static_assert(std::endian::native == std::endian::little, "AxisView reads u24 fields with one 32-bit load");

struct MetaPixel {
  std::uint8_t i = 0, f = 0, jLeft = 0, jRight = 0;
  friend bool operator==(const MetaPixel&, const MetaPixel&) = default;
};

// The compiled index of one axis.
struct AxisIndex {
  int cells = 0;                    // W
  std::uint32_t sizeUnits = 0;      // D
  std::vector<MetaPixel> meta;      // M pixels
  std::vector<std::uint32_t> exactUnits;  // M pixels: the boundary a pixel holds, 0 if none
  int pixels() const { return static_cast<int>(meta.size()); }
};

// Builds the metadata array for boundaries b_0..b_W in units (b_0 = 0, strictly increasing,
// b_W <= 2^24 - 1): the smallest valid M that is at least minPixels (a larger M lowers the
// heuristic error bound D / (512 M)), or the smallest valid M at all when none of those works.
// Fails when no M <= 256 works; the message says why (the caller adds which block and axis).
Result<AxisIndex> buildAxisIndex(std::span<const std::int64_t> boundsUnits, int minPixels = 1);

// The index compile() builds for an axis: at least the pixels that keep the heuristic lookup
// within heuristicToleranceM (CompileOptions; up to 256 pixels), one for an axis of one cell.
Result<AxisIndex> buildAxisIndexWithin(std::span<const std::int64_t> boundsUnits, double heuristicToleranceM);

// Read-only view of one axis's metadata as stored in an HNI: two rows of RGBA8 pixels.
// Lookups are branch-free: a data-dependent branch on "does this pixel hold a boundary" is a coin
// toss for random coordinates and cost 2-3x (docs/BENCHMARKS.md, lookup benchmark).
struct AxisView {
  const std::uint8_t* meta = nullptr;   // M pixels: i, f, j_left, j_right
  const std::uint8_t* exact = nullptr;  // M pixels: boundary position u24, 0
  int pixels = 0;                       // M
  int cells = 0;                        // W
  float size = 0;                       // D in units
  float scale = 0;                      // M / D: metadata pixels per unit
  float stepScale = 0;                  // 256 M / D: steps of f per unit
  float stepSize = 0;                   // D / (256 M): units per step of f
  float lastPixel = 0;                  // the largest float below M
  float lastStep = 0;                   // the largest float below 256 M
  float exactLast = 0;                  // the largest float <= D whose product with scale is below M

  static AxisView make(const std::uint8_t* meta, const std::uint8_t* exact, int pixels, int cells, float size) {
    AxisView v{meta, exact, pixels, cells, size};
    v.scale = static_cast<float>(pixels) / size;
    v.stepScale = v.scale * format::kFractionSteps;  // exact: a power-of-two multiple
    v.stepSize = size / (static_cast<float>(pixels) * format::kFractionSteps);
    v.lastPixel = std::nextafter(static_cast<float>(pixels), 0.0f);
    v.lastStep = std::nextafter(static_cast<float>(pixels * format::kFractionSteps), 0.0f);
    v.exactLast = exactClampOf(v.size, v.scale, pixels);
    return v;
  }

  // Metadata pixel of coordinate x (units); outside [0, D) and NaN clamp to the end pixels.
  int pixelOf(float x) const {
    return static_cast<int>(std::min(lastPixel, std::max(0.0f, x * scale)));
  }

  // Heuristic random access: the cell holding coordinate x. q is x in 1/256-pixel steps, clamped
  // like pixelOf; the pixel is q >> 8 and "f != 0 and the fraction reaches f" is one byte compare
  // (f = 0 wraps to 255, which no fraction exceeds). q is converted straight to a pointer-sized
  // integer, so indexing needs no extension: beyond the scale, clamp and truncation a uniform grid
  // pays, a lookup is a copy and a shift, two byte loads, a decrement, a compare and an add.
  int cellHeuristic(float x) const {
    const auto q = static_cast<std::ptrdiff_t>(std::min(lastStep, std::max(0.0f, x * stepScale)));
    const std::ptrdiff_t k = q >> 8;
    return meta[4 * k] + static_cast<int>(static_cast<std::uint8_t>(q) > static_cast<std::uint8_t>(meta[4 * k + 1] - 1));
  }

  // Exact random access: the metadata pixel picks the candidate, the exact row decides. x is
  // clamped once, to [0, exactLast] (NaN to 0); then trunc(x * scale) is pixelOf(x) with no second
  // clamp, and x >= b for an integer boundary b is trunc(x) >= b: no int-to-float conversion. The
  // exact pixel is 0 where f = 0 and its reserved byte is 0 (validate() enforces both), so e - 1
  // wraps to 2^32 - 1 there, which no trunc(x) <= D exceeds, and is b - 1 elsewhere: one unsigned
  // compare. The same cell as the unclamped comparison for every float x, including NaN, infinities and x outside
  // [0, D): see exactClampOf.
  int cellExact(float x) const {
    const float c = std::min(exactLast, std::max(0.0f, x));
    const auto t = static_cast<std::uint32_t>(static_cast<int>(c));
    const auto k = static_cast<std::ptrdiff_t>(c * scale);
    std::uint32_t e;
    std::memcpy(&e, exact + 4 * k, sizeof e);
    return meta[4 * k] + static_cast<int>(e - 1 < t);
  }

  // exactLast for an axis of `pixels` pixels over `size` units: the largest float c <= size with
  // c * scale < M, found from size down in a step or two (the product rounds within an ulp of M).
  // It is at least D - 1 and c * scale at least M - 1, so every x above it (up to +inf) has
  // pixelOf(x) = M - 1 and lies at or beyond every interior boundary (integers <= D - 1), as c
  // does: clamping x to c changes neither pixel nor cell. 0 for a degenerate axis (no pixels,
  // size < 1), which keeps lookups in pixel 0.
  static float exactClampOf(float size, float scale, int pixels) {
    const auto m = static_cast<float>(pixels);
    if (!(pixels > 0 && size >= 1.0f && scale > 0.0f)) return 0.0f;
    float c = size;
    for (int step = 0; step < 64 && !(c * scale < m); ++step) c = std::nextafter(c, 0.0f);
    return c * scale < m && c * scale >= m - 1.0f && c >= size - 1.0f ? c : 0.0f;
  }

  // Position (units) of the boundary held by metadata pixel k, heuristic: (k + f / 256) D / M.
  float boundaryHeuristic(int k) const {
    return static_cast<float>(k * format::kFractionSteps + meta[4 * k + 1]) * stepSize;
  }
  float exactPosition(int k) const {
    const std::uint8_t* e = exact + 4 * k;
    return static_cast<float>(e[0] | e[1] << 8 | e[2] << 16);
  }

  // Traversal (paper Figure 14a). The pixel holding the boundary ahead of a point in `cell`, found
  // by a lookup at pixel k, when moving in direction dir (+1 or -1). Callers handle the block's
  // faces (cell 0 moving -, cell W - 1 moving +) from the cell index.
  int boundaryPixelAhead(int k, int cell, int dir) const {
    const std::uint8_t* p = meta + 4 * k;
    if (p[1] != 0 && cell == p[0] + (dir > 0 ? 0 : 1)) return k;
    return dir > 0 ? k + p[3] : k - p[2];
  }
  // The pixel holding the boundary after the one held by pixel k, in direction dir.
  int nextBoundaryPixel(int k, int dir) const {
    return dir > 0 ? k + meta[4 * k + 3] : k - meta[4 * k + 2];
  }
};

// Encodes an AxisIndex into the two rows an AxisView reads (each pixels() * 4 bytes).
void encodeAxisIndex(const AxisIndex& index, std::uint8_t* metaRow, std::uint8_t* exactRow);

}  // namespace nut
