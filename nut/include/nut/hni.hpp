// nut/hni.hpp — compiling a Hierarchy into an HNI image, decoding it back, validating untrusted
// images, and measuring them. The layout is docs/FORMAT.md; constants are nut/format.hpp.
#pragma once

#include <cstdint>
#include <vector>

#include <nut/error.hpp>
#include <nut/format.hpp>
#include <nut/hierarchy.hpp>
#include <nut/image.hpp>

namespace nut {

struct CompileOptions {
  // The packer tries image widths from the widest record up to this (paper 4.4: 256).
  int maxSearchWidth = format::kMaxSearchWidth;
  // Metadata arrays get at least the pixels that keep the heuristic lookup's error bound
  // D / (512 M) within this many metres (up to the format's 256 pixels); 0 = the fewest pixels.
  // The paper uses the fewest; then a 22 m facade of three cells has M = 3 and boundaries up to
  // 15 mm off, which shows as one-pixel shifts of whole sub-blocks at street distances.
  double heuristicToleranceM = 0.002;
};

// Encodes every block of h (reachable or not) with its headers, metadata arrays, data components,
// redirection records, materials and texture infos packed by MaxRects best-area-fit over a width
// search, keeping the least waste. Lengths are rounded to millimetres (see quantized()). Fails,
// naming the block and axis, when a limit of the format is exceeded.
Result<Image> compile(const Hierarchy& h, const CompileOptions& options = {});

// Checks an untrusted image against every rule of docs/FORMAT.md: magic and version, sizes, every
// address in range and inside its region, every redirection target a block header, no cycles,
// enums in range, reserved bytes zero. The message names the block, field and pixel.
Status validate(const Image& image);

// validate() and then reads the image back into a Hierarchy (summaries included).
Result<Hierarchy> decode(const Image& image);

struct HniStats {
  int blocks = 0;
  long long cells = 0;           // cells of all blocks
  long long solidCells = 0;       // the 69 solids
  long long planeCells = 0;       // version 3
  long long redirectionCells = 0;
  int redirections = 0;          // distinct redirection records
  int materials = 0;
  int textures = 0;
  int width = 0, height = 0;
  long long bytesRaw = 0;        // width * height * 4
  long long usedPixels = 0;      // pixels covered by some record
  double wastePct = 0;           // pixels covered by no record
  int dagDepth = 0;
};

// Statistics of a valid image (validate() it first), computed from the records themselves.
HniStats computeStats(const Image& image);

// The record each pixel of a valid image belongs to. Metadata items have two rows: the
// (i, f, j_left, j_right) row and the exact row below it (docs/FORMAT.md).
enum class PixelKind : std::uint8_t {
  Unused,
  FileRecord,
  BlockTable,
  Header,
  MetadataRow,
  ExactRow,
  DataComponent,
  RedirectionRecord,
  Material,
  TextureInfo,
  PlaneRecord,
};
inline constexpr int kPixelKindCount = 11;
// "data component", "exact row", ...
const char* pixelKindName(PixelKind kind);
// Row-major, width * height entries; the basis of the waste figure and of `nut info --bytes`.
std::vector<PixelKind> pixelKinds(const Image& image);

}  // namespace nut
