// web_png_fixtures OUT_DIR [HNI.png ...]: the files of the browser viewer's byte test
// (web_viewer_test.mjs). Each HNI given is copied into OUT_DIR, and PNGs of every layout nut's
// reader widens (grey of 1 to 8 bits, grey + alpha, RGB, palette of 1 to 8 bits, with and without
// tRNS, and RGBA with A = 0 under RGB != 0) are written there with libpng's own encoder, which
// picks the scanline filters itself. Beside each PNG goes NAME.rgba: its pixels as nut's reader
// (libpng) decodes them, the independent reference the page's decoder must match byte for byte.
// files.json lists the names.
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include <png.h>

#include <nut/png_io.hpp>

namespace {

struct Layout {
  std::string name;
  int colourType, bitDepth;
  bool transparency;
};

// Writes random pixels in one layout with libpng; returns false on a libpng error.
bool writeLayout(const std::string& path, const Layout& layout, std::mt19937& random) {
  constexpr int kWidth = 37, kHeight = 23;  // odd sizes: rows end inside a byte at low depths
  const int channels = layout.colourType == PNG_COLOR_TYPE_GRAY || layout.colourType == PNG_COLOR_TYPE_PALETTE ? 1
                       : layout.colourType == PNG_COLOR_TYPE_GRAY_ALPHA                                           ? 2
                       : layout.colourType == PNG_COLOR_TYPE_RGB                                                  ? 3
                                                                                                                  : 4;
  const int maxSample = (1 << layout.bitDepth) - 1;
  const std::size_t stride = (static_cast<std::size_t>(kWidth) * channels * layout.bitDepth + 7) / 8;
  std::vector<std::vector<png_byte>> rows(kHeight, std::vector<png_byte>(stride, 0));
  for (auto& row : rows)
    for (int i = 0; i < kWidth * channels; ++i) {
      // Runs of equal samples (which the filters turn into zeros) between random ones.
      const int value = static_cast<int>(random() % 4 == 0 ? 0 : random() % static_cast<unsigned>(maxSample + 1));
      const int bit = i * layout.bitDepth;
      row[static_cast<std::size_t>(bit / 8)] |= static_cast<png_byte>(value << (8 - layout.bitDepth - bit % 8));
    }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file) return false;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(file);
    return false;
  }
  png_init_io(png, file);
  png_set_IHDR(png, info, kWidth, kHeight, layout.bitDepth, layout.colourType, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  std::vector<png_color> palette;
  std::vector<png_byte> alphas;
  if (layout.colourType == PNG_COLOR_TYPE_PALETTE) {
    for (int i = 0; i <= maxSample; ++i)
      palette.push_back({static_cast<png_byte>(random()), static_cast<png_byte>(random()), static_cast<png_byte>(random())});
    png_set_PLTE(png, info, palette.data(), static_cast<int>(palette.size()));
    if (layout.transparency) {
      for (int i = 0; i <= maxSample / 2; ++i) alphas.push_back(static_cast<png_byte>(random()));
      png_set_tRNS(png, info, alphas.data(), static_cast<int>(alphas.size()), nullptr);
    }
  } else if (layout.transparency) {
    png_color_16 key{};
    key.gray = static_cast<png_uint_16>(maxSample);
    key.red = key.green = key.blue = 0;  // the zero runs above hit it
    png_set_tRNS(png, info, nullptr, 0, &key);
  }
  std::vector<png_bytep> pointers;
  for (auto& row : rows) pointers.push_back(row.data());
  png_set_rows(png, info, pointers.data());
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  png_destroy_write_struct(&png, &info);
  return std::fclose(file) == 0;
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
