// nut/png_io.hpp — HNI images as PNG files (read by libpng, written by png_encode), with
// human metadata in text chunks.
//
// Pixels are stored and read back bit-exactly: alpha is never premultiplied, no colour conversion.
// Writes go to a temporary file in the destination folder that is renamed over the destination,
// so a failure never leaves a half-written file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/image.hpp>
#include <nut/png_encode.hpp>

namespace nut {

struct PngFile {
  Image image;
  HniText text;
  std::uintmax_t fileBytes = 0;
};

// Writes an RGBA8 image (a render, a diff) as PNG.
Status writePng(const std::string& path, const Image& image, PngEffort effort = PngEffort::Quick);

// Writes an HNI: its pixels and text chunks, as small as the effort allows (png_encode.hpp).
Status writeHni(const std::string& path, const Image& image, const HniText& text,
                PngEffort effort = PngEffort::Smallest);

// Writes a single-channel float image (e.g. depth) as a little-endian PFM, rows bottom to top as
// the format wants; same temporary-file-and-rename rule.
Status writePfm(const std::string& path, int width, int height, const std::vector<float>& values);

// Reads a whole file (OBJ, MTL, manifests) into memory; errors name the file: missing, a
// directory, unreadable.
Result<std::string> readTextFile(const std::string& path);

// Writes a text file (JSON reports) with the same temporary-file-and-rename rule.
Status writeTextFile(const std::string& path, const std::string& text);

// What a PNG is read as, which bounds the size its IHDR may declare. The bound is checked on the
// IHDR, before any pixel buffer is allocated, so a file of a few bytes cannot make the reader
// allocate more than the bound allows:
//   Hni     at most format::kMaxImageSize per side (4096 x 4096, docs/FORMAT.md, 64 MiB of pixels);
//           the smallest HNI (6 x 1) is validate's rule, not the reader's.
//   Render  at most kMaxRenderSize per side (16384 x 16384, camera.hpp, 1 GiB): renders and diffs.
enum class PngKind { Hni, Render };

// Reads a PNG as RGBA8 (grey and RGB files gain channels; 16-bit files are refused). Errors name
// the file; a size over the kind's bound: "<file>: the PNG declares WxH pixels; an HNI has at most
// 4096x4096" (for a render: "a render has at most 16384x16384").
Result<PngFile> readPng(const std::string& path, PngKind kind = PngKind::Hni);

// The same on the bytes of a PNG already in memory (a download); `name` names it in errors.
Result<PngFile> readPngBytes(const std::string& name, std::vector<std::uint8_t> bytes, PngKind kind = PngKind::Hni);

}  // namespace nut
