// Metadata arrays (paper section 3.2): choosing M = W + w and filling (i, f, j_left, j_right) and
// the exact row. The rules are in nut/metadata.hpp and docs/FORMAT.md.
#include <nut/metadata.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace nut {

namespace {

// Boundary m at b units in an array of M pixels over D units: q = round(256 M b / D), the
// boundary's position in 1/256 pixel steps. Integer arithmetic keeps it exact and deterministic.
std::int64_t quantizedPosition(std::int64_t b, int pixels, std::int64_t size) {
  const std::int64_t twice = 2 * format::kFractionSteps * pixels * b;  // 2 * 256 M b
  return (twice + size) / (2 * size);                                   // round half up
}

// Tries an array of `pixels` pixels; empty result when the rules fail for that size.
std::optional<AxisIndex> tryPixels(std::span<const std::int64_t> bounds, int pixels) {
  const int cells = static_cast<int>(bounds.size()) - 1;
  const std::int64_t size = bounds.back();
  // pixelOf[m]: the pixel holding boundary m; the faces are pixel 0 and pixel M by convention.
  std::vector<int> pixelOf(bounds.size());
  pixelOf[0] = 0;
  pixelOf[static_cast<std::size_t>(cells)] = pixels;
  AxisIndex index;
  index.cells = cells;
  index.sizeUnits = static_cast<std::uint32_t>(size);
  index.meta.assign(static_cast<std::size_t>(pixels), MetaPixel{});
  index.exactUnits.assign(static_cast<std::size_t>(pixels), 0);
  int previous = -1;
  for (int m = 1; m < cells; ++m) {
    const std::int64_t q = quantizedPosition(bounds[static_cast<std::size_t>(m)], pixels, size);
    const int k = static_cast<int>(q / format::kFractionSteps);
    const int f = static_cast<int>(q % format::kFractionSteps);
    if (f == 0 || k <= previous || k >= pixels) return std::nullopt;
    previous = k;
    pixelOf[static_cast<std::size_t>(m)] = k;
    auto& p = index.meta[static_cast<std::size_t>(k)];
    p.f = static_cast<std::uint8_t>(f);
    index.exactUnits[static_cast<std::size_t>(k)] =
        static_cast<std::uint32_t>(bounds[static_cast<std::size_t>(m)]);
  }
  // i and the j numbers, walking the pixels with the cell at each pixel's left edge. A pixel
  // holding boundary m = cell + 1 links to boundaries m - 1 and m + 1, one inside a cell to that
  // cell's two boundaries: either way the left link is boundary `cell`.
  int cell = 0;
  for (int k = 0; k < pixels; ++k) {
    auto& p = index.meta[static_cast<std::size_t>(k)];
    p.i = static_cast<std::uint8_t>(cell);
    const int rightBoundary = cell + (p.f != 0 ? 2 : 1);
    const int jRight = pixelOf[static_cast<std::size_t>(rightBoundary)] - k;
    // Links to the faces are never followed and may be clamped; links to interior boundaries not.
    if (jRight > 255 && rightBoundary < cells) return std::nullopt;
    p.jLeft = static_cast<std::uint8_t>(k - pixelOf[static_cast<std::size_t>(cell)]);
    p.jRight = static_cast<std::uint8_t>(std::min(jRight, 255));
    if (p.f != 0) ++cell;
  }
  return index;
}

}  // namespace

Result<AxisIndex> buildAxisIndexWithin(std::span<const std::int64_t> boundsUnits, double heuristicToleranceM) {
  const double tolerance = heuristicToleranceM / format::kMetresPerUnit;
  // An axis of one cell has no boundary the heuristic could misplace: one pixel does.
  const bool hasBoundaries = boundsUnits.size() > 2;
  const int minPixels = tolerance > 0 && hasBoundaries
                            ? static_cast<int>(std::min<double>(format::kMaxMetadataPixels,
                                                                std::ceil(static_cast<double>(boundsUnits.back()) / (512.0 * tolerance))))
                            : 1;
  return buildAxisIndex(boundsUnits, minPixels);
}

Result<AxisIndex> buildAxisIndex(std::span<const std::int64_t> boundsUnits, int minPixels) {
  const int cells = static_cast<int>(boundsUnits.size()) - 1;
  if (cells < 1) return Error{"no cells"};
  if (cells > format::kMaxCellsPerAxis)
    return Error{std::to_string(cells) + " cells exceed the limit of " +
                 std::to_string(format::kMaxCellsPerAxis)};
  for (int pixels = std::max(cells, minPixels); pixels <= format::kMaxMetadataPixels; ++pixels)
    if (auto index = tryPixels(boundsUnits, pixels)) return std::move(*index);
  for (int pixels = cells; pixels < std::min(minPixels, format::kMaxMetadataPixels + 1); ++pixels)
    if (auto index = tryPixels(boundsUnits, pixels)) return std::move(*index);
  std::int64_t narrowest = boundsUnits.back(), widest = 0;
  for (std::size_t m = 1; m < boundsUnits.size(); ++m) {
    narrowest = std::min(narrowest, boundsUnits[m] - boundsUnits[m - 1]);
    widest = std::max(widest, boundsUnits[m] - boundsUnits[m - 1]);
  }
  return Error{"no metadata array of W + w <= 256 pixels indexes these " + std::to_string(cells) +
               " cells (narrowest " + std::to_string(narrowest) + " mm, widest " +
               std::to_string(widest) + " mm, size " + std::to_string(boundsUnits.back()) +
               " mm); split the block"};
}

void encodeAxisIndex(const AxisIndex& index, std::uint8_t* metaRow, std::uint8_t* exactRow) {
  for (int k = 0; k < index.pixels(); ++k) {
    const MetaPixel& p = index.meta[static_cast<std::size_t>(k)];
    std::uint8_t* m = metaRow + 4 * k;
    m[0] = p.i, m[1] = p.f, m[2] = p.jLeft, m[3] = p.jRight;
    const std::uint32_t e = index.exactUnits[static_cast<std::size_t>(k)];
    std::uint8_t* x = exactRow + 4 * k;
    x[0] = static_cast<std::uint8_t>(e), x[1] = static_cast<std::uint8_t>(e >> 8);
    x[2] = static_cast<std::uint8_t>(e >> 16), x[3] = 0;
  }
}

}  // namespace nut
