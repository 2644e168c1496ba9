// Stretched hierarchies (converter/scale_hierarchy.hpp) and districts of buildings
// (converter/district.hpp), checked by looking points up through the redirections as
// docs/FORMAT.md defines them (tests/redirected_point.hpp), independently of the code under test:
// a stretched point must show what the point showed, and a district's point what the building
// placed there shows at that place.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include <converter/district.hpp>
#include <converter/scale_hierarchy.hpp>
#include <nut/hni.hpp>
#include <nut/raycast.hpp>

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

// A building whose root is only a frame (one cell redirecting, turned a quarter, to its grid, as
// a converted building turned about the vertical is stored) is redirected to straight: the frame
// is not stored, and every point shows what the framed building shows there.
TEST(District, AFrameRootIsNotStored) {
  testing::RandomHierarchyOptions options;
  options.maxCellM = 1.0;
  const Hierarchy grid = quantized(testing::randomHierarchy(61, options));
  const glm::dvec3 size = grid.blocks[grid.root].sizeM();
  // A quarter turn about +y takes x to -z and z to x: the grid's box spans x in [0, size.z] and
  // z in [-size.x, 0], moved by size.x along z into the frame.
  Hierarchy framed = grid;
  Block frame;
  frame.boundsM = {std::vector<double>{0.0, size.z}, {0.0, size.y}, {0.0, size.x}};
  frame.cells = {Cell::redirect(0)};
  frame.redirections = {Redirection{grid.root, glm::dvec3(0.0, 0.0, size.x), Rotation{20, 0}, {false, false, false}}};
  framed.root = framed.addBlock(std::move(frame));
  const std::vector<Placement> buildings{{framed, glm::dvec3(3.25, 0.0, -7.5), 0.0},
                                         {grid, glm::dvec3(40.0, 0.0, 0.0), 0.0}};
  auto district = mergeDistrict(placed(buildings));
  ASSERT_TRUE(district) << district.error().message;
  auto alone = mergeDistrict(placed({buildings[1]}));
  ASSERT_TRUE(alone) << alone.error().message;
  // The framed building brought its grid's blocks, not its frame.
  EXPECT_EQ(district->buildingBlocks, 2 * alone->buildingBlocks);
  const Hierarchy& d = district->hierarchy;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int mismatches = 0, solid = 0;
  const WorldBox box = placedRootBox(framed, buildings[0].positionM, 0.0);
  for (int n = 0; n < 4000; ++n) {
    const glm::dvec3 p = box.min + glm::dvec3(unit(rng), unit(rng), unit(rng)) * box.size();
    const int expected = contentAt(framed, framed.root, p - buildings[0].positionM);
    const int actual = contentAt(d, d.root, p - district->originM);
    mismatches += expected < 0 ? actual >= 0
                               : actual < 0 || d.materials[static_cast<std::size_t>(actual)] !=
                                                   framed.materials[static_cast<std::size_t>(expected)];
    solid += expected >= 0;
  }
  EXPECT_LE(mismatches, 2);
  EXPECT_GT(solid, 1000);
  auto image = compile(d);
  ASSERT_TRUE(image) << image.error().message;
  EXPECT_TRUE(validate(*image));
}

// Plane surfaces keep their materials in a district: rays at each building show the same colours
// through the district's HNI as through the building's own (the second building's materials are
// renumbered, its planes' surface materials with its cells'; translucent ones are composited as
// through the building alone, since each building is one cell of the root tree). The exact
// lookup: the heuristic one moves the root's boundaries by up to D / (512 M).
TEST(District, PlaneSurfacesKeepTheirMaterials) {
  std::vector<Placement> buildings;
  for (std::size_t i = 0; i < 2; ++i) {
    testing::RandomHierarchyOptions options;
    options.planeCellShare = 0.5;
    options.maxCellM = 2.0;
    buildings.push_back({quantized(testing::randomHierarchy(40 + i, options)),
                         glm::dvec3(100.0 * static_cast<double>(i), 0.0, 0.0), 0.0});
  }
  auto parts = compileDistrict(placed(buildings), {0, 1});
  ASSERT_TRUE(parts) << parts.error().message;
  ASSERT_EQ(parts->size(), 1u);
  const HniRayCaster district(parts->front().image, parts->front().district.originM);
  RayCastOptions exact;
  exact.lookup = Lookup::Exact;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int hits = 0, differing = 0, planeSurfaces = 0;
  for (const Placement& b : buildings) {
    for (const Block& block : b.hierarchy.blocks)
      for (const PlaneCut& cut : block.cuts)
        planeSurfaces += cut.surfaceMaterials[0].has_value() + cut.surfaceMaterials[1].has_value();
    auto image = compile(b.hierarchy);
    ASSERT_TRUE(image) << image.error().message;
    const HniRayCaster alone(*image, b.positionM);
    const WorldBox box = alone.bounds();
    const double radius = glm::length(box.size());
    for (int n = 0; n < 4000; ++n) {
      const glm::dvec3 target = box.min + glm::dvec3(unit(rng), unit(rng), unit(rng)) * box.size();
      const glm::dvec3 from = box.centre() + radius * glm::normalize(glm::dvec3(unit(rng), unit(rng), unit(rng)) - 0.5);
      const glm::dvec3 direction = glm::normalize(target - from);
      const RayResult a = alone.trace(from, direction, 0.0, exact), d = district.trace(from, direction, 0.0, exact);
      hits += a.hit;
      differing += a.hit != d.hit || a.colour != d.colour;
    }
  }
  EXPECT_GT(planeSurfaces, 10);
  EXPECT_GT(hits, 2000);
  EXPECT_LE(differing, 8) << "of " << hits << " hits";  // a ray along an edge, a millimetre apart
}

TEST(District, RefusesOverlappingBuildingsAndNamesThem) {
  const Hierarchy h = quantized(testing::randomHierarchy(7));
  std::vector<Placement> buildings{{h, glm::dvec3(0.0), 0.0}, {h, glm::dvec3(500.0, 0.0, 0.0), 0.0}, {h, glm::dvec3(0.001, 5.0, 0.0), 0.0}};
  auto district = mergeDistrict(placed(buildings));
  ASSERT_FALSE(district);
  EXPECT_EQ(district.error().message, "building 2 overlaps building 0 on the ground");
  EXPECT_FALSE(mergeDistrict({}));
}

// Squares of the side from a corner, by the centre of each box; within a square a box overlapping a member of a
// group joins the next group, and boxes that only touch share one (their millimetres meet).
TEST(DistrictGroups, SquaresByCentreAndNoTwoOverlappingBoxesInOneGroup) {
  const auto box = [](double x0, double z0, double x1, double z1) {
    return WorldBox{glm::dvec3(x0, 0.0, z0), glm::dvec3(x1, 10.0, z1)};
  };
  const std::vector<WorldBox> boxes{
      box(0, 0, 10, 10),        // 0: square (0, 0)
      box(10, 0, 14, 10),       // 1: touches 0
      box(5, 5, 15, 15),        // 2: overlaps 0 and 1
      box(300, 0, 310, 10),     // 3: square (1, 0)
      box(250, 0, 270, 10),     // 4: centre at 260: square (1, 0), though it starts in (0, 0)
      box(13.9996, 0, 20, 4),   // 5: starts 0.4 mm inside 1: the same millimetre once rounded
      box(12, 6, 13, 7),        // 6: inside 1 and 2
      box(-20, -20, -10, -10),  // 7: square (-1, -1), first in (x, z) order
  };
  const std::vector<std::vector<std::size_t>> groups = districtGroups(boxes, 256.0, glm::dvec2(0.0));
  const std::vector<std::vector<std::size_t>> expected{{7}, {0, 1, 5}, {2}, {6}, {3, 4}};
  EXPECT_EQ(groups, expected);
  // Squares from (-20, -20): 7 joins the square of 0, and 4 stays with 3 (its centre 280 m from the corner).
  const std::vector<std::vector<std::size_t>> shifted{{0, 1, 5, 7}, {2}, {6}, {3, 4}};
  EXPECT_EQ(districtGroups(boxes, 256.0, glm::dvec2(-20.0)), shifted);
}

// A building of 250 blocks of its own: a row of 1 m cells, each redirecting to a 1 m cube split at
// its own millimetre along x and at the building's along z, so that each block costs the HNI a
// header and no two buildings share one.
Hierarchy rowOfDistinctBlocks(int building) {
  constexpr int kCount = 250;  // under the 256 cells an axis indexes
  Hierarchy h;
  h.materials = {Material{}, Material{90, 60, 30}};
  Block root;
  for (int x = 0; x <= kCount; ++x) root.boundsM[0].push_back(x);
  root.boundsM[1] = {0.0, 1.0};
  root.boundsM[2] = {0.0, 1.0};
  for (int x = 0; x < kCount; ++x) {
    Block child;
    child.boundsM = {std::vector<double>{0.0, 0.001 * (x + 1), 1.0}, {0.0, 1.0}, {0.0, 0.001 * (building + 1), 1.0}};
    child.cells = {Cell::box(0), Cell::box(1), Cell::box(1), Cell::box(0)};
    root.cells.push_back(Cell::redirect(static_cast<std::uint32_t>(root.redirections.size())));
    root.redirections.push_back(
        Redirection{h.addBlock(std::move(child)), glm::dvec3(0.0), Rotation{}, {false, false, false}});
  }
  h.root = h.addBlock(std::move(root));
  return h;
}

// A district whose buildings do not fit one HNI is halved along their order until each part
// does; the parts together hold every building once, each compiles to an HNI that validates, and
// the suffixes name the halves.
TEST(DistrictGroups, ADistrictTooLargeForOneHniIsHalved) {
  constexpr std::size_t kBuildings = 24;
  std::vector<Placement> buildings;
  for (std::size_t i = 0; i < kBuildings; ++i)
    buildings.push_back(
        {rowOfDistinctBlocks(static_cast<int>(i)), glm::dvec3(0.0, 0.0, 2.0 * static_cast<double>(i)), 0.0});
  auto one = compileDistrict(placed(buildings), {0});
  ASSERT_TRUE(one) << one.error().message;
  ASSERT_EQ(one->size(), 1u);
  EXPECT_EQ(one->front().suffix, "");
  EXPECT_TRUE(validate(one->front().image));

  std::vector<std::size_t> all(kBuildings);
  std::iota(all.begin(), all.end(), std::size_t{0});
  auto parts = compileDistrict(placed(buildings), all);
  ASSERT_TRUE(parts) << parts.error().message;
  ASSERT_GT(parts->size(), 1u);
  std::vector<std::size_t> members;
  for (const CompiledDistrict& part : *parts) {
    EXPECT_TRUE(validate(part.image)) << part.suffix;
    members.insert(members.end(), part.members.begin(), part.members.end());
  }
  EXPECT_EQ(members, all);
  EXPECT_EQ(parts->front().suffix.front(), 'a');
  EXPECT_EQ(parts->back().suffix.front(), 'b');
}

}  // namespace
}  // namespace nut::converter
