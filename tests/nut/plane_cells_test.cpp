// Plane cells (format version 3): the plane encoding against its stated precision, the ray span
// against a brute-force walk along the ray, the records through compile, validate and decode,
// hostile records, visual summaries, and `nut info`'s counts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include <glm/geometric.hpp>

#include <nut/format.hpp>
#include <nut/hni.hpp>
#include <nut/hni_view.hpp>
#include <nut/plane_cells.hpp>
#include <nut/summary.hpp>

#include "../expect_rejected.hpp"
#include "../plane_roofs.hpp"
#include "../random_hierarchy.hpp"

namespace nut {
namespace {

glm::dvec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
}

TEST(PlaneEncoding, AxisNormalsAreExact) {
  for (int a = 0; a < 3; ++a)
    for (const double sign : {1.0, -1.0}) {
      glm::dvec3 n(0.0);
      n[a] = sign;
      const CutPlane q = quantizedPlane({n, 12.345});
      EXPECT_EQ(q.normal, n);
      EXPECT_NEAR(q.offsetM, 12.345, 1e-12);  // 790,080 steps of 1/64 mm
    }
}

// The stated precision: the normal within 3e-7 rad (so a face moves by at most 0.15 mm at 500 m),
// the offset within half a step, 1/128 mm.
TEST(PlaneEncoding, NormalsAndOffsetsWithinTheirStep) {
  std::mt19937_64 rng(3);
  double worstAngle = 0, worstOffset = 0;
  for (int i = 0; i < 200000; ++i) {
    CutPlane p{randomUnit(rng), std::uniform_real_distribution<double>(-30000, 30000)(rng)};
    if (i % 4 == 0) p.normal = glm::normalize(p.normal * glm::dvec3(1e-6, 1.0, 1e-3));  // near an axis
    const CutPlane q = quantizedPlane(p);
    EXPECT_NEAR(glm::length(q.normal), 1.0, 1e-15);
    worstAngle = std::max(worstAngle, std::acos(std::min(1.0, glm::dot(p.normal, q.normal))));
    worstOffset = std::max(worstOffset, std::abs(p.offsetM - q.offsetM));
  }
  EXPECT_LT(worstAngle, 3e-7);
  EXPECT_LE(worstOffset, 0.001 / 128 + 1e-12);
  std::printf("worst normal error %.3g rad, worst offset error %.3g m\n", worstAngle, worstOffset);
}

TEST(PlaneEncoding, FloatDecodingMatchesDouble) {
  std::mt19937_64 rng(4);
  for (int i = 0; i < 100000; ++i) {
    const auto e = encodePlane({randomUnit(rng), 1.0});
    ASSERT_TRUE(e);
    const glm::dvec3 exact = decodePlane(*e).normal;
    const glm::vec3 f = decodeNormalFloat(e->octX, e->octY);
    ASSERT_LT(glm::length(glm::dvec3(f) - exact), 4e-7) << i;
  }
}

TEST(PlaneEncoding, EveryCodeDecodesToAUnitNormal) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<std::uint32_t> code(1, format::kOctahedralMax);
  for (int i = 0; i < 100000; ++i) {
    const CutPlane p = decodePlane({code(rng), code(rng), 0});
    ASSERT_NEAR(glm::length(p.normal), 1.0, 1e-12);
  }
  for (const std::uint32_t x : {1u, format::kOctahedralCentre, format::kOctahedralMax})
    for (const std::uint32_t y : {1u, format::kOctahedralCentre, format::kOctahedralMax})
      EXPECT_NEAR(glm::length(decodePlane({x, y, 0}).normal), 1.0, 1e-12);
}

TEST(PlaneEncoding, OffsetsBeyondTheRangeAndNonFinitePlanesAreRefused) {
  EXPECT_TRUE(encodePlane({{0, 1, 0}, 33000.0}));
  EXPECT_FALSE(encodePlane({{0, 1, 0}, 34000.0}));
  EXPECT_FALSE(encodePlane({{0, 1, 0}, -34000.0}));
  EXPECT_FALSE(encodePlane({{0, 0, 0}, 1.0}));
  EXPECT_FALSE(encodePlane({{std::nan(""), 1, 0}, 1.0}));
  EXPECT_FALSE(encodePlane({{0, 1, 0}, std::numeric_limits<double>::infinity()}));
}

// The span against a walk along the ray in small steps with the half-space test itself.
TEST(PlaneSpan, MatchesAWalkAlongTheRay) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 20000; ++i) {
    const auto combine = static_cast<PlaneCombine>(1 + i % 3);
    std::array<glm::dvec3, 2> normals{randomUnit(rng), randomUnit(rng)};
    std::array<double, 2> offsets{};
    for (std::size_t p = 0; p < 2; ++p) offsets[p] = glm::dot(normals[p], glm::dvec3(unit(rng), unit(rng), unit(rng)));
    const glm::dvec3 origin(unit(rng), unit(rng), unit(rng));
    const glm::dvec3 dir = randomUnit(rng);
    const auto inside = [&](double t) {
      const glm::dvec3 x = origin + t * dir;
      const bool a = glm::dot(normals[0], x) <= offsets[0], b = glm::dot(normals[1], x) <= offsets[1];
      return combine == PlaneCombine::One ? a : combine == PlaneCombine::Both ? a && b : a || b;
    };
    const double tEnter = 0.0, tExit = 1.0;
    constexpr int kSteps = 4000;
    int first = -1, last = -1;
    for (int k = 0; k <= kSteps; ++k)
      if (inside(tExit * k / kSteps)) {
        if (first < 0) first = k;
        last = k;
      }
    const auto span = intersectPlaneCut<double>(normals, offsets, combine, origin, dir, tEnter, tExit);
    constexpr double kStep = 1.0 / kSteps;
    if (first < 0) {
      // Nothing sampled inside: at most a sliver between two samples.
      if (span) {
        EXPECT_LT(span->tOut - span->tIn, kStep) << i;
      }
      continue;
    }
    ASSERT_TRUE(span) << i;
    EXPECT_NEAR(span->tIn, first * kStep, kStep) << i;
    EXPECT_NEAR(span->tOut, last * kStep, kStep) << i;
    if (span->plane >= 0) {
      const auto p = static_cast<std::size_t>(span->plane);
      EXPECT_NEAR(glm::dot(normals[p], origin + span->tIn * dir), offsets[p], 1e-12) << i;
    } else {
      EXPECT_EQ(span->tIn, tEnter) << i;
    }
  }
}

TEST(PlaneCells, RoofHouseRoundTripsAsVersion3) {
  for (const PlaneCombine combine : {PlaneCombine::Both, PlaneCombine::Either}) {
    const testing::PlaneRoof roof = testing::planeRoofHouse(combine);
    auto image = compile(roof.h);
    ASSERT_TRUE(image.ok()) << image.error().message;
    EXPECT_EQ(image->at(0, 0)[3], format::kVersionPlanes);
    ASSERT_TRUE(validate(*image).ok()) << validate(*image).error().message;
    auto decoded = decode(*image);
    ASSERT_TRUE(decoded.ok());
    Hierarchy expected = quantized(roof.h);
    for (std::size_t b = 0; b < expected.blocks.size(); ++b) expected.blocks[b].summary = decoded->blocks[b].summary;
    EXPECT_EQ(*decoded, expected);
    const HniStats s = computeStats(*image);
    long long planeCells = 0;
    for (const Cell& c : roof.h.blocks[0].cells) planeCells += c.kind == CellKind::Plane;
    EXPECT_GT(planeCells, 10);
    EXPECT_EQ(s.planeCells, planeCells);
    // One record serves every plane cell: same cut, material and texture.
    const std::vector<PixelKind> kinds = pixelKinds(*image);
    EXPECT_EQ(std::count(kinds.begin(), kinds.end(), PixelKind::PlaneRecord),
              format::kPlaneRecordHeadPixels + 2 * format::kPixelsPerPlane);
  }
}

TEST(PlaneCells, RandomHierarchiesWithPlaneCellsRoundTrip) {
  testing::RandomHierarchyOptions options;
  options.planeCellShare = 0.5;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const Hierarchy h = testing::randomHierarchy(seed, options);
    auto image = compile(h);
    ASSERT_TRUE(image.ok()) << seed << ": " << image.error().message;
    auto decoded = decode(*image);
    ASSERT_TRUE(decoded.ok()) << seed;
    Hierarchy expected = quantized(h);
    for (std::size_t b = 0; b < expected.blocks.size(); ++b) expected.blocks[b].summary = decoded->blocks[b].summary;
    ASSERT_EQ(*decoded, expected) << seed;
    // quantized() is idempotent: what decode returns is what the format keeps.
    Hierarchy again = quantized(*decoded);
    for (std::size_t b = 0; b < again.blocks.size(); ++b) again.blocks[b].summary = decoded->blocks[b].summary;
    ASSERT_EQ(again, *decoded) << seed;
  }
}

TEST(PlaneCells, FileWithoutPlaneCellsStaysVersion1) {
  auto image = compile(testing::randomHierarchy(11));
  ASSERT_TRUE(image.ok());
  EXPECT_EQ(image->at(0, 0)[3], format::kVersion);
}

TEST(PlaneCells, ModelErrorsNameTheCell) {
  testing::PlaneRoof roof = testing::planeRoofHouse(PlaneCombine::Both);
  Hierarchy h = roof.h;
  h.blocks[0].cuts.clear();
  auto image = compile(h);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find("plane cut 0 out of range"), std::string::npos) << image.error().message;
  h = roof.h;
  h.blocks[0].cuts[0].planes[1].normal = {0, 2, 0};
  image = compile(h);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find("block 0 plane cut 0 plane 1"), std::string::npos) << image.error().message;
  h = roof.h;
  h.blocks[0].cuts[0].planes[0].offsetM = 40000;
  image = compile(h);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find("33.5 km"), std::string::npos) << image.error().message;
  h = roof.h;
  h.blocks[0].cuts[0].surfaceMaterials[1] = 3;
  image = compile(h);
  ASSERT_FALSE(image.ok());
  EXPECT_NE(image.error().message.find("block 0 plane cut 0 plane 1: surface material 3 out of range"),
            std::string::npos)
      << image.error().message;
}

// Hostile plane records: each rule of docs/FORMAT.md ("Plane cell record") broken on purpose.
struct PlaneRecordFixture : ::testing::Test {
  void SetUp() override {
    auto compiled = compile(testing::planeRoofHouse(PlaneCombine::Both).h);
    ASSERT_TRUE(compiled.ok());
    image = *compiled;
    const HniView view(image);
    const BlockHeader header = view.header(view.blockAddress(view.fileRecord(), 0));
    for (int z = 0; z < header.cells.z && !cell; ++z)
      for (int y = 0; y < header.cells.y && !cell; ++y)
        for (int x = 0; x < header.cells.x && !cell; ++x)
          if (view.cell(header, {x, y, z}).g == format::kCellPlane) {
            cell = image.at(header.data.u + x + z * header.cells.x, header.data.v + header.cells.y - 1 - y);
            record = view.cell(header, {x, y, z}).planeRecord;
          }
    ASSERT_TRUE(cell);
  }
  std::uint8_t* recordPixel(int i) { return image.at(record.u + i, record.v); }
  void expectRejected(const std::string& needle) const { testing::expectRejected(image, needle); }
  Image image;
  std::uint8_t* cell = nullptr;
  TexelAddress record;
};

TEST_F(PlaneRecordFixture, PlaneCellInAnOlderVersion) {
  image.at(0, 0)[3] = format::kVersionLod;
  expectRejected("plane cells need version 3");
}

TEST_F(PlaneRecordFixture, CombinationOutOfRange) {
  recordPixel(0)[3] = 0;
  expectRejected("combination 0 is not 1, 2 or 3");
  recordPixel(0)[3] = 4;
  expectRejected("combination 4 is not 1, 2 or 3");
}

TEST_F(PlaneRecordFixture, MaterialAndTextureOutOfRange) {
  recordPixel(0)[0] = 3;
  expectRejected("material 3 out of range");
  recordPixel(0)[0] = 0;
  recordPixel(0)[2] = 1;
  expectRejected("texture 1 out of range");
}

TEST_F(PlaneRecordFixture, SurfaceMaterialsAndZeroCodes) {
  recordPixel(2)[3] = 1;  // the high byte of plane 0's surface material code, whose low byte is 3
  expectRejected("plane 0: surface material 258 out of range");
  recordPixel(2)[3] = 0;
  recordPixel(4)[3] = 4;  // plane 1's code 4: material 3, and the house has three
  expectRejected("plane 1: surface material 3 out of range");
  recordPixel(4)[3] = 3;  // material 2: plane 1's surface shows it
  ASSERT_TRUE(validate(image).ok());
  const auto decoded = decode(image);
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(decoded->blocks[0].cuts[0].surfaceMaterials[1], std::optional<std::uint16_t>(2));
  recordPixel(4)[3] = 0;
  recordPixel(4)[0] = recordPixel(4)[1] = recordPixel(4)[2] = 0;
  expectRejected("octahedral coordinate 0");
}

TEST_F(PlaneRecordFixture, RecordOutsideTheImage) {
  // Two free columns on the right (addresses do not depend on the width): a head in the last one
  // whose two planes run past the edge.
  Image wider(image.width + 2, image.height);
  for (int v = 0; v < image.height; ++v) std::copy(image.at(0, v), image.at(0, v) + 4 * image.width, wider.at(0, v));
  const auto last = static_cast<std::uint32_t>(wider.width - 1);
  const std::ptrdiff_t cellOffset = cell - image.pixels.data();
  const int cellU = static_cast<int>(cellOffset / 4 % image.width),
            cellV = static_cast<int>(cellOffset / 4 / image.width);
  std::uint8_t* widerCell = wider.at(cellU, cellV);
  widerCell[0] = static_cast<std::uint8_t>(last), widerCell[1] = static_cast<std::uint8_t>(last >> 8 & 0xf);
  widerCell[2] = 0;
  wider.at(wider.width - 1, 0)[3] = 2;
  image = wider;
  expectRejected("do not fit in the image");
  image.at(cellU, cellV)[0] = image.at(cellU, cellV)[1] = image.at(cellU, cellV)[2] = 0xff;
  expectRejected("is outside the image");
}

// The summary of a single cell cut by the plane x + y <= 1 (unit cube): full from +x, +y, -x and
// -y (every column meets the solid), half from +z and -z. The summaries sample 24 x 24 rays, so
// the half is 300 / 576 of the side.
TEST(PlaneCells, VisualSummaryCoversWhatTheCutShows) {
  Hierarchy h;
  h.materials = {{100, 150, 200, 255, 0}};
  Block b = Block::fromSizes({{{1.0}, {1.0}, {1.0}}});
  b.cuts.push_back({{CutPlane{glm::normalize(glm::dvec3(1, 1, 0)), std::sqrt(0.5)}, CutPlane{}}, PlaneCombine::One});
  b.cell(0, 0, 0) = Cell::planeCell(0, 0);
  h.addBlock(b);
  const VisualSummary s = computeSummaries(h)[0];
  for (int side = 0; side < 4; ++side) EXPECT_EQ(s[static_cast<std::size_t>(side)].a, 255) << side;
  for (int side = 4; side < 6; ++side) EXPECT_EQ(s[static_cast<std::size_t>(side)].a, std::lround(255.0 * 300 / 576));
  EXPECT_EQ(s[0].r, 100);
  EXPECT_EQ(s[0].b, 200);
}

}  // namespace
}  // namespace nut
