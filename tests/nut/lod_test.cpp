// Level of detail from measured error (nut/lod.hpp) on blocks whose footprints follow by hand
// from their pictures, and the caster's --lod auto: summaries exactly where a pixel spans more
// than the footprint, full detail elsewhere and in files without footprints.
#include <gtest/gtest.h>

#include <nut/camera.hpp>
#include <nut/hni.hpp>
#include <nut/lod.hpp>
#include <nut/raycast.hpp>

namespace nut {
namespace {

constexpr double kSide = 8.0;  // metres; every test block is 8 x 8 x 1
const Material kDark{20, 20, 20}, kLight{230, 230, 230};

// A root of one cell redirecting to `block` (block 1).
Hierarchy underRoot(const Block& block, std::vector<Material> materials) {
  Hierarchy h;
  h.materials = std::move(materials);
  Block root = Block::fromSizes({{{kSide}, {kSide}, {1.0}}});
  root.redirections.push_back({1});
  root.cell(0, 0, 0) = Cell::redirect(0);
  h.addBlock(root);
  h.addBlock(block);
  return h;
}

// 8 x 8 cells of 1 m, dark and light alternating in x and y; every cell a full box.
Hierarchy checkerboard() {
  Block b = Block::fromSizes({{std::vector<double>(8, 1.0), std::vector<double>(8, 1.0), {1.0}}});
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) b.cell(x, y, 0) = Cell::box(static_cast<std::uint16_t>((x + y) % 2));
  return underRoot(b, {kDark, kLight});
}

double measuredFootprint(Hierarchy h) {
  auto image = compile(h);
  EXPECT_TRUE(image) << image.error().message;
  measureLevelOfDetail(h, *image);
  EXPECT_EQ(h.blocks[0].lodFootprintM, 0.0) << "the root has no record to carry a footprint";
  return h.blocks[1].lodFootprintM;
}

TEST(LevelOfDetail, AFlatBlockPassesEveryLevel) {
  Block b = Block::fromSizes({{{kSide}, {kSide}, {1.0}}});
  b.cell(0, 0, 0) = Cell::box(0);
  // One colour on every side: the summary matches down to the finest level, 32 pixels across.
  EXPECT_DOUBLE_EQ(measuredFootprint(underRoot(b, {kDark})), kSide / LodMeasureOptions{}.finestPixels);
}

TEST(LevelOfDetail, ACheckerboardPassesWhileAPixelCoversTwoCells) {
  // A pixel of 2 x 2 cells averages two dark and two light to the summary's grey; a pixel of one
  // cell is dark or light against grey. So 4 pixels across pass and 8 fail: 8 m / 4.
  EXPECT_DOUBLE_EQ(measuredFootprint(checkerboard()), 2.0);
}

TEST(LevelOfDetail, AHalfEmptyBlockIsNeverSummarised) {
  // Box in x < 4 only. Seen obliquely through the +x side, rays leave the 1 m thick block before
  // they reach the box: background where the +x summary says dark, over an eighth of a pixel
  // already at one pixel across.
  Block b = Block::fromSizes({{{4.0, 4.0}, {kSide}, {1.0}}});
  b.cell(0, 0, 0) = Cell::box(0);
  EXPECT_EQ(measuredFootprint(underRoot(b, {kDark})), 0.0);
}

TEST(LevelOfDetail, AStricterToleranceNeverGivesAFinerFootprint) {
  Hierarchy h = checkerboard();
  auto image = compile(h);
  ASSERT_TRUE(image);
  double previous = 0;
  for (int tolerance : {255, 64, 8, 1}) {
    measureLevelOfDetail(h, *image, {tolerance, 4, 32});
    if (previous > 0) {
      EXPECT_GE(h.blocks[1].lodFootprintM, previous) << "tolerance " << tolerance;
    }
    previous = h.blocks[1].lodFootprintM;
  }
  EXPECT_DOUBLE_EQ(previous, 2.0) << "even one level of difference fails a pixel of one cell";
}

// --lod auto in the caster, head-on at the +z side of the checkerboard with a 2 m footprint.
struct AutoLod : ::testing::Test {
  void SetUp() override {
    Hierarchy h = checkerboard();
    plain = *compile(h);
    h.blocks[1].lodFootprintM = 2.0;
    withFootprint = *compile(h);
  }
  static Camera headOn(double distanceM) {
    Camera c;
    c.width = c.height = 64;
    c.fovYDeg = 40.0;
    c.target = glm::dvec3(kSide / 2, kSide / 2, 1.0);
    c.eye = c.target + glm::dvec3(0.0, 0.0, distanceM);
    c.nearM = 0.1;
    c.farM = 2 * distanceM;
    return c;
  }
  static Image render(const Image& image, const Camera& camera, bool lodAuto) {
    const HniRayCaster caster(image, glm::dvec3(0.0));
    RayCastOptions options;
    options.lookup = Lookup::Exact;
    options.lodAuto = lodAuto;
    return renderHni(caster, camera, options, 1).colour;
  }
  Image plain, withFootprint;
};

TEST_F(AutoLod, TheFootprintMakesAVersion2File) {
  EXPECT_EQ(plain.at(0, 0)[3], 1);
  EXPECT_EQ(withFootprint.at(0, 0)[3], 2);
}

TEST_F(AutoLod, FarAwayThePixelsOfTheBlockAreItsSummary) {
  // 0.011 rad per pixel: at 300 m a pixel spans 3.4 m, more than 2 m.
  const Camera camera = headOn(300.0);
  const Image image = render(withFootprint, camera, true);
  const auto grey = shade({125, 125, 125}, {0, 0, 1}, {0, 0, -1});  // (20 + 230) / 2
  int block = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      if (p[0] == kBackground[0] && p[1] == kBackground[1] && p[2] == kBackground[2]) continue;
      ++block;
      EXPECT_EQ(p[0], grey[0]) << x << "," << y;
    }
  EXPECT_GT(block, 0);
  EXPECT_NE(render(withFootprint, camera, false).pixels, image.pixels) << "full detail shows the squares";
}

TEST_F(AutoLod, NearerTheBlockIsDrawnInFull) {
  const Camera camera = headOn(100.0);  // a pixel spans 1.1 m, less than 2 m
  EXPECT_EQ(render(withFootprint, camera, true).pixels, render(withFootprint, camera, false).pixels);
}

TEST_F(AutoLod, AFileWithoutFootprintsIsDrawnInFull) {
  const Camera camera = headOn(300.0);
  EXPECT_EQ(render(plain, camera, true).pixels, render(plain, camera, false).pixels);
}

}  // namespace
}  // namespace nut
