// PNG I/O: bit-exact RGBA8 (alpha is data in an HNI, never premultiplied), text chunks with a
// double-precision origin, atomic writes, and one clear error for files that are not PNGs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <cstdint>
#include <random>
#include <utility>

#include <nut/png_io.hpp>

namespace nut {
namespace {

namespace fs = std::filesystem;

fs::path outputDir() {
  const fs::path dir = fs::path(NUT_TEST_OUTPUT_DIR) / "png_io";
  fs::create_directories(dir);
  return dir;
}

Image randomImage(int w, int h, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Image image(w, h);
  for (auto& byte : image.pixels) byte = static_cast<std::uint8_t>(rng());
  // Transparent pixels with colour are the case premultiplication would destroy.
  for (std::size_t i = 0; i < image.pixels.size(); i += 16) image.pixels[i + 3] = 0;
  return image;
}

TEST(PngIo, RoundTripIsBitExact) {
  const fs::path path = outputDir() / "random.png";
  const Image image = randomImage(37, 11, 1);
  HniText text{"test building", "png_io_test", "m", {1234567.891234567, -0.125, 7654321.000000001}};
  ASSERT_TRUE(writeHni(path.string(), image, text).ok());
  auto read = readPng(path.string());
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->image, image);
  EXPECT_EQ(read->text.name, text.name);
  EXPECT_EQ(read->text.generator, text.generator);
  EXPECT_EQ(read->text.units, "m");
  EXPECT_EQ(read->text.originM, text.originM);  // %.17g keeps doubles exact
  EXPECT_EQ(read->fileBytes, fs::file_size(path));
}

// An image like an HNI: runs of zeros, repeated rows, a few noisy records.
Image structuredImage(int w, int h, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Image image(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.at(x, y);
      if (y % 3 == 0 && x < w / 2) p[0] = static_cast<std::uint8_t>(x / 4), p[3] = 2;  // repeated rows
      if (y == h / 2 && x % 7 == 0) {
        for (int c = 0; c < 4; ++c) p[c] = static_cast<std::uint8_t>(rng());
      }
    }
  return image;
}

// Every effort writes a file libpng (through OpenImageIO, an independent decoder) reads back
// bit-exactly, for shapes that exercise the filters' edges (one column, one row), and a higher
// effort is never larger.
TEST(PngIo, EveryEffortRoundTripsAndHigherEffortsAreNotLarger) {
  // 400x200 (320 KB) is deflated in parts on machines with several cores.
  for (const auto& [w, h] : {std::pair{1, 1}, {1, 9}, {9, 1}, {64, 48}, {300, 17}, {400, 200}}) {
    for (const Image& image : {randomImage(w, h, 7), structuredImage(w, h, 8)}) {
      std::size_t previous = SIZE_MAX;
      for (PngEffort effort : {PngEffort::Quick, PngEffort::Small, PngEffort::Smallest}) {
        const fs::path path = outputDir() / "effort.png";
        ASSERT_TRUE(writePng(path.string(), image, effort).ok());
        auto read = readPng(path.string());
        ASSERT_TRUE(read.ok()) << read.error().message;
        EXPECT_EQ(read->image, image) << w << "x" << h << " effort " << static_cast<int>(effort);
        if (effort != PngEffort::Quick) {
          EXPECT_LE(read->fileBytes, previous) << w << "x" << h;
        }
        previous = read->fileBytes;
      }
    }
  }
}

TEST(PngIo, WriteLeavesNoTemporaryFiles) {
  const fs::path dir = outputDir() / "atomic";
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_TRUE(writePng((dir / "a.png").string(), randomImage(4, 4, 2)).ok());
  ASSERT_TRUE(writePng((dir / "a.png").string(), randomImage(5, 5, 3)).ok());  // overwrite in place
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    ++files;
    EXPECT_EQ(entry.path().filename(), "a.png");
  }
  EXPECT_EQ(files, 1);
  EXPECT_EQ(readPng((dir / "a.png").string())->image.width, 5);
}

TEST(PngIo, FailedWriteLeavesNothing) {
  const fs::path missing = outputDir() / "no-such-dir" / "x.png";
  const Status s = writePng(missing.string(), randomImage(2, 2, 4));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("x.png"), std::string::npos) << s.error().message;
  EXPECT_FALSE(fs::exists(missing.parent_path()));
}

TEST(PngIo, ReadErrorsNameTheFile) {
  const fs::path notPng = outputDir() / "not-a.png";
  std::ofstream(notPng) << "this is text, not an image";
  auto r = readPng(notPng.string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message.rfind(notPng.string(), 0), 0u) << r.error().message;
  auto missing = readPng((outputDir() / "missing.png").string());
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("no such file"), std::string::npos);
}

TEST(PngIo, TruncatedPngIsAnError) {
  const fs::path path = outputDir() / "truncated.png";
  ASSERT_TRUE(writePng(path.string(), randomImage(64, 64, 5)).ok());
  const auto size = fs::file_size(path);
  for (auto keep : {size / 2, size - 20, std::uintmax_t{40}}) {
    fs::resize_file(path, keep);
    EXPECT_FALSE(readPng(path.string()).ok()) << keep << " bytes";
    ASSERT_TRUE(writePng(path.string(), randomImage(64, 64, 5)).ok());
  }
}

TEST(PngIo, CorruptChunkIsNamed) {
  const fs::path path = outputDir() / "corrupt.png";
  ASSERT_TRUE(writePng(path.string(), randomImage(16, 16, 6)).ok());
  {
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(40);  // inside the first chunks after IHDR
    f.put('\x5a');
  }
  auto r = readPng(path.string());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("CRC mismatch in chunk"), std::string::npos) << r.error().message;
}

}  // namespace
}  // namespace nut
