// The iteration heat-map (nut/heat_map.hpp, RayCastOptions::heatMap): the ramp at points worked out
// by hand, iteration counts of rays counted by hand on a one-row block, and on random hierarchies
// that the heat-map changes colours only, each hit drawn in the ramp colour of its own iterations.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include <nut/camera.hpp>
#include <nut/heat_map.hpp>
#include <nut/hni.hpp>
#include <nut/raycast.hpp>

#include "../random_hierarchy.hpp"

namespace nut {
namespace {

using Rgb = std::array<std::uint8_t, 3>;

// With a cap of 15 the scale is log2(16) = 4 octaves, one per ramp segment: iterations 2^k - 1
// land exactly on stop k.
TEST(HeatMap, RampStopsAtPowersOfTwo) {
  EXPECT_EQ(heatColour(0, 15), (Rgb{0, 0, 96}));
  EXPECT_EQ(heatColour(1, 15), (Rgb{0, 128, 255}));
  EXPECT_EQ(heatColour(3, 15), (Rgb{0, 200, 80}));
  EXPECT_EQ(heatColour(7, 15), (Rgb{255, 220, 0}));
  EXPECT_EQ(heatColour(15, 15), (Rgb{255, 40, 0}));
  EXPECT_EQ(heatColour(400, 15), (Rgb{255, 40, 0}));  // past the cap: the last stop
  // Between stops 1 and 2: log2(3) - 1 = 0.585 of the way from blue to green.
  EXPECT_EQ(heatColour(2, 15), (Rgb{0, 170, 153}));
}

// Five 1 m cells along x with a box in the last one.
Hierarchy boxAtTheEndOfARow() {
  Hierarchy h;
  h.materials.push_back({200, 100, 50, 255, 0});
  Block b = Block::fromSizes({{{1.0, 1.0, 1.0, 1.0, 1.0}, {1.0}, {1.0}}});
  b.cell(4, 0, 0) = Cell::box(0);
  h.addBlock(b);
  return h;
}

TEST(HeatMap, HitsShowTheIterationsCountedByHand) {
  const auto image = compile(boxAtTheEndOfARow());
  ASSERT_TRUE(image.ok()) << image.error().message;
  const HniRayCaster caster(*image, glm::dvec3(0.0));
  RayCastOptions options;
  options.heatMap = true;
  // From -x the ray crosses the four empty cells and hits the box in the fifth: five visits.
  const RayResult fromLeft = caster.trace({-2.0, 0.5, 0.5}, {1.0, 0.0, 0.0}, 1e-3, options);
  ASSERT_TRUE(fromLeft.hit);
  EXPECT_EQ(fromLeft.iterations, 5);
  EXPECT_EQ(fromLeft.colour, heatColour(5, options.maxIterations));
  // From +x it enters the box's cell first: one visit.
  const RayResult fromRight = caster.trace({7.0, 0.5, 0.5}, {-1.0, 0.0, 0.0}, 1e-3, options);
  ASSERT_TRUE(fromRight.hit);
  EXPECT_EQ(fromRight.iterations, 1);
  EXPECT_EQ(fromRight.colour, heatColour(1, options.maxIterations));
  // A miss keeps the background.
  const RayResult miss = caster.trace({-2.0, 3.0, 0.5}, {1.0, 0.0, 0.0}, 1e-3, options);
  EXPECT_FALSE(miss.hit);
  EXPECT_EQ(miss.colour, kBackground);
}

TEST(HeatMap, ChangesColoursOnly) {
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const Hierarchy h = testing::randomHierarchy(seed);
    const auto image = compile(h);
    ASSERT_TRUE(image.ok()) << "seed " << seed << ": " << image.error().message;
    const HniRayCaster caster(*image, glm::dvec3(0.0));
    const glm::dvec3 size = h.blocks[h.root].sizeM();
    Camera camera;
    camera.width = 96, camera.height = 64;
    camera.target = 0.5 * size;
    camera.eye = camera.target + glm::dvec3(1.1, 0.8, 1.6) * glm::length(size);
    camera.farM = 4.0 * glm::length(size);
    RayCastOptions options;
    const RenderOutput shaded = renderHni(caster, camera, options, 1);
    options.heatMap = true;
    const RenderOutput heat = renderHni(caster, camera, options, 1);
    ASSERT_EQ(heat.iterations, shaded.iterations) << "seed " << seed;
    ASSERT_EQ(heat.distanceM, shaded.distanceM) << "seed " << seed;
    int hits = 0;
    for (int y = 0; y < camera.height; ++y)
      for (int x = 0; x < camera.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y * camera.width + x);
        if (!std::isfinite(heat.distanceM[i])) continue;
        ++hits;
        const std::uint8_t* p = heat.colour.at(x, y);
        const Rgb expected = heatColour(heat.iterations[i], options.maxIterations);
        ASSERT_EQ((Rgb{p[0], p[1], p[2]}), expected) << "seed " << seed << " pixel " << x << "," << y;
      }
    EXPECT_GT(hits, 0) << "seed " << seed;
  }
}

}  // namespace
}  // namespace nut
