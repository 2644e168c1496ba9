// nut/png_io.hpp — HNI images as PNG files (OpenImageIO), with human metadata in text chunks.
//
// Pixels are stored and read back bit-exactly: alpha is never premultiplied, no colour conversion.
// Writes go to a temporary file in the destination folder that is renamed over the destination,
// so a failure never leaves a half-written file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/error.hpp>
#include <nut/image.hpp>

namespace nut {

// Stored as PNG text chunks nut:name, nut:generator, nut:units, nut:origin ("x y z", metres).
struct HniText {
  std::string name;
  std::string generator;
  std::string units = "m";
  glm::dvec3 originM{0.0};  // world position of the root block's origin, full double precision
};

struct PngFile {
  Image image;
  HniText text;
  std::uintmax_t fileBytes = 0;
};

// Writes an RGBA8 image. The PNG is compressed at the highest zlib level.
Status writePng(const std::string& path, const Image& image, const HniText& text = {});

// Writes a single-channel float image (e.g. depth) as a little-endian PFM, rows bottom to top as
// the format wants; same temporary-file-and-rename rule.
Status writePfm(const std::string& path, int width, int height, const std::vector<float>& values);

// Reads a whole file (OBJ, MTL, manifests) into memory; errors name the file: missing, a
// directory, unreadable.
Result<std::string> readTextFile(const std::string& path);

// Writes a text file (JSON reports) with the same temporary-file-and-rename rule.
Status writeTextFile(const std::string& path, const std::string& text);

// Reads a PNG as RGBA8 (grey and RGB files gain channels; 16-bit files are refused). Errors name
// the file.
Result<PngFile> readPng(const std::string& path);

}  // namespace nut
