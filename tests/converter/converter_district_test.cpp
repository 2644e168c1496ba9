// Stretched hierarchies (converter/scale_hierarchy.hpp) and districts of buildings
// (converter/district.hpp), checked by looking points up through the redirections as
// docs/FORMAT.md defines them (tests/redirected_point.hpp), independently of the code under test:
// a stretched point must show what the point showed, and a district's point what the building
// placed there shows at that place.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <converter/district.hpp>
#include <converter/scale_hierarchy.hpp>
#include <nut/hni.hpp>

#include "random_hierarchy.hpp"
#include "redirected_point.hpp"

namespace nut::converter {
namespace {

using testing::contentAt;

struct Comparison {
  int mismatches = 0, solid = 0;
};

// Random hierarchies without texture infos (which a stretch refuses), with plane cells when asked.
Hierarchy untexturedHierarchy(std::uint64_t seed, double planeCellShare = 0.0) {
  testing::RandomHierarchyOptions options;
  options.planeCellShare = planeCellShare;
  Hierarchy h = testing::randomHierarchy(seed, options);
  h.textures.clear();
  for (Block& b : h.blocks)
    for (Cell& c : b.cells) c.texture = 0;
  return h;
}

Comparison compareStretched(const Hierarchy& h, const Hierarchy& scaled, const glm::dvec3& factors, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Comparison out;
  const glm::dvec3 size = h.blocks[h.root].sizeM();
  for (int i = 0; i < 20000; ++i) {
    const glm::dvec3 p = glm::dvec3(unit(rng), unit(rng), unit(rng)) * size;
    const int expected = contentAt(h, h.root, p);
    out.mismatches += contentAt(scaled, scaled.root, p * factors) != expected;
    out.solid += expected >= 0;
  }
  return out;
}

TEST(ScaleHierarchy, AStretchedPointShowsWhatThePointShowed) {
  int stretchedApart = 0, refused = 0;
  for (std::uint64_t seed = 1; seed <= 60; ++seed) {
    const Hierarchy h = untexturedHierarchy(seed, seed > 30 ? 0.5 : 0.0);  // plane cells from seed 31
    for (const glm::dvec3 factors : {glm::dvec3(1.37), glm::dvec3(0.8, 1.6, 0.8), glm::dvec3(1.25, 0.7, 1.1)}) {
      auto scaled = scaleHierarchy(h, factors);
      if (!scaled) {
        // Only a yaw under a block stretched differently along its x and z may refuse.
        EXPECT_NE(factors.x, factors.y) << scaled.error().message;
        EXPECT_NE(scaled.error().message.find("yaw"), std::string::npos) << scaled.error().message;
        ++refused;
        continue;
      }
      ASSERT_TRUE(checkHierarchy(*scaled)) << "seed " << seed;
      const Comparison c = compareStretched(h, *scaled, factors, static_cast<std::uint32_t>(seed));
      EXPECT_EQ(c.mismatches, 0) << "seed " << seed << ", factors " << factors.x << " " << factors.y << " " << factors.z;
      stretchedApart += factors.x != factors.y && c.solid > 0;
    }
  }
  // The non-uniform stretches did run, through rotated blocks, and only a minority of the 120
  // was refused for a yaw.
  EXPECT_GT(stretchedApart, 40);
  EXPECT_LT(refused, 60 * 2 * 2 / 3);
}

TEST(ScaleHierarchy, ABlockUnderTwoStretchesIsStoredOnceForEach) {
  // The root redirects twice to one target: once as it is, once turned so that its x lies along
  // the root's y. Stretching the root's y alone stretches the two uses along different axes.
  Hierarchy h;
  Block target = Block::fromSizes({{{1.0, 2.0}, {1.0}, {1.0}}});
  target.cells[0] = Cell::box(0);
  const BlockId t = h.addBlock(target);
  Block root = Block::fromSizes({{{3.0, 3.0}, {3.0}, {3.0}}});
  root.redirections = {Redirection{t, glm::dvec3(0.0), Rotation{}, {}},
                       Redirection{t, glm::dvec3(0.0, 0.0, 1.0), Rotation{16, 0}, {}}};
  root.cells = {Cell::redirect(0), Cell::redirect(1)};
  h.root = h.addBlock(root);
  h.addMaterial(Material{});
  const glm::dvec3 factors(1.0, 2.0, 1.0);
  auto scaled = scaleHierarchy(h, factors);
  ASSERT_TRUE(scaled) << scaled.error().message;
  EXPECT_EQ(scaled->blocks.size(), 3u);
  EXPECT_EQ(compareStretched(h, *scaled, factors, 5).mismatches, 0);
}

TEST(ScaleHierarchy, RefusesWhatItCannotStretch) {
  Hierarchy h = untexturedHierarchy(3);
  EXPECT_FALSE(scaleHierarchy(h, glm::dvec3(1.0, 0.0, 1.0)));
  EXPECT_FALSE(scaleHierarchy(h, glm::dvec3(1.0, NAN, 1.0)));
  h.textures.push_back(TextureInfo{});
  const auto textured = scaleHierarchy(h, glm::dvec3(2.0));
  ASSERT_FALSE(textured);
  EXPECT_NE(textured.error().message.find("texture"), std::string::npos);
}

// Buildings of a district as a manifest places them (docs/CITY.md).
struct Placement {
  Hierarchy hierarchy;
  glm::dvec3 positionM;
  double yawDeg;
};

std::vector<PlacedHierarchy> placed(const std::vector<Placement>& buildings) {
  std::vector<PlacedHierarchy> out;
  for (const Placement& b : buildings) out.push_back({&b.hierarchy, b.positionM, b.yawDeg});
  return out;
}

TEST(District, AWorldPointShowsWhatTheBuildingPlacedThereShows) {
  std::vector<Placement> buildings;
  const std::array<double, 5> yaws{0.0, 180.0, 90.0, 270.0, 45.0};
  for (std::size_t i = 0; i < yaws.size(); ++i) {
    testing::RandomHierarchyOptions options;
    options.maxCellM = 1.0;  // roots of a few metres, 40 m apart
    Hierarchy h = quantized(testing::randomHierarchy(100 + i, options));
    buildings.push_back({std::move(h), glm::dvec3(40.0 * static_cast<double>(i) + 1000.25, 3.5, -20.125 * static_cast<double>(i % 2)), yaws[i]});
  }
  auto district = mergeDistrict(placed(buildings));
  ASSERT_TRUE(district) << district.error().message;
  ASSERT_TRUE(checkHierarchy(district->hierarchy));
  const Hierarchy& d = district->hierarchy;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Which building a point lies in is told by the materials: each building's are renumbered in
  // the district, so compare the materials themselves.
  int mismatches = 0, solid = 0;
  for (std::size_t i = 0; i < buildings.size(); ++i) {
    const Placement& b = buildings[i];
    const WorldBox box = placedRootBox(b.hierarchy, b.positionM, b.yawDeg);
    for (int n = 0; n < 4000; ++n) {
      const glm::dvec3 p = box.min + glm::dvec3(unit(rng), unit(rng), unit(rng)) * box.size();
      const glm::dmat3 turn(glm::rotate(glm::dmat4(1.0), glm::radians(b.yawDeg), glm::dvec3(0, 1, 0)));
      const int expected = contentAt(b.hierarchy, b.hierarchy.root, glm::transpose(turn) * (p - b.positionM));
      const int actual = contentAt(d, d.root, p - district->originM);
      const bool same = expected < 0 ? actual < 0 : actual >= 0 && d.materials[static_cast<std::size_t>(actual)] == b.hierarchy.materials[static_cast<std::size_t>(expected)];
      mismatches += !same;
      solid += expected >= 0;
    }
  }
  EXPECT_LE(mismatches, 2);  // a point within rounding of a turned solid's face may go either way
  EXPECT_GT(solid, 2000);
  // Between the buildings the district is empty.
  EXPECT_LT(contentAt(d, d.root, glm::dvec3(20.0, 1.0, 1.0) + buildings[0].positionM - district->originM), 0);
  // It compiles to a valid HNI.
  auto image = compile(d);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_TRUE(validate(*image));
}

TEST(District, EqualBlocksOfTwoBuildingsAreStoredOnce) {
  const Hierarchy h = quantized(testing::randomHierarchy(7));
  std::vector<Placement> buildings{{h, glm::dvec3(0.0), 0.0}, {h, glm::dvec3(100.0, 0.0, 0.0), 180.0}};
  auto district = mergeDistrict(placed(buildings));
  ASSERT_TRUE(district) << district.error().message;
  // Every block of the second building equals one of the first's.
  EXPECT_EQ(district->buildingBlocks % 2, 0u);
  EXPECT_GE(district->mergedBlocks, district->buildingBlocks / 2);
  EXPECT_EQ(district->hierarchy.blocks.size(), district->buildingBlocks - district->mergedBlocks + 1);
  EXPECT_EQ(district->hierarchy.materials.size(), h.materials.size());
}

TEST(District, RefusesOverlappingBuildingsAndNamesThem) {
  const Hierarchy h = quantized(testing::randomHierarchy(7));
  std::vector<Placement> buildings{{h, glm::dvec3(0.0), 0.0}, {h, glm::dvec3(500.0, 0.0, 0.0), 0.0}, {h, glm::dvec3(0.001, 5.0, 0.0), 0.0}};
  auto district = mergeDistrict(placed(buildings));
  ASSERT_FALSE(district);
  EXPECT_EQ(district.error().message, "building 2 overlaps building 0 on the ground");
  EXPECT_FALSE(mergeDistrict({}));
}

}  // namespace
}  // namespace nut::converter
