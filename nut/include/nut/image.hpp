// nut/image.hpp — an RGBA8 image in memory: what an HNI is before it becomes a PNG.
#pragma once

#include <cstdint>
#include <vector>

#include <nut/hierarchy.hpp>

namespace nut {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // RGBA8, row-major, row 0 first

  Image() = default;
  Image(int w, int h)
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4, 0) {}

  std::uint8_t* at(int x, int y) { return pixels.data() + offset(x, y); }
  const std::uint8_t* at(int x, int y) const { return pixels.data() + offset(x, y); }
  Rgba8 texel(int x, int y) const {
    const std::uint8_t* p = at(x, y);
    return {p[0], p[1], p[2], p[3]};
  }
  std::size_t byteSize() const { return pixels.size(); }
  friend bool operator==(const Image&, const Image&) = default;

 private:
  std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 4;
  }
};

}  // namespace nut
