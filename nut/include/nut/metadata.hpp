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

#include <cstdint>
#include <span>
#include <vector>

#include <nut/error.hpp>
#include <nut/format.hpp>

namespace nut {

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
// b_W <= 2^24 - 1). Fails when no M <= 256 works; the message says why (the caller adds which
// block and axis).
Result<AxisIndex> buildAxisIndex(std::span<const std::int64_t> boundsUnits);

// Read-only view of one axis's metadata as stored in an HNI: two rows of RGBA8 pixels.
struct AxisView {
  const std::uint8_t* meta = nullptr;   // M pixels: i, f, j_left, j_right
  const std::uint8_t* exact = nullptr;  // M pixels: boundary position u24, 0
  int pixels = 0;                       // M
  int cells = 0;                        // W
  float size = 0;                       // D in units

  // Heuristic random access: the cell holding coordinate x (units, clamped into [0, D)).
  int cellHeuristic(float x) const {
    const float t = x * static_cast<float>(pixels) / size;
    const int k = clampPixel(t);
    const std::uint8_t* p = meta + 4 * k;
    const float frac = (t - static_cast<float>(k)) * format::kFractionSteps;
    return p[0] + (p[1] != 0 && frac >= static_cast<float>(p[1]) ? 1 : 0);
  }

  // Exact random access: the metadata pixel picks the candidate, the exact row decides.
  int cellExact(float x) const {
    const int k = clampPixel(x * static_cast<float>(pixels) / size);
    const std::uint8_t* p = meta + 4 * k;
    return p[0] + (p[1] != 0 && x >= exactPosition(k) ? 1 : 0);
  }

  // Position (units) of the boundary held by metadata pixel k, heuristic: (k + f / 256) D / M.
  float boundaryHeuristic(int k) const {
    return (static_cast<float>(k) + meta[4 * k + 1] * (1.0f / format::kFractionSteps)) * size /
           static_cast<float>(pixels);
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

  int clampPixel(float t) const {
    const int k = static_cast<int>(t);
    return k < 0 ? 0 : (k >= pixels ? pixels - 1 : k);
  }
};

// Encodes an AxisIndex into the two rows an AxisView reads (each pixels() * 4 bytes).
void encodeAxisIndex(const AxisIndex& index, std::uint8_t* metaRow, std::uint8_t* exactRow);

}  // namespace nut
