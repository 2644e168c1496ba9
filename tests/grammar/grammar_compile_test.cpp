// The grammar producer (grammar/derive.hpp, grammar/compile.hpp): every sample compiles to a
// valid HNI; rays cast straight at the compiled facades find the windows and floors the grammar's
// arithmetic says; alike results are one block; the seed decides, RandStack groups as the facade
// paper's Figure 6 says; and every derivation error names the rule.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <grammar/city.hpp>
#include <grammar/compile.hpp>
#include <nut/hni.hpp>
#include <nut/png_encode.hpp>
#include <nut/raycast.hpp>
#include <nut/units.hpp>

#include "grammar_samples.hpp"

namespace nut::grammar {
namespace {

CompiledGrammar compiled(const std::string& text, const DeriveOptions& options = {}) {
  auto g = parseGrammar(text, "g");
  EXPECT_TRUE(g) << g.error().message;
  auto c = compileGrammar(*g, options);
  EXPECT_TRUE(c) << c.error().message;
  return c ? std::move(*c) : CompiledGrammar{};
}

std::string compileError(const std::string& text, const DeriveOptions& options = {}) {
  auto g = parseGrammar(text, "g");
  EXPECT_TRUE(g) << g.error().message;
  if (!g) return {};
  auto c = compileGrammar(*g, options);
  EXPECT_FALSE(c);
  return c ? std::string() : c.error().message;
}

// The colour a ray cast straight at the facade (from +z, along -z) finds at (x, y).
std::array<std::uint8_t, 3> colourAt(const CompiledGrammar& c, double x, double y) {
  const HniRayCaster caster(c.image, c.originM);
  const RayResult r = caster.trace({x, y, 50.0}, {0, 0, -1}, 1e-4, RayCastOptions{Lookup::Exact});
  EXPECT_TRUE(r.hit) << "at " << x << ", " << y;
  return r.colour;
}

// The colours a line of straight rays (from +z, one every centimetre) meets from `from` to `to`,
// each run of one colour once, in order.
std::vector<std::array<std::uint8_t, 3>> runsAlong(const CompiledGrammar& c, glm::dvec2 from, glm::dvec2 to) {
  const HniRayCaster caster(c.image, c.originM);
  const int steps = static_cast<int>(glm::length(to - from) / 0.01);
  std::vector<std::array<std::uint8_t, 3>> runs;
  for (int i = 0; i <= steps; ++i) {
    const glm::dvec2 p = from + (to - from) * (static_cast<double>(i) / steps);
    const RayResult r = caster.trace({p.x, p.y, 50.0}, {0, 0, -1}, 1e-4, RayCastOptions{Lookup::Exact});
    if (runs.empty() || runs.back() != r.colour) runs.push_back(r.colour);
  }
  return runs;
}

TEST(GrammarCompile, EverySampleCompilesValidatesAndDecodes) {
  const auto names = testing::sampleGrammarNames();
  ASSERT_GE(names.size(), 4u);
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    auto g = readGrammar(testing::sampleGrammarPath(name));
    ASSERT_TRUE(g) << g.error().message;
    auto c = compileGrammar(*g);
    ASSERT_TRUE(c) << c.error().message;
    ASSERT_TRUE(validate(c->image)) << validate(c->image).error().message;
    auto back = decode(c->image);
    ASSERT_TRUE(back);
    EXPECT_EQ(back->blocks.size(), c->hierarchy.blocks.size());
    EXPECT_GT(c->derivation.shapes, static_cast<long long>(c->derivation.nodes.size()));  // sharing happened
  }
}

// Figure 12 of the facade paper on 15 x 12 m: a 3 m ground floor of 2.5 m tiles (6 windows), a
// 2.5 m top floor of 3 m tiles (5), and between them 6.5 m of 2.8 m floors (2) of 2 m tiles
// (15 / 2 = 7.5, rounded: 8). Each window is 1 m wide and 1.3 m high, centred in its tile.
TEST(GrammarCompile, FigureTwelveHasTheWindowsAndFloorsItsArithmeticSays) {
  auto g = readGrammar(testing::sampleGrammarPath("krecklau_figure12"));
  ASSERT_TRUE(g) << g.error().message;
  auto c = compileGrammar(*g);
  ASSERT_TRUE(c) << c.error().message;
  const double floorCentres[] = {1.5, 3.0 + 6.5 / 4, 3.0 + 3 * 6.5 / 4, 12.0 - 1.25};
  const int windows[] = {6, 8, 8, 5};
  const auto wall = colourAt(*c, 0.1, 0.1);
  for (int f = 0; f < 4; ++f) {
    SCOPED_TRACE(::testing::Message() << "floor " << f);
    const auto runs = runsAlong(*c, {0.005, floorCentres[f]}, {14.995, floorCentres[f]});
    ASSERT_EQ(runs.size(), 2u * windows[f] + 1) << "wall, window, wall, ... along the floor";
    for (std::size_t i = 0; i < runs.size(); i += 2) EXPECT_EQ(runs[i], wall);
    // RandStack at each floor and RandUni(1, ...) per window: one window style per floor.
    for (std::size_t i = 3; i < runs.size(); i += 2) EXPECT_EQ(runs[i], runs[1]);
    EXPECT_GT(runs[1][2], runs[1][0]) << "windows are the blue-grey tone";
  }
  // Between floors, above the ground floor's windows, only wall.
  EXPECT_EQ(runsAlong(*c, {0.005, 2.9}, {14.995, 2.9}).size(), 1u);
  // Shared through the Layer's Skips: per floor kind a tile and a window column, the middle
  // floors' row, the floors' split and the facade; not a block per window.
  EXPECT_LE(c->hierarchy.blocks.size(), 9u);
}

// Windows counted along rows and columns of the front of five samples, against counts worked out by
// hand from each grammar's sizes (seed 0). The window colour is read at one window's centre.
TEST(GrammarCompile, EverySampleHasTheWindowsItsSizesSay) {
  struct Line {
    glm::dvec2 from, to;
    int windows;
  };
  const struct {
    std::string sample;
    glm::dvec2 window;  // the centre of one window
    std::vector<Line> lines;
  } cases[] = {
      // 4 x 6 x 4 mass, front at z = 4: six 1 m floors of eight 0.5 m tiles, each window the middle
      // half of its tile both ways.
      {"pga_simple_house", {0.25, 0.5}, {{{0.01, 2.5}, {3.99, 2.5}, 8}, {{0.25, 0.01}, {0.25, 5.99}, 6}}},
      // 14 x 15 x 10: ground floor 2.4 m door then 11.6 m of 1.8 m tiles (6); four 3 m floors of
      // 14 / 1.8 -> 8 tiles; windows 1.4 m high from 0.91 m above each floor.
      {"marvie_building",
       {3.367, 1.61},
       {{{0.01, 1.61}, {13.99, 1.61}, 6}, {{0.01, 4.61}, {13.99, 4.61}, 8}, {{0.875, 0.01}, {0.875, 14.99}, 4}}},
      // 14 x 16 facade: 4 m ground floor of 3.5 m shops (4), 11.2 m of 3.2 m floors (round(3.5) = 4,
      // 2.8 m each) of 2.8 m tiles (5), 0.8 m cornice; a window 1.6 m high, 0.75 m up its floor.
      {"gbef_m1",
       {1.4, 5.55},
       {{{0.01, 5.55}, {13.99, 5.55}, 5}, {{0.01, 1.9}, {13.99, 1.9}, 4}, {{1.4, 0.01}, {1.4, 15.99}, 5}}},
      // 16 x 19 facade: 4.5 m ground floor (two 3 m shops each side of a 3.2 m entrance), 13.5 m of
      // 3.4 m storeys (4, 3.375 m each: a 0.25 m course, then six 2.667 m tiles), recessed glass.
      {"gbef_m2",
       {1.333, 6.306},
       {{{0.01, 6.306}, {15.99, 6.306}, 6}, {{0.01, 2.1}, {15.99, 2.1}, 4}, {{1.333, 4.6}, {1.333, 18.9}, 4}}},
      // 20 x 22 facade: 13.4 m of upper floors between a 5 m ground floor and a 2.6 m attic; three
      // 5.6 m bays between 0.8 m pilasters, 4 floors of 3.35 m, one pair of a tall and a wide
      // window per bay and floor; six 3.33 m arches below, one of them under the first tall window.
      {"gbef_m8", {2.2, 7.0}, {{{0.01, 7.0}, {19.99, 7.0}, 6}, {{2.2, 0.01}, {2.2, 21.99}, 5}}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.sample);
    auto g = readGrammar(testing::sampleGrammarPath(c.sample));
    ASSERT_TRUE(g) << g.error().message;
    auto compiledSample = compileGrammar(*g);
    ASSERT_TRUE(compiledSample) << compiledSample.error().message;
    const auto window = colourAt(*compiledSample, c.window.x, c.window.y);
    EXPECT_GT(window[2], window[0]) << "the probe hits a window (blue-grey)";
    for (const Line& line : c.lines) {
      const auto runs = runsAlong(*compiledSample, line.from, line.to);
      EXPECT_EQ(std::count(runs.begin(), runs.end(), window), line.windows)
          << "from " << line.from.x << ", " << line.from.y << " to " << line.to.x << ", " << line.to.y;
    }
  }
}

// Three window styles chosen per tile: the tiles that came out alike are one block each, so a
// facade of 40 windows costs at most three tile blocks, not forty.
TEST(GrammarCompile, AlikeResultsAreOneBlock) {
  const std::string text = R"(
    @size 20, 8
    F -> SplitY(Rel, 1, Floor, Rel, 1, Floor)
    Floor -> RepeatX(1, Tile)
    Tile -> SplitX(Rel, 1, W, Abs, 0.5, Pick, Rel, 1, W)
    Pick -> RandUni(0, A, B, C)
    W -> Mat(Color, 0, 0.8, 0.8, 0.7, 1)
    A -> Mat(Color, 0, 0.1, 0.1, 0.5, 1)
    B -> Mat(Color, 0, 0.1, 0.5, 0.1, 1)
    C -> Mat(Color, 0, 0.5, 0.1, 0.1, 1)
  )";
  const CompiledGrammar c = compiled(text, {.seed = 3});
  // 2 floors x 20 tiles; every tile is a node of three cells, so distinct tiles = distinct styles.
  std::set<std::array<std::uint8_t, 3>> seen;
  for (int f = 0; f < 2; ++f)
    for (int t = 0; t < 20; ++t) seen.insert(colourAt(c, t + 0.5, 2 + 4 * f));
  EXPECT_EQ(seen.size(), 3u) << "all three styles show up among 40 windows";
  int tileNodes = 0;
  for (const Node& n : c.derivation.nodes)
    if (n.pieces.size() == 3 && std::abs(n.sizeM.x - 1.0) < 1e-9) ++tileNodes;
  EXPECT_EQ(tileNodes, 3);
  EXPECT_LE(c.hierarchy.blocks.size(), 3u + 3u);  // the tiles, the two floors (alike or not) and the facade
}

// A repeat whose tiles are alike is one wrapped redirection: the facade of 30 identical tiles is
// two blocks, whatever the count.
TEST(GrammarCompile, AlikeTilesAreOneWrappedRedirection) {
  const std::string text = R"(
    @size 30, 3
    F -> RepeatX(1, Tile)
    Tile -> SplitX(Rel, 1, W, Abs, 0.5, G, Rel, 1, W)
    W -> Mat(Color, 0, 0.8, 0.8, 0.7, 1)
    G -> Mat(Color, 0, 0.1, 0.1, 0.5, 1)
  )";
  const CompiledGrammar c = compiled(text);
  ASSERT_EQ(c.hierarchy.blocks.size(), 2u);
  const Block& root = c.hierarchy.blocks[c.hierarchy.root];
  ASSERT_EQ(root.redirections.size(), 1u);
  EXPECT_TRUE(root.redirections[0].wrap[0]);
  EXPECT_EQ(runsAlong(c, {0.005, 1.5}, {29.995, 1.5}).size(), 61u);  // 30 windows between 31 walls
}

TEST(GrammarCompile, TheSameSeedGivesTheSameBytesAndOtherSeedsOtherFacades) {
  auto g = readGrammar(testing::sampleGrammarPath("krecklau_figure12"));
  ASSERT_TRUE(g);
  const auto bytes = [&](std::uint64_t seed) {
    auto c = compileGrammar(*g, {.seed = seed});
    EXPECT_TRUE(c);
    return c ? encodePng(c->image, nullptr, PngEffort::Quick) : std::string();
  };
  const std::string first = bytes(1);
  EXPECT_EQ(bytes(1), first);
  std::set<std::string> others;
  for (std::uint64_t seed = 2; seed < 8; ++seed) others.insert(bytes(seed));
  others.insert(first);
  EXPECT_GE(others.size(), 4u) << "seven seeds give at least four different facades";
}

// The facade paper's Figure 6: Rand's first parameter picks the seed. With RandStack per floor and
// level 1 every window of a floor is alike; with level 0 each window draws its own.
TEST(GrammarCompile, RandStackGroupsAsFigureSixDescribes) {
  const auto withLevel = [](int level) {
    std::string text = R"(
    @size 12, 12
    F -> RepeatY(3, Floor)
    Floor -> RandStack(Row)
    Row -> RepeatX(1.5, Tile)
    Tile -> SplitX(Rel, 1, W, Abs, 0.8, Pick, Rel, 1, W)
    Pick -> RandUni()";
    text += std::to_string(level);
    text += R"(, A, B, C, D)
    W -> Mat(Color, 0, 0.8, 0.8, 0.7, 1)
    A -> Mat(Color, 0, 0.1, 0.1, 0.5, 1)
    B -> Mat(Color, 0, 0.1, 0.5, 0.1, 1)
    C -> Mat(Color, 0, 0.5, 0.1, 0.1, 1)
    D -> Mat(Color, 0, 0.5, 0.5, 0.1, 1)
  )";
    return text;
  };
  const auto floorStyles = [](const CompiledGrammar& c) {
    std::vector<std::set<std::array<std::uint8_t, 3>>> floors(4);
    for (int f = 0; f < 4; ++f)
      for (int t = 0; t < 8; ++t) floors[f].insert(colourAt(c, 1.5 * t + 0.75, 3.0 * f + 1.5));
    return floors;
  };
  const auto byFloor = floorStyles(compiled(withLevel(1), {.seed = 11}));
  std::set<std::array<std::uint8_t, 3>> acrossFloors;
  for (const auto& styles : byFloor) {
    EXPECT_EQ(styles.size(), 1u) << "one style per floor";
    acrossFloors.insert(*styles.begin());
  }
  EXPECT_GE(acrossFloors.size(), 2u) << "floors draw apart";
  const auto perWindow = floorStyles(compiled(withLevel(0), {.seed = 11}));
  for (const auto& styles : perWindow) EXPECT_GE(styles.size(), 2u) << "each window draws its own";
}

// A recess: a ray at its centre goes the recess's depth further than one at the wall.
TEST(GrammarCompile, AnIntrusionIsARecessOfItsDepth) {
  const std::string text = R"(
    @size 3, 3
    F -> SplitX(Rel, 1, W, Abs, 1, Col, Rel, 1, W)
    Col -> SplitY(Rel, 1, W, Abs, 1, Hole, Rel, 1, W)
    Hole -> Intrusion(0.2, Side, Side, Side, Side, Back)
    Side -> Mat(Color, 0, 0.5, 0.5, 0.5, 1)
    Back -> Mat(Color, 0, 0.1, 0.1, 0.4, 1)
    W -> Mat(Color, 0, 0.8, 0.8, 0.7, 1)
  )";
  const CompiledGrammar c = compiled(text);
  const HniRayCaster caster(c.image, c.originM);
  const RayCastOptions exact{Lookup::Exact};
  const RayResult wall = caster.trace({0.5, 0.5, 10}, {0, 0, -1}, 1e-4, exact);
  const RayResult back = caster.trace({1.5, 1.5, 10}, {0, 0, -1}, 1e-4, exact);
  const RayResult side = caster.trace({1.02, 1.5, 10}, {0, 0, -1}, 1e-4, exact);  // on the left side's edge
  ASSERT_TRUE(wall.hit && back.hit && side.hit);
  EXPECT_NEAR(wall.distanceM, 10.0, 1e-3);
  EXPECT_NEAR(back.distanceM, 10.2, 1e-3);
  EXPECT_NEAR(side.distanceM, 10.0, 1e-3);
  EXPECT_NE(back.colour, wall.colour);
}

// The fronts mesh has two triangles per facade terminal. The simple house (4 x 6 x 4 m, 0.3 m
// walls): six floors of eight tiles of five quads on each side, but the two sides between the
// front and back walls are clipped to [0.3, 3.7] m, which drops the outer wall strip of the first
// and the last tile on every floor (38 quads a floor there); and one roof and one floor quad.
TEST(GrammarCompile, TheFrontsMeshHasTwoTrianglesPerFacadeTerminal) {
  auto g = readGrammar(testing::sampleGrammarPath("pga_simple_house"));
  ASSERT_TRUE(g) << g.error().message;
  auto c = compileGrammar(*g);
  ASSERT_TRUE(c) << c.error().message;
  auto fronts = derivationMesh(c->derivation, MeshFaces::Fronts);
  ASSERT_TRUE(fronts) << fronts.error().message;
  const int quads = 2 * 6 * 40 + 2 * 6 * 38 + 2;
  EXPECT_EQ(fronts->triangles.size(), 2u * quads);
  auto solid = derivationMesh(c->derivation);
  ASSERT_TRUE(solid);
  EXPECT_GT(solid->triangles.size(), fronts->triangles.size());
  // Every front faces out of the house: its normal points away from the house's centre.
  const glm::dvec3 centre(2, 3, 2);
  for (const auto& t : fronts->triangles) {
    const glm::dvec3 a = fronts->positions[t[0]], b = fronts->positions[t[1]], d = fronts->positions[t[2]];
    const glm::dvec3 normal = glm::cross(b - a, d - a);
    EXPECT_GT(glm::dot(normal, (a + b + d) / 3.0 - centre), 0.0);
  }
}

TEST(GrammarCompile, DerivationErrorsNameTheRule) {
  const struct {
    std::string text, message;
    DeriveOptions options;
  } cases[] = {
      {"@size 4, 3\nA -> SplitX(Abs, 3, B, Abs, 2, B)\nB -> Mat(Color, 0, 1, 0, 0, 1)",
       "g:2:1: rule 'A': parts of 5 m do not fit a scope of 4 m along x",
       {}},
      {"@size 4, 3\nA -> Intrusion(0.5, B, B, B, B, B)\nB -> Mat(Color, 0, 1, 0, 0, 1)",
       "g:2:1: rule 'A': a recess of 0.5 m needs a wall thicker than that; the wall is 0.3 m (--wall)",
       {}},
      {"@size 4, 3\nA -> ComponentSplit {B, B, B}\nB -> Generate {Quad}",
       "g:2:1: rule 'A': ComponentSplit needs a mass (a box scope); this scope is a facade",
       {}},
      {"@size 4, 3, 4\nA -> SubdivideX {1r : B, 1r : T}\nT -> Translate {(-1, 0, 0) : B}\nB -> Generate {Box}",
       "g:2:1: rule 'A': two of its shapes overlap",
       {}},
      {"@size 400, 3\nA -> RepeatX {0.01 : B}\nB -> Generate {Quad}",
       "the derivation exceeds 1000 shapes",
       {.maxShapes = 1000}},
      {"A -> Generate {Quad}",
       "g: no start scope: give --size W,H (a facade) or W,H,D (a mass), or @size in the file",
       {}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    const std::string message = compileError(c.text, c.options);
    EXPECT_NE(message.find(c.message), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << "one line";
  }
}

TEST(CityPlan, RedrawnHeightsSpreadOverThePlansRange) {
  // nut city's retry of a converted building that repeats an earlier one's pixels rests on this:
  // the next seeds give other heights, within the 0.7 to 1.6 times the plan draws.
  std::set<double> heights;
  for (std::uint64_t seed = 1; seed <= 200; ++seed) {
    const double h = redrawHeight(10.0, seed);
    EXPECT_GE(h, 7.0);
    EXPECT_LE(h, 16.0);
    heights.insert(snapToUnits(h));  // to the millimetre, as the HNI stores it
    EXPECT_NE(snapToUnits(h), snapToUnits(redrawHeight(10.0, seed + 1))) << seed;
  }
  // 200 draws from 9,000 millimetres: about 2 repeat by chance.
  EXPECT_GE(heights.size(), 190u);
  EXPECT_EQ(redrawHeight(10.0, 7), redrawHeight(10.0, 7));
}

}  // namespace
}  // namespace nut::grammar
