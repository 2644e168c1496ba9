// PNG I/O: bit-exact RGBA8 (alpha is data in an HNI, never premultiplied), text chunks with a
// double-precision origin, atomic writes, and one clear error for files that are not PNGs.
#include <gtest/gtest.h>
#include <png.h>
#include <sys/resource.h>
#include <zlib.h>

#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <utility>

#include <nut/png_io.hpp>

#include "declared_size_png.hpp"
#include "foreign_png.hpp"
#include "test_files.hpp"

namespace nut {
namespace {

namespace fs = std::filesystem;
using testing::ForeignPng;
using testing::writeForeignPng;

fs::path outputDir() { return testing::testOutputDir("png_io"); }

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

// Every effort writes a file libpng (an independent decoder) reads back
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
  EXPECT_NE(s.error().message.find("there is no folder " + missing.parent_path().string()), std::string::npos)
      << s.error().message;
  EXPECT_FALSE(fs::exists(missing.parent_path()));
  // A file where the folder should be.
  const fs::path file = outputDir() / "a-file";
  std::ofstream(file) << "not a folder";
  const Status t = writeTextFile((file / "report.json").string(), "{}");
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.error().message.find(file.string() + " is not a folder"), std::string::npos) << t.error().message;
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

// Peak resident memory of this process so far, in bytes (Linux reports ru_maxrss in KiB).
std::uint64_t peakRssBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
}

// A file of 70 bytes that declares more pixels than its kind may have is refused from its IHDR,
// with one error naming the file and the declared size, before any pixel buffer is allocated: the
// peak resident memory grows by less than 16 MiB, where 16384 x 16384 RGBA8 would be 1 GiB.
TEST(PngIo, OversizedIhdrIsRefusedBeforeAllocating) {
  struct Case {
    std::uint32_t width, height;
    PngKind kind;
    std::string bound;
  };
  const std::string hni = "an HNI has at most 4096x4096", render = "a render has at most 16384x16384";
  const Case cases[] = {{100000, 100000, PngKind::Hni, hni},       {16384, 16384, PngKind::Hni, hni},
                        {4097, 1, PngKind::Hni, hni},              {6, 4097, PngKind::Hni, hni},
                        {4294967295u, 1, PngKind::Hni, hni},       {100000, 100000, PngKind::Render, render},
                        {16385, 16, PngKind::Render, render}};
  for (const Case& c : cases) {
    const std::string size = std::to_string(c.width) + "x" + std::to_string(c.height);
    const fs::path path = outputDir() / ("declares-" + size + ".png");
    testing::writePngDeclaringSize(path.string(), c.width, c.height);
    const std::uint64_t before = peakRssBytes();
    auto r = readPng(path.string(), c.kind);
    const std::uint64_t grown = peakRssBytes() - before;
    ASSERT_FALSE(r.ok()) << size;
    EXPECT_EQ(r.error().message, path.string() + ": the PNG declares " + size + " pixels; " + c.bound);
    EXPECT_LT(grown, std::uint64_t{16} << 20) << size;
  }
}

// At the bound the size is accepted, and it is the missing pixel data that is refused.
TEST(PngIo, SizeAtTheBoundIsReadOn) {
  const fs::path path = outputDir() / "declares-4096x4096.png";
  testing::writePngDeclaringSize(path.string(), 4096, 4096);
  auto r = readPng(path.string());
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().message.find("the PNG declares"), std::string::npos) << r.error().message;
  EXPECT_EQ(r.error().message.rfind(path.string() + ": ", 0), 0u) << r.error().message;
}

// Grey, grey + alpha, RGB, palette with transparency and interlaced files widen to RGBA8 as
// stored: no gamma, no premultiplication, missing alpha 255.
TEST(PngIo, OtherLayoutsWidenToRgba) {
  struct Case {
    const char* name;
    ForeignPng png;
    std::vector<std::uint8_t> expected;  // RGBA of the 2 x 1 image
  };
  const std::vector<Case> cases = {
      {"grey", {2, 1, PNG_COLOR_TYPE_GRAY, 8, false, {{7, 200}}, {}, {}}, {7, 7, 7, 255, 200, 200, 200, 255}},
      {"grey1", {2, 1, PNG_COLOR_TYPE_GRAY, 1, false, {{0x40}}, {}, {}}, {0, 0, 0, 255, 255, 255, 255, 255}},
      {"grey_alpha", {2, 1, PNG_COLOR_TYPE_GRAY_ALPHA, 8, false, {{9, 0, 250, 3}}, {}, {}}, {9, 9, 9, 0, 250, 250, 250, 3}},
      {"rgb", {2, 1, PNG_COLOR_TYPE_RGB, 8, false, {{1, 2, 3, 4, 5, 6}}, {}, {}}, {1, 2, 3, 255, 4, 5, 6, 255}},
      {"palette",
       {2, 1, PNG_COLOR_TYPE_PALETTE, 8, false, {{1, 0}}, {{10, 20, 30}, {40, 50, 60}}, {128}},
       {40, 50, 60, 255, 10, 20, 30, 128}},
      {"rgb_keyed",
       {2, 1, PNG_COLOR_TYPE_RGB, 8, false, {{1, 2, 3, 4, 5, 6}}, {}, {}, true, {0, 4, 5, 6, 0}},
       {1, 2, 3, 255, 4, 5, 6, 0}},
      {"interlaced",
       {2, 1, PNG_COLOR_TYPE_RGB_ALPHA, 8, true, {{1, 2, 3, 0, 4, 5, 6, 7}}, {}, {}},
       {1, 2, 3, 0, 4, 5, 6, 7}},
  };
  for (const Case& c : cases) {
    const fs::path path = outputDir() / (std::string("layout_") + c.name + ".png");
    ASSERT_TRUE(writeForeignPng(path, c.png)) << c.name;
    auto read = readPng(path.string());
    ASSERT_TRUE(read.ok()) << c.name << ": " << read.error().message;
    EXPECT_EQ(read->image.width, 2);
    EXPECT_EQ(read->image.height, 1);
    EXPECT_EQ(read->image.pixels, c.expected) << c.name;
  }
}

TEST(PngIo, SixteenBitFilesAreRefused) {
  const fs::path path = outputDir() / "sixteen.png";
  ASSERT_TRUE(writeForeignPng(path, {1, 1, PNG_COLOR_TYPE_RGB, 16, false, {{0, 1, 0, 2, 0, 3}}, {}, {}}));
  auto read = readPng(path.string());
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().message, path.string() + ": not an 8-bit PNG (16 bits per channel)");
}

// A file whose chunks are sound but whose image data is not: one line from the decoder.
TEST(PngIo, BadImageDataIsNamed) {
  const fs::path path = outputDir() / "bad_data.png";
  ASSERT_TRUE(writePng(path.string(), randomImage(8, 8, 9)).ok());
  std::vector<std::uint8_t> bytes(fs::file_size(path));
  std::ifstream(path, std::ios::binary).read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  // Find IDAT, break its zlib header (CMF byte), and fix the chunk's CRC so only the data is wrong.
  std::size_t at = 8;
  while (std::string(bytes.begin() + static_cast<std::ptrdiff_t>(at) + 4, bytes.begin() + static_cast<std::ptrdiff_t>(at) + 8) != "IDAT")
    at += 12 + (std::size_t{bytes[at]} << 24 | std::size_t{bytes[at + 1]} << 16 | std::size_t{bytes[at + 2]} << 8 | bytes[at + 3]);
  const std::size_t length = std::size_t{bytes[at]} << 24 | std::size_t{bytes[at + 1]} << 16 | std::size_t{bytes[at + 2]} << 8 | bytes[at + 3];
  bytes[at + 8] = 0x0f;  // compression method 15: not deflate
  const auto crc = png_uint_32(crc32(crc32(0L, Z_NULL, 0), &bytes[at + 4], static_cast<unsigned>(length + 4)));
  for (int i = 0; i < 4; ++i) bytes[at + 8 + length + static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(crc >> (24 - 8 * i));
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  auto read = readPng(path.string());
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().message.rfind(path.string() + ": ", 0), 0u) << read.error().message;
  EXPECT_EQ(read.error().message.find('\n'), std::string::npos) << read.error().message;
}

}  // namespace
}  // namespace nut
