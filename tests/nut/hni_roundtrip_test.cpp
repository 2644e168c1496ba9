// compile / decode round trips on seeded random hierarchies, and the metadata error bound measured
// through HniView on every boundary of every block, the way the shader reads the image; and every
// hierarchy rule and format limit compile() enforces, each refused naming where.
#include <gtest/gtest.h>

#include <nut/hni.hpp>
#include <nut/hni_view.hpp>
#include <nut/units.hpp>

#include "random_hierarchy.hpp"

namespace nut {
namespace {

Hierarchy withoutSummaries(Hierarchy h) {
  for (Block& b : h.blocks) b.summary.reset();
  return h;
}

TEST(HniRoundTrip, RandomHierarchiesDecodeToTheirQuantizedSelf) {
  for (std::uint64_t seed = 0; seed < 300; ++seed) {
    const Hierarchy h = testing::randomHierarchy(seed);
    auto image = compile(h);
    ASSERT_TRUE(image.ok()) << "seed " << seed << ": " << image.error().message;
    ASSERT_TRUE(validate(*image).ok()) << "seed " << seed << ": " << validate(*image).error().message;
    auto decoded = decode(*image);
    ASSERT_TRUE(decoded.ok()) << "seed " << seed << ": " << decoded.error().message;
    ASSERT_EQ(withoutSummaries(*decoded), quantized(h)) << "seed " << seed;
    // Re-encoding the decoded hierarchy reproduces the image byte for byte.
    auto again = compile(*decoded);
    ASSERT_TRUE(again.ok());
    ASSERT_EQ(*again, *image) << "seed " << seed;
  }
}

TEST(HniRoundTrip, MillimetreGridIsExact) {
  for (std::uint64_t seed = 1000; seed < 1100; ++seed) {
    // A producer that works in whole millimetres: every boundary is toMetres(integer).
    Hierarchy h = testing::randomHierarchy(seed);
    for (Block& block : h.blocks)
      for (auto& bounds : block.boundsM)
        for (double& b : bounds) b = toMetres(toUnits(b));
    auto image = compile(h);
    ASSERT_TRUE(image.ok()) << image.error().message;
    auto decoded = decode(*image);
    ASSERT_TRUE(decoded.ok());
    for (std::size_t b = 0; b < h.blocks.size(); ++b)
      ASSERT_EQ(decoded->blocks[b].boundsM, h.blocks[b].boundsM) << "seed " << seed << " block " << b;
  }
}

TEST(HniRoundTrip, LargeHierarchiesUseSeveralRowsOfEveryTable) {
  testing::RandomHierarchyOptions options;
  options.minBlocks = 300;
  options.maxBlocks = 320;
  options.maxCellsPerAxis = 3;
  const Hierarchy h = testing::randomHierarchy(7, options);
  auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  auto decoded = decode(*image);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  EXPECT_EQ(withoutSummaries(*decoded), quantized(h));
}

TEST(HniRoundTrip, TwoHundredBlocksKeepTheirRecordsInTheMetadataRegion) {
  // By area alone the data components would take the top rows first; compile falls back to
  // placing the 8-bit-addressed records first.
  testing::RandomHierarchyOptions options;
  options.minBlocks = options.maxBlocks = 200;
  const Hierarchy h = testing::randomHierarchy(9, options);
  auto image = compile(h);
  ASSERT_TRUE(image.ok()) << image.error().message;
  auto decoded = decode(*image);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  EXPECT_EQ(withoutSummaries(*decoded), quantized(h));
}

// Paper 3.2: E <= D / (512 (W + w)) for the heuristic; the exact row is the model's boundary.
TEST(HniRoundTrip, HeuristicErrorWithinBoundOnEveryBoundaryExactErrorZero) {
  long long boundaries = 0;
  double worstRatio = 0;
  for (std::uint64_t seed = 0; seed < 300; ++seed) {
    const Hierarchy h = quantized(testing::randomHierarchy(seed));
    auto image = compile(h);
    ASSERT_TRUE(image.ok());
    const HniView view(*image);
    const FileRecord file = view.fileRecord();
    for (int b = 0; b < file.blockCount; ++b) {
      const BlockHeader header = view.header(view.blockAddress(file, b));
      for (int a = 0; a < 3; ++a) {
        const AxisView axis = view.axis(header, a);
        const auto& truth = h.blocks[static_cast<std::size_t>(b)].boundsM[static_cast<std::size_t>(a)];
        const double D = header.sizeUnits[a];
        const double bound = D / (512.0 * axis.pixels);
        int m = 1;
        for (int k = 0; k < axis.pixels; ++k) {
          if (axis.meta[4 * k + 1] == 0) continue;
          const double exact = static_cast<double>(toUnits(truth[static_cast<std::size_t>(m)]));
          const double heuristic = (k + axis.meta[4 * k + 1] / 256.0) * D / axis.pixels;
          ASSERT_LE(std::abs(heuristic - exact), bound) << "seed " << seed << " block " << b << " axis " << a;
          worstRatio = std::max(worstRatio, std::abs(heuristic - exact) / bound);
          ASSERT_EQ(axis.exactPosition(k), exact);
          ++m;
          ++boundaries;
        }
      }
    }
  }
  RecordProperty("boundaries_checked", std::to_string(boundaries));
  RecordProperty("worst_error_over_bound", std::to_string(worstRatio));
  EXPECT_GT(boundaries, 5000);
}

// Paper 4.4: with many blocks the width search wastes little. Target: at most 1 % mean for
// hierarchies of 40+ blocks; the figure goes to docs/PERFORMANCE.md.
TEST(HniCompile, PackingWasteOfOneHundredHierarchiesOfFortyPlusBlocks) {
  testing::RandomHierarchyOptions options;
  options.minBlocks = 40;
  options.maxBlocks = 120;
  double sum = 0, worst = 0;
  for (std::uint64_t seed = 0; seed < 100; ++seed) {
    auto image = compile(testing::randomHierarchy(5000 + seed, options));
    ASSERT_TRUE(image.ok()) << image.error().message;
    const double waste = computeStats(*image).wastePct;
    sum += waste;
    worst = std::max(worst, waste);
  }
  const double mean = sum / 100;
  std::printf("packing waste over 100 random hierarchies of 40-120 blocks: mean %.2f %%, max %.2f %%\n", mean, worst);
  RecordProperty("waste_mean_pct", std::to_string(mean));
  RecordProperty("waste_max_pct", std::to_string(worst));
  EXPECT_LE(mean, 1.0);
}

TEST(HniCompile, NamesTheBlockAndAxisThatBreaksALimit) {
  Hierarchy h;
  h.materials.push_back({});
  h.addBlock(Block::fromSizes({{{1.0}, {1.0}, {1.0}}}));
  Block wide = Block::fromSizes({{{1.0}, {0.001, 0.001, 400.0}, {1.0}}});
  h.addBlock(wide);
  h.blocks[0].redirections.push_back({1});
  h.blocks[0].cells[0] = Cell::redirect(0);
  auto image = compile(h);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find("block 1 axis y"), std::string::npos) << image.error().message;

  Hierarchy far = h;
  far.blocks[1] = Block::fromSizes({{{1.0}, {1.0}, {1.0}}});
  far.blocks[0].redirections[0].offsetM = {9000.0, 0, 0};
  image = compile(far);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find("block 0 redirection 0"), std::string::npos) << image.error().message;

  Hierarchy cyclic = far;
  cyclic.blocks[0].redirections[0].offsetM = {0, 0, 0};
  cyclic.blocks[1].redirections.push_back({0});
  image = compile(cyclic);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find("cycle"), std::string::npos) << image.error().message;
}

// Every rule a hierarchy built through the API must keep (checkHierarchy) and every limit of the
// format compile() enforces: each broken on its own in a valid two-block hierarchy, and refused
// with a message that names the place.
struct BrokenHierarchy {
  const char* name;
  void (*breakIt)(Hierarchy&);
  const char* message;
};

class HniCompileRefuses : public ::testing::TestWithParam<BrokenHierarchy> {};

// Block 0 (2 x 1 x 1 cells) holds a box of material 0 and a redirection to block 1 (one cell).
Hierarchy twoBlocks() {
  Hierarchy h;
  h.materials.push_back({200, 100, 50});
  h.addBlock(Block::fromSizes({{{1.0, 1.0}, {1.0}, {1.0}}}));
  h.addBlock(Block::fromSizes({{{1.0}, {1.0}, {1.0}}}));
  h.blocks[0].cells[0] = Cell::box(0);
  h.blocks[0].redirections.push_back({1});
  h.blocks[0].cells[1] = Cell::redirect(0);
  h.blocks[1].cells[0] = Cell::box(0);
  return h;
}

TEST(HniCompile, TheValidTwoBlockHierarchyCompiles) { EXPECT_TRUE(compile(twoBlocks()).ok()); }

TEST_P(HniCompileRefuses, NamingWhere) {
  Hierarchy h = twoBlocks();
  GetParam().breakIt(h);
  auto image = compile(h);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find(GetParam().message), std::string::npos) << image.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Rules, HniCompileRefuses,
    ::testing::Values(
        BrokenHierarchy{"NoBlocks", [](Hierarchy& h) { h.blocks.clear(); }, "hierarchy has no blocks"},
        BrokenHierarchy{"Root", [](Hierarchy& h) { h.root = 2; }, "root block 2 out of range (2 blocks)"},
        BrokenHierarchy{"NoCells", [](Hierarchy& h) { h.blocks[1].boundsM[2] = {0.0}; }, "block 1 axis z: no cells"},
        BrokenHierarchy{"FirstBoundary",
                        [](Hierarchy& h) {
                          h.blocks[1].boundsM[0] = {0.5, 1.0};
                        },
                        "block 1 axis x: first boundary must be 0"},
        BrokenHierarchy{"NotIncreasing",
                        [](Hierarchy& h) {
                          h.blocks[0].boundsM[0] = {0.0, 1.0, 1.0};
                        },
                        "block 0 axis x: boundary 2 is not finite and greater than the previous one"},
        BrokenHierarchy{"NotFinite",
                        [](Hierarchy& h) {
                          h.blocks[0].boundsM[1] = {0.0, std::nan("")};
                        },
                        "block 0 axis y: boundary 1 is not finite"},
        BrokenHierarchy{"CellCount", [](Hierarchy& h) { h.blocks[0].cells.pop_back(); },
                        "block 0: 1 cells, expected 2"},
        BrokenHierarchy{"Solid", [](Hierarchy& h) { h.blocks[1].cells[0].solid.index = kSolidCount; }, "solid 69"},
        BrokenHierarchy{"Material", [](Hierarchy& h) { h.blocks[1].cells[0].material = 1; },
                        "material 1 out of range (1 materials)"},
        BrokenHierarchy{"Texture", [](Hierarchy& h) { h.blocks[1].cells[0].texture = 1; },
                        "texture 1 out of range (0 textures)"},
        BrokenHierarchy{"Redirection", [](Hierarchy& h) { h.blocks[0].cells[1].redirection = 1; },
                        "redirection 1 out of range"},
        BrokenHierarchy{"Target", [](Hierarchy& h) { h.blocks[0].redirections[0].target = 5; },
                        "block 0 redirection 0: target block out of range"},
        BrokenHierarchy{"CubeRotation", [](Hierarchy& h) { h.blocks[0].redirections[0].rotation.cube = 24; },
                        "block 0 redirection 0: cube rotation out of range"},
        BrokenHierarchy{
            "OffsetNotFinite",
            [](Hierarchy& h) { h.blocks[0].redirections[0].offsetM.y = std::numeric_limits<double>::infinity(); },
            "block 0 redirection 0: offset is not finite"},
        BrokenHierarchy{"NarrowerThanAMillimetre",
                        [](Hierarchy& h) {
                          h.blocks[0].boundsM[0] = {0.0, 0.0004, 1.0};
                        },
                        "block 0 axis x: cell 0 is narrower than 1 mm"},
        BrokenHierarchy{"Longer",
                        [](Hierarchy& h) {
                          h.blocks[1].boundsM[2] = {0.0, 20000.0};
                        },
                        "block 1 axis z size: 20000.000000 m is outside the encodable range"},
        BrokenHierarchy{"DataComponent",
                        [](Hierarchy& h) {
                          std::vector<double> sizes(65, 0.01);
                          h.blocks[1] = Block::fromSizes({{sizes, {1.0}, sizes}});  // 65 x 65 = 4225 px wide
                        },
                        "block 1: data component 4225 px wide (n_x * n_z) exceeds 4096"},
        BrokenHierarchy{"Materials", [](Hierarchy& h) { h.materials.resize(65536); },
                        "65536 materials exceed the limit of 65535"},
        BrokenHierarchy{"TextureInfos", [](Hierarchy& h) { h.textures.resize(256); },
                        "256 texture infos exceed the limit of 255"},
        BrokenHierarchy{"TextureOffset",
                        [](Hierarchy& h) {
                          h.textures.push_back({{0.0, 0.0, -9000.0}, 1});
                        },
                        "texture info 0: offset -9000.000000 m is outside"}),
    [](const ::testing::TestParamInfo<BrokenHierarchy>& p) { return std::string(p.param.name); });

TEST(HniCompile, RootFileRecordAndMagic) {
  const Hierarchy h = testing::randomHierarchy(42);
  auto image = compile(h);
  ASSERT_TRUE(image.ok());
  const std::uint8_t* p = image->at(0, 0);
  EXPECT_EQ(p[0], 'N');
  EXPECT_EQ(p[1], 'U');
  EXPECT_EQ(p[2], 'T');
  EXPECT_EQ(p[3], format::kVersion);
  const HniView view(*image);
  EXPECT_EQ(view.fileRecord().root, view.blockAddress(view.fileRecord(), static_cast<int>(h.root)));
  EXPECT_LE(image->width, format::kMaxSearchWidth);
}

// pixelKinds (nut info --bytes, the waste figure) against what decode() and the header reader
// find: one data pixel per cell, 12 per header, 2 per material, 4 per distinct redirection
// record, both rows of every block's metadata items where the headers point.
TEST(HniStats, PixelKindsCountEveryRecordOnce) {
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    auto image = compile(testing::randomHierarchy(7000 + seed));
    ASSERT_TRUE(image.ok()) << image.error().message;
    const auto h = decode(*image);
    ASSERT_TRUE(h.ok()) << h.error().message;
    const std::vector<PixelKind> kinds = pixelKinds(*image);
    std::array<long long, kPixelKindCount> count{};
    for (PixelKind k : kinds) ++count[static_cast<std::size_t>(k)];
    const auto of = [&](PixelKind k) { return count[static_cast<std::size_t>(k)]; };
    long long cells = 0, records = 0;
    for (const Block& b : h->blocks) {
      cells += static_cast<long long>(b.cells.size());
      records += static_cast<long long>(b.redirections.size());
    }
    EXPECT_EQ(of(PixelKind::DataComponent), cells) << "seed " << seed;
    EXPECT_EQ(of(PixelKind::Header), format::kHeaderPixels * static_cast<long long>(h->blocks.size())) << "seed " << seed;
    EXPECT_EQ(of(PixelKind::Material), format::kMaterialPixels * static_cast<long long>(h->materials.size())) << "seed " << seed;
    // decode() gives each block its own records; the file stores equal ones once.
    EXPECT_LE(of(PixelKind::RedirectionRecord), format::kRedirectionPixels * records) << "seed " << seed;
    EXPECT_EQ(of(PixelKind::RedirectionRecord) % format::kRedirectionPixels, 0) << "seed " << seed;
    EXPECT_EQ(of(PixelKind::FileRecord), format::kFileRecordPixels);
    EXPECT_EQ(of(PixelKind::MetadataRow), of(PixelKind::ExactRow)) << "seed " << seed;
    const HniView view(*image);
    const FileRecord file = view.fileRecord();
    for (int b = 0; b < file.blockCount; ++b) {
      const BlockHeader header = view.header(view.blockAddress(file, b));
      for (int a = 0; a < 3; ++a) {
        const TexelAddress m = header.meta[static_cast<std::size_t>(a)];
        const auto at = [&](int u, int v) { return kinds[static_cast<std::size_t>(v) * static_cast<std::size_t>(image->width) + static_cast<std::size_t>(u)]; };
        EXPECT_EQ(at(m.u, m.v), PixelKind::MetadataRow);
        EXPECT_EQ(at(m.u + header.metaPixels[a] - 1, m.v + 1), PixelKind::ExactRow);
      }
    }
    EXPECT_EQ(computeStats(*image).usedPixels, static_cast<long long>(kinds.size()) - of(PixelKind::Unused));
  }
}

}  // namespace
}  // namespace nut
