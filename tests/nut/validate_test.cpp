// validate() against hostile images: each rule of docs/FORMAT.md broken on purpose, every prefix
// of an image, and decode() refusing what validate() refuses.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <nut/hni.hpp>
#include <nut/hni_view.hpp>
#include <nut/units.hpp>

#include "expect_rejected.hpp"
#include "random_hierarchy.hpp"

namespace nut {
namespace {

// Root (2 cells: redirect to A, box) -> A (2 cells: redirect to B, wedge) -> B (one box).
Hierarchy chain() {
  Hierarchy h;
  h.materials = {{200, 40, 40}, {40, 200, 40}};
  Block root = Block::fromSizes({{{2.0, 1.0}, {3.0}, {1.0}}});
  root.redirections.push_back({1});
  root.cell(0, 0, 0) = Cell::redirect(0);
  root.cell(1, 0, 0) = Cell::box(0);
  Block a = Block::fromSizes({{{2.0}, {1.5, 1.5}, {1.0}}});
  a.redirections.push_back({2, {0.1, 0.2, 0.0}});
  a.cell(0, 0, 0) = Cell::redirect(0);
  a.cell(0, 1, 0) = Cell::solidCell(Solid{3}, 1);
  Block b = Block::fromSizes({{{0.5}, {0.5}, {0.5}}});
  b.cell(0, 0, 0) = Cell::box(1);
  h.addBlock(root);
  h.addBlock(a);
  h.addBlock(b);
  return h;
}

struct Fixture : ::testing::Test {
  void SetUp() override {
    auto compiled = compile(chain());
    ASSERT_TRUE(compiled.ok()) << compiled.error().message;
    image = *compiled;
    ASSERT_TRUE(validate(image).ok()) << validate(image).error().message;
  }
  HniView view() const { return HniView(image); }
  BlockHeader header(int block) const { return view().header(view().blockAddress(view().fileRecord(), block)); }
  TexelAddress headerAt(int block) const { return view().blockAddress(view().fileRecord(), block); }
  std::uint8_t* cell(int block, glm::ivec3 c) {
    const BlockHeader h = header(block);
    return image.at(h.data.u + c.x + c.z * h.cells.x, h.data.v + h.cells.y - 1 - c.y);
  }
  // Expects validate and decode to fail with a message containing `needle`.
  void expectRejected(const std::string& needle) const { testing::expectRejected(image, needle); }
  Image image;
};

TEST_F(Fixture, WrongMagic) {
  image.at(0, 0)[1] = 'X';
  expectRejected("wrong magic");
}

TEST_F(Fixture, WrongVersion) {
  image.at(0, 0)[3] = 9;
  expectRejected("unsupported version 9");
}

TEST_F(Fixture, TruncatedPixelBuffer) {
  image.pixels.resize(image.pixels.size() - 3);
  expectRejected("truncated");
}

TEST_F(Fixture, EveryShorterImageIsRejected) {
  const Image full = image;
  for (int rows = 1; rows < full.height; ++rows) {
    image = Image(full.width, rows);
    std::copy_n(full.pixels.begin(), image.pixels.size(), image.pixels.begin());
    EXPECT_FALSE(validate(image).ok()) << rows << " rows";
  }
  for (int columns = 1; columns < full.width; ++columns) {
    image = Image(columns, full.height);
    for (int y = 0; y < full.height; ++y) std::copy_n(full.at(0, y), columns * 4, image.at(0, y));
    EXPECT_FALSE(validate(image).ok()) << columns << " columns";
  }
}

TEST_F(Fixture, OversizedDimensions) {
  image = Image(format::kMaxImageSize + 1, 2);
  expectRejected("exceeds the 4096 px limit");
}

TEST_F(Fixture, DataAddressOutOfRange) {
  const TexelAddress h = headerAt(1);
  std::uint8_t* z = image.at(h.u + format::kHeaderMetaZ, h.v);
  z[3] = 0xff;  // v of the data component far below the image
  expectRejected("block 1 header");
}

TEST_F(Fixture, MetadataAddressOutOfRange) {
  const TexelAddress h = headerAt(0);
  image.at(h.u + format::kHeaderMetaXY, h.v)[0] = 255;  // the x array would run past u = 256
  expectRejected("axis x: metadata array");
}

TEST_F(Fixture, RedirectionTargetNotAHeader) {
  std::uint8_t* c = cell(0, {0, 0, 0});
  const TexelAddress record{c[0], c[1]};
  image.at(record.u + 3, record.v)[0] ^= 1;
  expectRejected("is not a block header");
}

TEST_F(Fixture, LevelOfDetailByteInAVersion1File) {
  std::uint8_t* c = cell(0, {0, 0, 0});
  image.at(c[0] + format::kRedirectionLodPixel, c[1])[3] = 5;
  expectRejected("level-of-detail byte is not zero in a version 1 file");
}

// Root with two redirections to one block, at different offsets: two records, one target.
Hierarchy twoRecordsToOneBlock(double footprintM) {
  Hierarchy h;
  h.materials = {{90, 90, 200}};
  Block root = Block::fromSizes({{{1.0, 1.0}, {1.0}, {1.0}}});
  root.redirections = {{1}, {1, {0.0, 0.25, 0.0}}};
  root.cell(0, 0, 0) = Cell::redirect(0);
  root.cell(1, 0, 0) = Cell::redirect(1);
  Block b = Block::fromSizes({{{0.5}, {0.5}, {0.5}}});
  b.cell(0, 0, 0) = Cell::box(0);
  b.lodFootprintM = footprintM;
  h.addBlock(root);
  h.addBlock(b);
  return h;
}

TEST(LevelOfDetailFormat, FootprintsRoundTripInAVersion2File) {
  const Hierarchy h = twoRecordsToOneBlock(0.3);
  auto image = compile(h);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_EQ(image->at(0, 0)[3], format::kVersionLod);
  auto decoded = decode(*image);
  ASSERT_TRUE(decoded) << decoded.error().message;
  // 0.3 m is coded as the next step up: 2^(-28/16) = 0.2973 is below it, 2^(-27/16) = 0.3100 not.
  EXPECT_DOUBLE_EQ(decoded->blocks[1].lodFootprintM, std::exp2(-27.0 / 16.0));
  EXPECT_EQ(decoded->blocks[1].lodFootprintM, quantized(h).blocks[1].lodFootprintM);
  auto again = compile(*decoded);
  ASSERT_TRUE(again);
  EXPECT_EQ(*again, *image);
}

TEST(LevelOfDetailFormat, NoFootprintWritesVersion1) {
  auto image = compile(twoRecordsToOneBlock(0.0));
  ASSERT_TRUE(image);
  EXPECT_EQ(image->at(0, 0)[3], format::kVersion);
}

TEST(LevelOfDetailFormat, RecordsToOneBlockMustAgree) {
  auto image = compile(twoRecordsToOneBlock(0.3));
  ASSERT_TRUE(image);
  const HniView view(*image);
  const BlockHeader root = view.header(view.blockAddress(view.fileRecord(), 0));
  const CellTexel second = view.cell(root, {1, 0, 0});
  image->at(second.redirection.u + format::kRedirectionLodPixel, second.redirection.v)[3] += 1;
  const Status s = validate(*image);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("differs from"), std::string::npos) << s.error().message;
}

TEST(LevelOfDetailFormat, CodesAndFootprints) {
  EXPECT_EQ(lodCode(0.0), 0);
  EXPECT_EQ(lodCode(-1.0), 0);
  EXPECT_EQ(lodCode(std::nan("")), 0);
  EXPECT_EQ(lodFootprintM(0), 0.0);
  EXPECT_EQ(lodFootprintM(format::kLodCodeOneMetre), 1.0);
  EXPECT_EQ(lodCode(1e-6), 1) << "below the smallest footprint: clamped up";
  EXPECT_EQ(lodCode(1e6), 255) << "above the largest: clamped";
  for (int c = 1; c <= 255; ++c) EXPECT_EQ(lodCode(lodFootprintM(static_cast<std::uint8_t>(c))), c);
  // Rounding is up: the stored footprint is never below the measured one (inside the range).
  for (double m = lodFootprintM(1); m < lodFootprintM(255); m *= 1.013) EXPECT_GE(lodFootprintM(lodCode(m)), m);
}

TEST_F(Fixture, Cycle) {
  // Point A's record (to B) back at the root: root -> A -> root.
  std::uint8_t* c = cell(1, {0, 0, 0});
  std::uint8_t* target = image.at(c[0] + 3, c[1]);
  const TexelAddress root = headerAt(0);
  target[0] = static_cast<std::uint8_t>(root.u), target[1] = static_cast<std::uint8_t>(root.v);
  expectRejected("cycle");
}

TEST_F(Fixture, SelfRedirection) {
  std::uint8_t* c = cell(1, {0, 0, 0});
  std::uint8_t* target = image.at(c[0] + 3, c[1]);
  const TexelAddress self = headerAt(1);
  target[0] = static_cast<std::uint8_t>(self.u), target[1] = static_cast<std::uint8_t>(self.v);
  expectRejected("cycle");
}

TEST_F(Fixture, BadCellDescriptor) {
  cell(2, {0, 0, 0})[3] = 200;
  expectRejected("g = 200 is out of range");
}

TEST_F(Fixture, BadRotationAndTiling) {
  std::uint8_t* c = cell(0, {0, 0, 0});
  image.at(c[0] + 1, c[1])[3] = 24;
  expectRejected("rotation 24 out of range");
  image.at(c[0] + 1, c[1])[3] = 0;
  image.at(c[0], c[1])[3] = 8;
  expectRejected("tiling flags 8 out of range");
}

TEST_F(Fixture, MaterialOutOfRange) {
  cell(2, {0, 0, 0})[0] = 7;
  expectRejected("material 7 out of range");
}

TEST_F(Fixture, InconsistentMetadataPixel) {
  const BlockHeader h = header(1);
  std::uint8_t* meta = image.at(h.meta[1].u, h.meta[1].v);
  meta[4 * 0 + 3] ^= 1;  // a wrong j_right on the y axis
  expectRejected("axis y metadata pixel 0");
}

TEST_F(Fixture, ExactRowDisagreesWithF) {
  const BlockHeader h = header(1);
  for (int k = 0; k < h.metaPixels[1]; ++k)
    if (image.at(h.meta[1].u + k, h.meta[1].v)[1] != 0) image.at(h.meta[1].u + k, h.meta[1].v + 1)[0] ^= 0x40;
  expectRejected("does not match the exact boundary");
}

TEST_F(Fixture, RootNotAHeader) {
  image.at(format::kFileRoot, 0)[0] ^= 1;
  expectRejected("root");
}

// Arbitrary bytes never crash validate or decode (the libFuzzer target explores this further).
TEST(Validate, RandomBytesAndMutationsNeverCrash) {
  std::mt19937_64 rng(5);
  auto compiled = compile(testing::randomHierarchy(3));
  ASSERT_TRUE(compiled.ok());
  int accepted = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    Image image = *compiled;
    const int flips = std::uniform_int_distribution<int>(1, 8)(rng);
    for (int f = 0; f < flips; ++f)
      image.pixels[std::uniform_int_distribution<std::size_t>(0, image.pixels.size() - 1)(rng)] =
          static_cast<std::uint8_t>(rng());
    if (validate(image).ok()) {
      ++accepted;
      ASSERT_TRUE(decode(image).ok());
      (void)computeStats(image);
    }
  }
  RecordProperty("mutants_accepted", accepted);
}

}  // namespace
}  // namespace nut
