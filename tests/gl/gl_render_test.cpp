// The GLSL ray caster against the CPU reference caster (nut/raycast.hpp), frame by frame: every
// sample HNI and stress-like scenes (random hierarchies with every feature of the format, a camera
// inside a building, city-sized world coordinates, centimetre cells in a half-kilometre block,
// translucent panes, a chain of blocks deeper than the traversal stack, level of detail, exact
// lookup, the iteration heat-map). Tolerance (docs/GL.md): at least 99.9 % of the pixels within
// 2/255 and, where both drew a surface, window depths within gltest::kWindowDepthBound of the
// CPU's (3x3 range). Renders are small (320x180 to 640x360) to keep llvmpipe quick; on failure
// <name>.actual.png, .expected.png, .diff.png are written to tests/gl/output/render.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <set>

#include <glm/geometric.hpp>

#include <grammar/compile.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>

#include "../plane_roofs.hpp"
#include "../random_hierarchy.hpp"
#include "gl_scenes.hpp"
#include "gl_test_support.hpp"

namespace nut::gltest {
namespace {

constexpr int kThreshold = 2;
constexpr double kMinWithinPct = 99.9;

void expectSameImage(const Scene& s) {
  ASSERT_GT(s.image.width, 0) << s.name << ": no HNI";
  const HniRayCaster caster(s.image, s.originM);
  const RenderOutput cpu = renderHni(caster, s.camera, s.options);
  auto renderer = openRenderer();
  ASSERT_TRUE(renderer);
  ASSERT_TRUE(renderer->addHni(s.image, s.originM).ok());
  auto gl = renderer->render(s.camera, s.options);
  ASSERT_TRUE(gl.ok()) << gl.error().message;
  const Agreement a = compareFrames(outputDir("render"), s.name, cpu.colour, cpu.windowDepth, gl->colour,
                                    gl->windowDepth, kThreshold, kMinWithinPct);
  EXPECT_GE(a.withinPct, kMinWithinPct) << s.name;
  EXPECT_EQ(a.depthOutOfRange, 0) << s.name << ": window depths out of range; see the diff image";
  EXPECT_GT(a.depthPixels, 0) << s.name << ": nothing drawn";
  // The distances read back (what --depth writes) invert the window depth: where the depths agree,
  // they agree with the CPU's distances to the depth buffer's precision.
  long long distanceOff = 0;
  for (std::size_t i = 0; i < cpu.distanceM.size(); ++i)
    if (cpu.windowDepth[i] < 1.0f && std::abs(gl->windowDepth[i] - cpu.windowDepth[i]) <= kWindowDepthBound)
      distanceOff += std::abs(gl->distanceM[i] - cpu.distanceM[i]) > 1e-4 * cpu.distanceM[i];
  EXPECT_EQ(distanceOff, 0) << s.name << ": distances differ by more than 1e-4 of themselves";
}

class SampleMatchesCpu : public ::testing::TestWithParam<std::string> {};

TEST_P(SampleMatchesCpu, HeuristicLookup) {
  Scene s = sampleScene(GetParam(), 640, 360);
  expectSameImage(s);
}

INSTANTIATE_TEST_SUITE_P(Samples, SampleMatchesCpu, ::testing::Values("facade", "building", "solids", "rotations"));

// Every sample grammar (samples/grammars/), compiled with seed 0, from the default camera.
class GrammarSampleMatchesCpu : public ::testing::TestWithParam<std::string> {};

TEST_P(GrammarSampleMatchesCpu, HeuristicLookup) {
  auto g = grammar::readGrammar(std::string(NUT_SOURCE_DIR) + "/samples/grammars/" + GetParam() + ".grammar");
  ASSERT_TRUE(g) << g.error().message;
  auto c = grammar::compileGrammar(*g);
  ASSERT_TRUE(c) << c.error().message;
  auto bounds = contentBounds(c->hierarchy, c->originM);
  ASSERT_TRUE(bounds);
  Scene s{"grammar-" + GetParam(), c->hierarchy, c->image, c->originM, fitCamera(*bounds, 480, 320), {}};
  expectSameImage(s);
}

INSTANTIATE_TEST_SUITE_P(Grammars, GrammarSampleMatchesCpu,
                         ::testing::Values("krecklau_figure12", "pga_simple_house", "pga_random_windows",
                                           "pga_random_rule", "pga_complex_house", "marvie_building", "gbef_m1",
                                           "gbef_m2", "gbef_m8"));

TEST(GlMatchesCpu, ExactLookup) {
  Scene s = sampleScene("building", 640, 360);
  s.name = "building-exact";
  s.options.lookup = Lookup::Exact;
  expectSameImage(s);
}

TEST(GlMatchesCpu, LevelOfDetailFromAfar) {
  Scene s = sampleScene("building", 480, 270);
  s.name = "building-lod";
  // Two and a half times as far: many redirected blocks span less than 4 pixels.
  s.camera.eye = s.camera.target + 2.5 * (s.camera.eye - s.camera.target);
  s.camera.farM *= 2.5;
  s.options.lodPx = 4.0;
  expectSameImage(s);
}

TEST(GlMatchesCpu, MeasuredLevelOfDetailFromAfar) {
  auto g = grammar::readGrammar(std::string(NUT_SOURCE_DIR) + "/samples/grammars/pga_complex_house.grammar");
  ASSERT_TRUE(g) << g.error().message;
  auto c = grammar::compileGrammar(*g, {}, LodMeasureOptions{});
  ASSERT_TRUE(c) << c.error().message;
  auto bounds = contentBounds(c->hierarchy, c->originM);
  ASSERT_TRUE(bounds);
  Scene s{"grammar-lod-auto", c->hierarchy, c->image, c->originM, fitCamera(*bounds, 320, 180), {}};
  // Eight times as far: a pixel spans about 1.5 m, more than several blocks' footprints.
  s.camera.eye = s.camera.target + 8.0 * (s.camera.eye - s.camera.target);
  s.camera.farM *= 8.0;
  s.options.lodAuto = true;
  expectSameImage(s);
  // The comparison is of summaries: the CPU draws some where full detail differs.
  const HniRayCaster caster(s.image, s.originM);
  RayCastOptions full = s.options;
  full.lodAuto = false;
  EXPECT_NE(renderHni(caster, s.camera, s.options).colour, renderHni(caster, s.camera, full).colour);
}

TEST(GlMatchesCpu, IterationHeatMap) {
  Scene s = sampleScene("building", 480, 270);
  s.name = "building-heat-map";
  s.options.heatMap = true;
  expectSameImage(s);
  // The building's rays take from a few to dozens of iterations: the image spreads over the ramp.
  const HniRayCaster caster(s.image, s.originM);
  const RenderOutput heat = renderHni(caster, s.camera, s.options);
  std::set<int> colours;  // as 0xRRGGBB
  for (int y = 0; y < heat.colour.height; ++y)
    for (int x = 0; x < heat.colour.width; ++x) {
      const std::uint8_t* p = heat.colour.at(x, y);
      colours.insert(p[0] << 16 | p[1] << 8 | p[2]);
    }
  EXPECT_GE(colours.size(), 8u);
}

TEST(GlMatchesCpu, CameraInsideTheBuilding) {
  Scene s = sampleScene("building", 480, 270);
  s.name = "building-inside";
  // From the middle of the ground floor towards a corner: walls, floors and ceilings all around.
  const HniRayCaster caster(s.image, s.originM);
  const WorldBox box = caster.bounds();
  s.camera.eye = box.min + glm::dvec3(0.5, 0.25, 0.5) * box.size();
  s.camera.target = box.min + glm::dvec3(0.88, 0.27, 0.91) * box.size();
  s.camera.nearM = 0.05;
  s.camera.farM = glm::length(box.size());
  s.camera.fovYDeg = 70.0;
  expectSameImage(s);
}

TEST(GlMatchesCpu, CityCoordinates) {
  // The facade a million metres from the world origin: the eye-relative set-up keeps float precision.
  Scene s = sampleScene("facade", 480, 270);
  s.name = "facade-city";
  const glm::dvec3 shift(1.0e6 + 0.123, 35.0, -2.0e6 - 0.456);
  s.originM += shift;
  s.camera.eye += shift;
  s.camera.target += shift;
  expectSameImage(s);
}

TEST(GlMatchesCpu, CentimetreCellsInAHalfKilometreBlock) {
  Scene s = compiledScene("centimetre-cells", centimetreCells(), glm::dvec3(-250.0, 0.0, -250.0), 480, 270);
  // A metre from the 0.6 m block of 1 cm cells in the middle of the 500 m root.
  s.camera.target = glm::dvec3(0.0, 0.0, 0.0);
  s.camera.eye = glm::dvec3(0.5, 0.7, 0.9);
  s.camera.nearM = 0.05;
  s.camera.farM = 1000.0;
  expectSameImage(s);
}

TEST(GlMatchesCpu, TranslucentPanes) {
  Scene s = compiledScene("translucent", translucentPanes(), glm::dvec3(0.0), 480, 270);
  s.camera.eye = glm::dvec3(2.6, 1.3, -4.0);  // from the side of the panes
  s.camera.target = glm::dvec3(2.0, 1.0, 1.5);
  expectSameImage(s);
}

TEST(GlMatchesCpu, ChainDeeperThanTheStack) {
  // 40 nested blocks: below level kMaxStackDepth both casters draw the visual summary.
  Scene s = compiledScene("chain-40", nestedChain(40), glm::dvec3(0.0), 480, 270);
  // Above the common centre, close enough for the innermost levels to cover the view.
  const double side = s.model.blocks[28].sizeM().x;
  const glm::dvec3 centre = 0.5 * s.model.blocks[0].sizeM();
  s.camera.target = centre;
  s.camera.eye = centre + glm::dvec3(0.4, 1.6, 0.9) * side;
  s.camera.nearM = 0.01 * side;
  s.camera.farM = 10.0 * side;
  expectSameImage(s);
}

TEST(Fxaa, SmoothsEdgesOnly) {
  // Optional post-process: it changes pixels at edges (a neighbour differs by more than 8/255 in
  // the plain frame) and nowhere else.
  const Scene s = sampleScene("facade", 480, 270);
  auto renderer = openRenderer();
  ASSERT_TRUE(renderer);
  ASSERT_TRUE(renderer->addHni(s.image, s.originM).ok());
  auto plain = renderer->render(s.camera, {});
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  ASSERT_TRUE(renderer->setFxaa(true).ok());
  auto smooth = renderer->render(s.camera, {});
  ASSERT_TRUE(smooth.ok()) << smooth.error().message;
  const Image& a = plain->colour;
  const Image& b = smooth->colour;
  long long changed = 0, changedAwayFromEdges = 0;
  for (int y = 1; y + 1 < a.height; ++y)
    for (int x = 1; x + 1 < a.width; ++x) {
      if (std::equal(a.at(x, y), a.at(x, y) + 3, b.at(x, y))) continue;
      ++changed;
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          for (int c = 0; c < 3; ++c) edge = edge || std::abs(a.at(x, y)[c] - a.at(x + dx, y + dy)[c]) > 8;
      changedAwayFromEdges += !edge;
    }
  std::printf("fxaa: %lld pixels changed, %lld of them away from edges\n", changed, changedAwayFromEdges);
  EXPECT_GT(changed, 500);
  EXPECT_EQ(changedAwayFromEdges, 0);
  if (std::getenv("NUT_TEST_KEEP_IMAGES")) {
    EXPECT_TRUE(writePng((outputDir("render") / "facade-fxaa.png").string(), b).ok());
  }
}

class RandomHierarchyMatchesCpu : public ::testing::TestWithParam<int> {};

TEST_P(RandomHierarchyMatchesCpu, DefaultCamera) {
  // Every solid, rotation and yaw of redirections, wrapping, translucency, textures (ignored).
  const int seed = GetParam();
  Scene s = compiledScene("random-" + std::to_string(seed), testing::randomHierarchy(static_cast<std::uint64_t>(seed)),
                          glm::dvec3(0.0), 320, 180);
  expectSameImage(s);
}

INSTANTIATE_TEST_SUITE_P(Seeds, RandomHierarchyMatchesCpu, ::testing::Range(1, 9));

class PlaneCellHierarchyMatchesCpu : public ::testing::TestWithParam<int> {};

TEST_P(PlaneCellHierarchyMatchesCpu, DefaultCamera) {
  // Half the solid cells plane cells (format version 3), with everything else random hierarchies have.
  const int seed = GetParam();
  testing::RandomHierarchyOptions options;
  options.planeCellShare = 0.5;
  const Hierarchy h = testing::randomHierarchy(static_cast<std::uint64_t>(seed), options);
  Scene s = compiledScene("random-planes-" + std::to_string(seed), h, glm::dvec3(0.0), 320, 180);
  expectSameImage(s);
}

INSTANTIATE_TEST_SUITE_P(Seeds, PlaneCellHierarchyMatchesCpu, ::testing::Range(1, 7));

// The roof houses seen across their ridge or valley line. (Seen along it, rays graze both roof
// planes at once, and the hit distance of either caster moves by a millimetre for a rounding of
// its direction: a few pixels on the line then fail the depth neighbourhood check; the stress
// tests judge such rays by their backward error.)
TEST(GlMatchesCpu, PlaneCellRoofs) {
  for (const PlaneCombine combine : {PlaneCombine::Both, PlaneCombine::Either}) {
    const glm::dvec3 origin(100.0, 0.0, -40.0);
    Scene s = compiledScene(combine == PlaneCombine::Both ? "ridge-roof" : "valley-roof",
                            testing::planeRoofHouse(combine).h, origin, 480, 270);
    const double yaw = (combine == PlaneCombine::Both ? 23.0 : 57.0) * std::numbers::pi / 180.0;
    const glm::dvec3 across(-std::sin(yaw), 0.0, std::cos(yaw)), along(std::cos(yaw), 0.0, std::sin(yaw));
    s.camera.target = origin + glm::dvec3(5.0, 4.0, 4.0);
    s.camera.eye = s.camera.target + 14.0 * across + 4.0 * along + glm::dvec3(0.0, 8.0, 0.0);
    expectSameImage(s);
  }
}

}  // namespace
}  // namespace nut::gltest
