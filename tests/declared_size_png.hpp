// tests/declared_size_png.hpp — a PNG of a few dozen bytes whose IHDR declares any size, made byte
// by byte (CRC-32 computed here, not by zlib): what a hostile file looks like to a reader that
// trusts the declared size. Its chunks are well formed (signature, IHDR, IDAT, IEND with correct
// CRCs), so only the size can refuse it; the IDAT holds a one-byte zlib stream, far too little
// for the declared pixels.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace nut::testing {

inline std::uint32_t pngCrc32(const std::uint8_t* bytes, std::size_t count) {
  std::uint32_t crc = 0xffffffffu;
  for (std::size_t i = 0; i < count; ++i) {
    crc ^= bytes[i];
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

inline void appendBigEndian32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<std::uint8_t>(v >> shift));
}

inline void appendChunk(std::vector<std::uint8_t>& out, const char* type, const std::vector<std::uint8_t>& data) {
  appendBigEndian32(out, static_cast<std::uint32_t>(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  appendBigEndian32(out, pngCrc32(&out[start], out.size() - start));
}

// RGBA8, non-interlaced, `width` x `height` as the IHDR declares it.
inline std::vector<std::uint8_t> pngDeclaringSize(std::uint32_t width, std::uint32_t height) {
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<std::uint8_t> ihdr;
  appendBigEndian32(ihdr, width);
  appendBigEndian32(ihdr, height);
  ihdr.insert(ihdr.end(), {8, 6, 0, 0, 0});  // bit depth 8, RGBA, deflate, adaptive filters, no interlace
  appendChunk(png, "IHDR", ihdr);
  // zlib header, one stored block holding the byte 0 (row 0's filter type), Adler-32 of it.
  appendChunk(png, "IDAT", {0x78, 0x01, 0x01, 0x01, 0x00, 0xfe, 0xff, 0x00, 0x00, 0x01, 0x00, 0x01});
  appendChunk(png, "IEND", {});
  return png;
}

inline void writePngDeclaringSize(const std::string& path, std::uint32_t width, std::uint32_t height) {
  const std::vector<std::uint8_t> png = pngDeclaringSize(width, height);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
}

}  // namespace nut::testing
