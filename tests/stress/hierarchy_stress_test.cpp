// Stress tests of the float ray caster (raycast.hpp) on the structure of the hierarchy: chains of
// redirections as deep as the traversal stack and deeper, sub-blocks wrapped a thousand times along
// one and two axes (and the iteration cap that ends rays through them), and every rotation a
// redirection can carry. Compared with the exact path (exact_path.hpp) in both lookup modes with
// the tolerances of stress_support.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include <nut/camera.hpp>

#include "stress_support.hpp"

namespace nut::stress {
namespace {

const std::vector<Material> kMaterials{
    {200, 60, 40, 255, 0}, {60, 160, 90, 255, 0}, {70, 90, 200, 255, 0}, {230, 210, 80, 255, 0}};

// --- Deep chains -------------------------------------------------------------------------------

constexpr double kChainSide = 30.0;   // side of the root cube, metres
constexpr double kChainShrink = 0.9;  // each level's cube is this much smaller

double chainSide(int level) { return kChainSide * std::pow(kChainShrink, level); }

// A chain of `blocks` nested cubes: block k has 3 cells per axis, a 4 % shell around a 92 % middle
// cell that redirects to block k + 1, placed off-centre in the cell and turned by a random cube
// rotation and a small yaw (so that it stays inside the cell). A few shell cells hold solids (none
// in the last `clearLevels` blocks), and the last block has a box in its middle cell.
Hierarchy nestedChain(int blocks, int clearLevels, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Hierarchy h;
  h.materials = kMaterials;
  for (int k = 0; k < blocks; ++k) {
    const double side = chainSide(k);
    const std::vector<double> cells{0.04 * side, 0.92 * side, 0.04 * side};
    Block b = Block::fromSizes({cells, cells, cells});
    if (k + clearLevels < blocks) {
      for (Cell& c : b.cells) {
        if (rng() % 25 != 0) continue;
        const auto material = static_cast<std::uint16_t>(rng() % kMaterials.size());
        const SolidGroup group =
            std::array{SolidGroup::Box, SolidGroup::Wedge, SolidGroup::QuarterCylinder, SolidGroup::Pyramid}[rng() % 4];
        c = Cell::solidCell(makeSolid(group, static_cast<int>(rng() % static_cast<std::uint64_t>(groupOrientationCount(group)))),
                            material);
      }
    }
    if (k + 1 < blocks) {
      Redirection r;
      r.target = static_cast<BlockId>(k + 1);
      r.rotation.cube = static_cast<std::uint8_t>(rng() % 24);
      r.rotation.yaw = static_cast<std::uint16_t>((65536 + static_cast<int>(rng() % 201) - 100) % 65536);
      const double half = 0.5 * chainSide(k + 1);
      const glm::dvec3 jitter{uniform(rng, -0.004, 0.004), uniform(rng, -0.004, 0.004), uniform(rng, -0.004, 0.004)};
      r.offsetM = glm::dvec3(0.46 * side) - rotationMatrix(r.rotation) * glm::dvec3(half) + side * jitter;
      b.redirections.push_back(r);
      b.cell(1, 1, 1) = Cell::redirect(0);
    } else {
      b.cell(1, 1, 1) = Cell::box(3);
    }
    h.addBlock(std::move(b));
  }
  return h;
}

// World placement of every block of a chain: local point p of block k is at origin[k] + R[k] p.
struct ChainFrames {
  std::vector<glm::dvec3> origin;
  std::vector<glm::dmat3> rotation;
};

ChainFrames chainFrames(const Hierarchy& h, const glm::dvec3& rootOrigin) {
  ChainFrames f{{rootOrigin}, {glm::dmat3(1.0)}};
  for (std::size_t k = 0; k + 1 < h.blocks.size(); ++k) {
    const Block& b = h.blocks[k];
    const Redirection& r = b.redirections[0];
    const glm::dvec3 cellMin{b.boundsM[0][1], b.boundsM[1][1], b.boundsM[2][1]};
    f.origin.push_back(f.origin[k] + f.rotation[k] * (cellMin + r.offsetM));
    f.rotation.push_back(f.rotation[k] * rotationMatrix(r.rotation));
  }
  return f;
}

// A ray from outside the root towards a random point near the centre of the chain's block `level`.
Ray rayIntoChain(const Scene& s, const ChainFrames& frames, int level, std::mt19937_64& rng, long long index) {
  const double side = chainSide(level);
  const glm::dvec3 local = glm::dvec3(0.5 * side) + 0.5 * side * glm::dvec3(uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1));
  const auto k = static_cast<std::size_t>(level);
  return s.rayFromOutside(rng, frames.origin[k] + frames.rotation[k] * local, index);
}

// 32 levels, the most the traversal stack holds (kMaxStackDepth: the root and 31 nested
// redirections), each a smaller cube at an offset, turned by cube rotations and small yaws, with
// rays aimed at the deepest block. Guards against float error that accumulates over 31 changes of
// frame, against a stack that overflows or ends one level early, and against lost clipping or
// entry normals deep in the stack.
TEST(Stress, ThirtyTwoLevelChainMatchesTheExactPath) {
  const Hierarchy h = nestedChain(kMaxStackDepth, 4, 61);
  const auto s = makeScene("32-level chain", h, glm::dvec3(-120.0, 3.0, 640.0));
  ASSERT_TRUE(s);
  const ChainFrames frames = chainFrames(s->model, s->origin);
  std::mt19937_64 rng(62);
  Comparison chain("32-level chain");
  long long deepest = 0;
  for (int i = 0; i < 20000; ++i) {
    const int level = i % 2 == 0 ? kMaxStackDepth - 1 : static_cast<int>(rng() % kMaxStackDepth);
    const Reference exact = chain.check(*s, rayIntoChain(*s, frames, level, rng, i));
    if (exact.result.hit && exact.surface.path.size() == static_cast<std::size_t>(kMaxStackDepth)) ++deepest;
  }
  chain.report();
  std::printf("  %lld rays hit the box of the deepest block\n", deepest);
  EXPECT_GT(deepest, 1000) << "the rays must reach the bottom of the chain";
}

// A chain of 40 nested redirections, deeper than the stack: the caster draws the visual summary of
// the first block that does not fit (block kMaxStackDepth) where the ray enters the cell that holds
// it, shaded with that face's normal, within the default iteration cap, and does not crash. The
// exact path with the same depth limit (maxDepth = kMaxStackDepth - 1 redirections) ends these
// rays capped; the expected distance and face come from the exact path on the same chain with that
// cell made a box (on the model of the lookup mode). Guards against stack overflow, unbounded
// work, and a summary of the wrong block or face.
TEST(Stress, RedirectionsBeyondTheStackDrawTheVisualSummary) {
  Hierarchy h = nestedChain(41, 12, 63);
  VisualSummary summary;
  for (std::size_t side = 0; side < 6; ++side)
    summary[side] = {static_cast<std::uint8_t>(40 + 30 * side), static_cast<std::uint8_t>(220 - 25 * side), 90, 255};
  h.blocks[kMaxStackDepth].summary = summary;
  const auto s = makeScene("40 nested redirections", h, glm::dvec3(3.0e5, 12.0, -4.0e5));
  ASSERT_TRUE(s);
  // The chain of each lookup mode, with the redirection to block kMaxStackDepth replaced by a box.
  std::array<Hierarchy, 2> truncated{s->model, s->heuristicModel};
  for (Hierarchy& t : truncated) t.blocks[kMaxStackDepth - 1].cell(1, 1, 1) = Cell::box(0);
  const ChainFrames frames = chainFrames(s->model, s->origin);
  const glm::dmat3& summaryFrame = frames.rotation[kMaxStackDepth];

  std::mt19937_64 rng(64);
  long long casts = 0, summaries = 0, wrong = 0;
  int mostIterations = 0;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 10000; ++i) {
    const Ray ray = rayIntoChain(*s, frames, kMaxStackDepth, rng, i);
    for (const Lookup lookup : {Lookup::Exact, Lookup::Heuristic}) {
      const RayResult limited =
          traceExact(s->modelFor(lookup), s->origin, ray.origin, ray.dir, {.maxDepth = kMaxStackDepth - 1});
      ExactSurface surface;
      const RayResult expected = traceExact(truncated[lookup == Lookup::Exact ? 0 : 1], s->origin, ray.origin, ray.dir,
                                            {.surface = &surface});
      RayCastOptions options;
      options.lookup = lookup;
      const RayResult cast = s->caster->trace(ray.origin, ray.dir, 1e-3, options);
      ++casts;
      mostIterations = std::max(mostIterations, cast.iterations);
      bool ok = !cast.capped;
      // Rays stopped earlier by a solid of the chain's shells are the other tests' business.
      if (ok && expected.hit && surface.path.size() == static_cast<std::size_t>(kMaxStackDepth)) {
        ++summaries;
        // The side of block kMaxStackDepth the ray meets: the entry normal in that block's frame.
        const glm::dvec3 n = glm::transpose(summaryFrame) * expected.normal;
        const int axis =
            std::abs(n.x) >= std::max(std::abs(n.y), std::abs(n.z)) ? 0 : std::abs(n.y) >= std::abs(n.z) ? 1 : 2;
        const Rgba8 side = summary[static_cast<std::size_t>(2 * axis + (n[axis] > 0 ? 0 : 1))];
        const auto colour = shade({side.r, side.g, side.b}, expected.normal, ray.dir);
        ok = cast.hit && std::abs(cast.distanceM - expected.distanceM) <= exactTolerance(*s, ray, expected) &&
             limited.capped;
        for (std::size_t c = 0; c < 3; ++c) ok = ok && std::abs(cast.colour[c] - colour[c]) <= 1;
        if (!ok && ++wrong <= 5)
          ADD_FAILURE() << "beyond the stack, the caster must draw block " << kMaxStackDepth
                        << "'s summary where the exact path meets its cell, shaded for that face (colour ("
                        << int(colour[0]) << ", " << int(colour[1]) << ", " << int(colour[2]) << ")):\n  "
                        << describe(*s, ray, expected, cast, lookup);
      } else if (!ok && ++wrong <= 5) {
        ADD_FAILURE() << "capped:\n  " << describe(*s, ray, expected, cast, lookup);
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("40 nested redirections: %lld casts, %lld summaries drawn, %lld wrong, at most %d iterations "
              "(%.2f s with the exact path)\n",
              casts, summaries, wrong, mostIterations, seconds);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(summaries, casts / 4);
  EXPECT_LE(mostIterations, 8 * kMaxStackDepth);

  // A whole frame of the chain, looking into it: every pixel ends, none at the cap.
  Camera camera;
  camera.eye = frames.origin[0] + glm::dvec3(-20.0, 45.0, 70.0);
  camera.target = frames.origin[kMaxStackDepth] + frames.rotation[kMaxStackDepth] * glm::dvec3(0.5 * chainSide(kMaxStackDepth));
  camera.fovYDeg = 2.0;
  camera.width = camera.height = 96;
  RenderStats stats;
  renderHni(*s->caster, camera, RayCastOptions{}, 2, &stats);
  std::printf("  96 x 96 frame: %.3f s, %.0f iterations per ray on average, at most %d, %.2f %% capped\n",
              stats.seconds, stats.iterationsMean, stats.iterationsMax, stats.cappedPct);
  EXPECT_EQ(stats.cappedPct, 0.0);
  EXPECT_LE(stats.iterationsMax, 8 * kMaxStackDepth);
}

// --- Wrapping ----------------------------------------------------------------------------------

constexpr int kTiles = 1000;

// A tile of side `tile` repeated kTiles times along x (and along z when twoAxes) in the middle cell
// of a root that has an empty metre before the run and a box wall after it on each tiled axis. On
// one axis the tile is a slat in its lower +x quarter (a channel runs above the slats); on two, a
// pillar in its lower corner (a channel runs above the pillars).
Hierarchy tiledRun(double tile, bool twoAxes) {
  Hierarchy h;
  h.materials = kMaterials;
  const double run = kTiles * tile;
  Block root = Block::fromSizes({{{1.0, run, 1.0}, {tile}, twoAxes ? std::vector<double>{1.0, run, 1.0} : std::vector<double>{tile}}});
  root.redirections.push_back({1, glm::dvec3(0.0), {}, {true, false, twoAxes}});
  const int zCells = twoAxes ? 3 : 1;
  for (int z = 0; z < zCells; ++z) root.cell(2, 0, z) = Cell::box(3);
  if (twoAxes) {
    for (int x = 0; x < 3; ++x) root.cell(x, 0, 2) = Cell::box(3);
    root.cell(1, 0, 1) = Cell::redirect(0);
  } else {
    root.cell(1, 0, 0) = Cell::redirect(0);
  }
  h.addBlock(root);
  const double half = 0.5 * tile;
  Block t = Block::fromSizes({{{half, half}, {half, half}, twoAxes ? std::vector<double>{half, half} : std::vector<double>{tile}}});
  if (twoAxes)
    t.cell(0, 0, 0) = Cell::box(0);
  else
    t.cell(1, 0, 0) = Cell::box(0);
  h.addBlock(t);
  return h;
}

// Sub-blocks of 1 cm, 10 cm and 1 m wrapped 1000 times along x (and 1 cm and 1 m over 1000 x 1000
// tiles along x and z), with rays across the run (onto random tiles) and along it through the
// channel, level or descending onto a tile far down the run. Guards against drift of the tile
// origin over a thousand wraps, against seams between tiles, and against a wrapped level that
// never ends. The long rays are shallow, so their distances are judged by the backward error
// (minCosine 0). Then the cap: with the default RayCastOptions::maxIterations, the level rays
// through the whole run end capped with kCappedColour, promptly, instead of hanging.
TEST(Stress, ThousandFoldWrapping) {
  struct Config {
    double tile;
    bool twoAxes;
  };
  std::mt19937_64 rng(71);
  long long index = 0;
  for (const Config config : {Config{0.01, false}, Config{0.1, false}, Config{1.0, false}, Config{0.01, true},
                              Config{1.0, true}}) {
    char name[96];
    std::snprintf(name, sizeof name, "%g m tile x %d along %s", config.tile, kTiles, config.twoAxes ? "x and z" : "x");
    const auto s = makeScene(name, tiledRun(config.tile, config.twoAxes), glm::dvec3(-500.0, 20.0, 800.0));
    ASSERT_TRUE(s);
    const double run = kTiles * config.tile;
    const glm::dvec3 runSize{run, config.tile, config.twoAxes ? run : config.tile};
    const glm::dvec3 runMin{1.0, 0.0, config.twoAxes ? 1.0 : 0.0};

    Comparison across(std::string(name) + ": rays across the run");
    for (int i = 0; i < 5000; ++i) {
      const glm::dvec3 target = runMin + runSize * glm::dvec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
      across.check(*s, s->rayFromOutside(rng, s->toWorld(target), index++));
    }
    across.report();

    // Along the run from the empty metre before it, in the channel above the slats or pillars:
    // level (the first of every eight exactly along the axis or the diagonal) or descending by at
    // most enough to reach the slat tops within the run.
    Comparison along(std::string(name) + ": rays along the run");
    std::vector<Ray> level;
    for (int i = 0; i < 800; ++i) {
      const double y = uniform(rng, 0.55, 0.95) * config.tile;
      const glm::dvec3 start{0.5, y, config.twoAxes ? 0.5 : 0.5 * config.tile};
      const double drop = i % 8 == 0 ? 0.0 : uniform(rng, 0, 1.2) * std::atan((y - 0.5 * config.tile) / run);
      const double heading = !config.twoAxes ? 0.0 : i % 8 == 0 ? std::numbers::pi / 4 : uniform(rng, 0, std::numbers::pi / 2);
      glm::dvec3 dir{std::cos(drop) * std::cos(heading), -std::sin(drop), std::cos(drop) * std::sin(heading)};
      if (!config.twoAxes) dir.z = 0;
      dir = glm::normalize(dir);
      const Ray ray{index++, s->toWorld(start), dir};
      along.check(*s, ray, {.compare = Compare::Distance, .minCosine = 0});
      if (drop == 0.0) level.push_back(ray);
    }
    along.report();

    long long notCapped = 0;
    const auto start = std::chrono::steady_clock::now();
    for (const Ray& ray : level)
      for (const Lookup lookup : {Lookup::Exact, Lookup::Heuristic}) {
        RayCastOptions options;
        options.lookup = lookup;
        const RayResult r = s->caster->trace(ray.origin, ray.dir, 1e-3, options);
        if ((!r.capped || r.hit || r.colour != kCappedColour || r.iterations > options.maxIterations + 1) &&
            ++notCapped <= 3)
          ADD_FAILURE() << name << ": a ray through the whole run must end capped at the default cap:\n  "
                        << describe(*s, ray, s->exact(ray).result, r, lookup);
      }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("%s: %zu level rays at the default cap: %lld not capped, %.1f us per ray\n", name, level.size(),
                notCapped, 1e6 * seconds / std::max<double>(1.0, 2.0 * static_cast<double>(level.size())));
    EXPECT_EQ(notCapped, 0);
  }
}

// --- Rotations ---------------------------------------------------------------------------------

// An asymmetric block (no rotation maps it onto itself): unequal cells, a box, a wedge, a quarter
// cylinder, a pyramid and a sphere octant in an irregular pattern.
Block asymmetricBlock() {
  Block b = Block::fromSizes({{{0.4, 0.8}, {0.3, 0.5}, {0.6, 0.4, 0.6}}});
  b.cell(0, 0, 0) = Cell::box(0);
  b.cell(1, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::Wedge, 2 * 4 + 1), 1);
  b.cell(0, 0, 1) = Cell::solidCell(makeSolid(SolidGroup::QuarterCylinder, 0 * 4 + 2), 2);
  b.cell(1, 0, 2) = Cell::solidCell(makeSolid(SolidGroup::Pyramid, 5), 3);
  b.cell(0, 1, 2) = Cell::box(1);
  b.cell(1, 1, 1) = Cell::solidCell(makeSolid(SolidGroup::SphereOctant, 3), 0);
  return b;
}

// The asymmetric block redirected into the middle cell of a 3 x 3 x 3 root with the given rotation,
// centred in the cell: a 2.5 m cell holds it whole; a 1 m cell clips it.
Hierarchy rotatedTarget(const Rotation& rotation, double cell) {
  Hierarchy h;
  h.materials = kMaterials;
  Block root = Block::fromSizes({{{2.0, cell, 2.0}, {2.0, cell, 2.0}, {2.0, cell, 2.0}}});
  const Block target = asymmetricBlock();
  root.redirections.push_back({1, glm::dvec3(0.5 * cell) - rotationMatrix(rotation) * (0.5 * target.sizeM()), rotation,
                               {false, false, false}});
  root.cell(1, 1, 1) = Cell::redirect(0);
  root.cell(0, 0, 0) = Cell::box(2);  // something else in the scene, outside the rotated block
  h.addBlock(root);
  h.addBlock(target);
  return h;
}

// Every rotation of the format: the 24 cube rotations, yaws of 0, 1, 8192 (45 degrees), 16384,
// 32768 and 65535 steps and random ones, and random cube and yaw pairs, each with the asymmetric
// block whole and clipped by its cell. Guards against a rotation applied inverted, transposed or
// in the wrong order (cube, then yaw), against normals not turned back to the world, and against
// clip faces lost under rotation.
TEST(Stress, EveryRotationOfTheFormat) {
  std::vector<Rotation> rotations;
  for (int cube = 0; cube < 24; ++cube) rotations.push_back({static_cast<std::uint8_t>(cube), 0});
  std::mt19937_64 rng(81);
  for (const int yaw : {1, 8192, 16384, 32768, 65535}) rotations.push_back({0, static_cast<std::uint16_t>(yaw)});
  for (int i = 0; i < 6; ++i) rotations.push_back({0, static_cast<std::uint16_t>(rng() % 65536)});
  for (int i = 0; i < 6; ++i) rotations.push_back({static_cast<std::uint8_t>(rng() % 24), static_cast<std::uint16_t>(rng() % 65536)});

  Comparison whole("rotated block, whole"), clipped("rotated block, clipped by its cell");
  long long index = 0;
  for (const Rotation& rotation : rotations) {
    for (const double cell : {2.5, 1.0}) {
      const std::string name = "cube " + std::to_string(rotation.cube) + " yaw " + std::to_string(rotation.yaw) +
                               (cell < 2 ? ", clipped" : ", whole");
      const auto s = makeScene(name, rotatedTarget(rotation, cell), glm::dvec3(77.0, -3.0, 1.0e4));
      ASSERT_TRUE(s);
      Comparison& comparison = cell < 2 ? clipped : whole;
      for (int i = 0; i < 2500; ++i) {
        const glm::dvec3 target = glm::dvec3(2.0) + cell * glm::dvec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
        comparison.check(*s, s->rayFromOutside(rng, s->toWorld(target), index++));
      }
    }
  }
  whole.report();
  clipped.report();
}

}  // namespace
}  // namespace nut::stress
