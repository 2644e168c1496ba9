// web_png_fixtures OUT_DIR [HNI.png ...]: the files of the browser viewer's byte test
// (web_viewer_test.mjs). Each HNI given is copied into OUT_DIR, and PNGs of every layout nut's
// reader widens (grey of 1 to 8 bits, grey + alpha, RGB, palette of 1 to 8 bits, with and without
// tRNS, and RGBA with A = 0 under RGB != 0) are written there with libpng's own encoder, which
// picks the scanline filters itself. Beside each PNG goes NAME.rgba: its pixels as nut's reader
// (libpng) decodes them, the independent reference the page's decoder must match byte for byte.
// files.json lists the names.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <nut/png_io.hpp>

#include "foreign_png.hpp"

namespace {

struct Layout {
  std::string name;
  int colourType, bitDepth;
  bool transparency;
};

// Random pixels in one layout, written by libpng; returns false on a libpng error.
bool writeLayout(const std::string& path, const Layout& layout, std::mt19937& random) {
  constexpr int kWidth = 37, kHeight = 23;  // odd sizes: rows end inside a byte at low depths
  const int channels = layout.colourType == PNG_COLOR_TYPE_GRAY || layout.colourType == PNG_COLOR_TYPE_PALETTE ? 1
                       : layout.colourType == PNG_COLOR_TYPE_GRAY_ALPHA                                           ? 2
                       : layout.colourType == PNG_COLOR_TYPE_RGB                                                  ? 3
                                                                                                                  : 4;
  const int maxSample = (1 << layout.bitDepth) - 1;
  const std::size_t stride = (static_cast<std::size_t>(kWidth) * channels * layout.bitDepth + 7) / 8;
  nut::testing::ForeignPng png{kWidth, kHeight, layout.colourType, layout.bitDepth};
  png.rows.assign(kHeight, std::vector<std::uint8_t>(stride, 0));
  for (auto& row : png.rows)
    for (int i = 0; i < kWidth * channels; ++i) {
      // Runs of equal samples (which the filters turn into zeros) between random ones.
      const int value = static_cast<int>(random() % 4 == 0 ? 0 : random() % static_cast<unsigned>(maxSample + 1));
      const int bit = i * layout.bitDepth;
      row[static_cast<std::size_t>(bit / 8)] |= static_cast<std::uint8_t>(value << (8 - layout.bitDepth - bit % 8));
    }
  if (layout.colourType == PNG_COLOR_TYPE_PALETTE) {
    for (int i = 0; i <= maxSample; ++i)
      png.palette.push_back({static_cast<png_byte>(random()), static_cast<png_byte>(random()), static_cast<png_byte>(random())});
    if (layout.transparency)
      for (int i = 0; i <= maxSample / 2; ++i) png.paletteAlpha.push_back(static_cast<std::uint8_t>(random()));
  } else if (layout.transparency) {
    png.keyed = true;
    png.key.gray = static_cast<png_uint_16>(maxSample);  // the keys the random samples hit: grey at
    png.key.red = png.key.green = png.key.blue = 0;      // its maximum, RGB in the zero runs
  }
  return nut::testing::writeForeignPng(path, png);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: web_png_fixtures OUT_DIR [HNI.png ...]\n");
    return 2;
  }
  const std::filesystem::path out = argv[1];
  std::filesystem::create_directories(out);
  std::vector<std::string> names;
  for (int i = 2; i < argc; ++i) {
    const std::string name = std::filesystem::path(argv[i]).filename().string();
    std::filesystem::copy_file(argv[i], out / name, std::filesystem::copy_options::overwrite_existing);
    names.push_back(name);
  }
  const std::vector<Layout> layouts = {
      {"grey1", PNG_COLOR_TYPE_GRAY, 1, false},        {"grey2_trns", PNG_COLOR_TYPE_GRAY, 2, true},
      {"grey4", PNG_COLOR_TYPE_GRAY, 4, false},        {"grey8_trns", PNG_COLOR_TYPE_GRAY, 8, true},
      {"grey_alpha8", PNG_COLOR_TYPE_GRAY_ALPHA, 8, false}, {"rgb8", PNG_COLOR_TYPE_RGB, 8, false},
      {"rgb8_trns", PNG_COLOR_TYPE_RGB, 8, true},      {"palette1", PNG_COLOR_TYPE_PALETTE, 1, false},
      {"palette4_trns", PNG_COLOR_TYPE_PALETTE, 4, true}, {"palette8_trns", PNG_COLOR_TYPE_PALETTE, 8, true},
      {"rgba8", PNG_COLOR_TYPE_RGB_ALPHA, 8, false}};
  std::mt19937 random(2026);
  for (const Layout& layout : layouts) {
    const std::string name = "layout_" + layout.name + ".png";
    if (!writeLayout((out / name).string(), layout, random)) {
      std::fprintf(stderr, "error: %s: libpng could not write it\n", (out / name).c_str());
      return 1;
    }
    names.push_back(name);
  }
  std::string list = "[";
  for (const std::string& name : names) {
    auto png = nut::readPng((out / name).string(), nut::PngKind::Render);
    if (!png) {
      std::fprintf(stderr, "error: %s\n", png.error().message.c_str());
      return 1;
    }
    const auto& pixels = png->image.pixels;
    const std::string raw(reinterpret_cast<const char*>(pixels.data()), pixels.size());
    if (nut::Status s = nut::writeTextFile((out / (name + ".rgba")).string(), raw); !s) {
      std::fprintf(stderr, "error: %s\n", s.error().message.c_str());
      return 1;
    }
    list += (list.size() > 1 ? ", \"" : "\"") + name + "\"";
  }
  list += "]\n";
  if (nut::Status s = nut::writeTextFile((out / "files.json").string(), list); !s) {
    std::fprintf(stderr, "error: %s\n", s.error().message.c_str());
    return 1;
  }
  std::printf("%zu PNGs and their RGBA bytes in %s\n", names.size(), out.c_str());
  return 0;
}
