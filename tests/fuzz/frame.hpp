// The byte framing shared by the fuzz target, its seed writer and its corpus test.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <nut/image.hpp>

namespace nut::fuzz {

// u16 width (little-endian), then pixel bytes. The height is the number of whole rows the bytes
// hold; the pixel buffer keeps every byte, so a ragged tail reaches validate's size check.
inline Image unframe(const std::uint8_t* data, std::size_t size) {
  Image image;
  if (size < 2) return image;
  image.width = data[0] | data[1] << 8;
  image.pixels.assign(data + 2, data + size);
  image.height = image.width > 0 ? static_cast<int>(image.pixels.size() / (4 * static_cast<std::size_t>(image.width))) : 0;
  return image;
}

inline std::vector<std::uint8_t> frame(const Image& image) {
  // Sized once and copied into: GCC 12 misreads an insert after a two-byte vector (-Warray-bounds).
  std::vector<std::uint8_t> bytes(2 + image.pixels.size());
  bytes[0] = static_cast<std::uint8_t>(image.width);
  bytes[1] = static_cast<std::uint8_t>(image.width >> 8);
  std::copy(image.pixels.begin(), image.pixels.end(), bytes.begin() + 2);
  return bytes;
}

}  // namespace nut::fuzz
