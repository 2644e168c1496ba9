// Stress tests of plane cells (format version 3) in the float ray caster against the exact path:
// random hierarchies with plane cells at random angles (nearly axis-aligned ones included), rays
// grazing roof planes, lying in them, and crossing them where a plane meets a cell's edge, cameras
// inside, and a million rays aimed inside closed roof houses (a ridge, a valley, and a ridge in a
// yawed sub-block) that must not leak through the seams between cells cut by the same plane.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include <nut/hni.hpp>
#include <nut/png_io.hpp>

#include "../plane_roofs.hpp"
#include "../random_hierarchy.hpp"
#include "stress_support.hpp"

namespace nut::stress {
namespace {

const glm::dvec3 kCityOrigin(2.5e5, 31.0, -6.0e5);

// Random hierarchies in which half the solid cells are plane cells, compared at random rays from
// outside and from cameras inside the root box. Distances only, as WorldCoordinatesNearAMillionMetres
// (translucent inverse solids leave slivers float cannot resolve).
TEST(Stress, PlaneCellsInRandomHierarchies) {
  testing::RandomHierarchyOptions options;
  options.planeCellShare = 0.5;
  Comparison outside("plane cells, rays from outside"), inside("plane cells, cameras inside");
  for (std::uint64_t seed = 0; seed < 120; ++seed) {
    const auto s = makeScene("random hierarchy with plane cells " + std::to_string(seed),
                             testing::randomHierarchy(seed, options), kCityOrigin);
    ASSERT_TRUE(s);
    std::mt19937_64 rng(seed);
    for (int i = 0; i < 300; ++i) {
      const glm::dvec3 target = s->rootSize() * glm::dvec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
      outside.check(*s, s->rayFromOutside(rng, s->toWorld(target), i), {.compare = Compare::Distance});
      const glm::dvec3 eye = s->rootSize() * glm::dvec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
      inside.check(*s, {i, s->toWorld(eye), randomDirection(rng)}, {.compare = Compare::Distance});
    }
  }
  outside.report();
  inside.report();
}

// A camera inside a random hierarchy with plane cells (tests/data/step_before_exit.png: what
// randomHierarchy(93) with planeCellShare 0.5 made while it drew surface materials from its main
// stream) looks along a sub-block whose boundary, in float, falls 2.5e-5 units before the parent
// cell's exit. The caster stepped into the cell beyond and hit it where the exact path leaves the
// parent; a step that close to its level's exit now leaves the level.
TEST(Stress, AStepRoundedBeforeItsLevelsExitLeavesTheLevel) {
  auto png = readPng(std::string(NUT_SOURCE_DIR) + "/tests/data/step_before_exit.png");
  ASSERT_TRUE(png) << png.error().message;
  auto h = decode(png->image);
  ASSERT_TRUE(h) << h.error().message;
  const auto s = makeScene("step before the parent cell's exit", *h, kCityOrigin);
  ASSERT_TRUE(s);
  Comparison comparison("a step rounded before its level's exit");
  comparison.check(*s,
                   {89,
                    {250001.31241404545, 31.462099630344163, -599999.9677668598},
                    {0.21291456439998221, -0.85795394829186877, -0.46752797871010798}},
                   {.compare = Compare::Distance});
  comparison.report();
}

// The roof houses with their planes at ordinary and at nearly axis-aligned angles.
struct RoofScene {
  testing::PlaneRoof roof;
  std::unique_ptr<Scene> scene;
};

std::vector<RoofScene> roofScenes() {
  std::vector<RoofScene> scenes;
  const auto add = [&](const std::string& name, PlaneCombine combine, double yawDeg, double pitchDeg) {
    RoofScene r{testing::planeRoofHouse(combine, yawDeg, pitchDeg), nullptr};
    r.scene = makeScene(name, r.roof.h, kCityOrigin);
    scenes.push_back(std::move(r));
  };
  add("ridge roof", PlaneCombine::Both, 23.0, 20.0);
  add("valley roof", PlaneCombine::Either, 57.0, 20.0);
  add("ridge nearly along x", PlaneCombine::Both, 1e-4, 20.0);
  add("nearly flat ridge roof", PlaneCombine::Both, 31.0, 1e-3);
  return scenes;
}

// A point of roof plane p over the footprint, away from the other plane's side.
glm::dvec3 pointOnPlane(const CutPlane& p, double x, double z) {
  return {x, (p.offsetM - p.normal.x * x - p.normal.z * z) / p.normal.y, z};
}

TEST(Stress, RaysGrazingLyingInAndCrossingRoofPlanes) {
  std::mt19937_64 rng(41);
  long long index = 0;
  for (const RoofScene& r : roofScenes()) {
    ASSERT_TRUE(r.scene);
    const Scene& s = *r.scene;
    const Block& block = r.roof.h.blocks[0];
    Comparison grazing(s.name + ": grazing rays"), lying(s.name + ": rays 0.1 mm off a roof plane"),
        edges(s.name + ": rays through a plane's crossing with a cell edge");
    for (int i = 0; i < 4000; ++i) {
      const CutPlane& plane = r.roof.cut.planes[static_cast<std::size_t>(i % 2)];
      const glm::dvec3 onPlane = pointOnPlane(plane, uniform(rng, r.roof.lo.x + 0.2, r.roof.hi.x - 0.2),
                                              uniform(rng, r.roof.lo.z + 0.2, r.roof.hi.z - 0.2));
      // A direction in the plane, tilted into it by 1e-6 to 1e-3 rad.
      const glm::dvec3 along = glm::normalize(glm::cross(plane.normal, randomDirection(rng)));
      const double angle = std::pow(10.0, uniform(rng, -6, -3));
      const glm::dvec3 dir = glm::normalize(std::cos(angle) * along - std::sin(angle) * plane.normal);
      grazing.check(s, {index++, s.toWorld(onPlane) - 15.0 * dir, dir}, {.compare = Compare::Distance, .minCosine = 0});
      // Parallel to the plane 0.1 mm inside or outside it: 50 times the float spacing of the
      // coordinates, so the side is decided. (A ray exactly in the plane only touches the solid,
      // and either answer is rounding.)
      const glm::dvec3 parallel = onPlane + (i % 4 < 2 ? -1e-4 : 1e-4) * plane.normal;
      lying.check(s, {index++, s.toWorld(parallel) - 15.0 * along, along},
                  {.compare = Compare::Distance, .minCosine = 0});
      // Where the plane crosses the vertical edge of roof cells at boundaries x_i, z_k.
      const double x = block.boundsM[0][2 + static_cast<std::size_t>(rng() % 6)];
      const double z = block.boundsM[2][2 + static_cast<std::size_t>(rng() % 4)];
      edges.check(s, s.rayFromOutside(rng, s.toWorld(pointOnPlane(plane, x, z)), index++));
    }
    grazing.report();
    lying.report();
    edges.report();
  }
}

// Closed roof houses hit by 250,000 rays each from outside, aimed at points at least a margin
// inside (1 mm, and in heuristic lookup also the largest distance the heuristic moves a cell
// face): half at points on a boundary between roof cells (cut by the same plane on both sides), a
// quarter of those with the whole ray in that boundary plane, and a tenth grazing a roof plane. A
// ray that reaches its target has leaked. Every caster leak is checked with the exact path on the
// same model: a leak there means the scene itself is open (never expected); otherwise it fails.
TEST(Stress, NoLeaksThroughPlaneCellRoofs) {
  struct House {
    std::string name;
    testing::PlaneRoof roof;
    Hierarchy h;  // the roof house, or a root that holds it turned
    glm::dmat3 houseToRoot{1.0};
    glm::dvec3 houseOrigin{0.0};  // in the root block
  };
  std::vector<House> houses;
  houses.push_back({"ridge house", testing::planeRoofHouse(PlaneCombine::Both, 23.0, 20.0), {}});
  houses.push_back({"valley house", testing::planeRoofHouse(PlaneCombine::Either, 57.0, 20.0), {}});
  houses.push_back({"ridge nearly along x", testing::planeRoofHouse(PlaneCombine::Both, 1e-4, 35.0), {}});
  houses.push_back({"ridge house in a yawed sub-block", testing::planeRoofHouse(PlaneCombine::Both, 71.0, 25.0), {}});
  for (House& house : houses) house.h = house.roof.h;
  {
    // The house turned by 0.1 turn about y in a 16 m root cell, which it fits.
    House& turned = houses.back();
    Hierarchy h;
    h.materials = turned.roof.h.materials;
    Block root = Block::fromSizes({{{16.0}, {10.0}, {16.0}}});
    const Rotation yaw{0, static_cast<std::uint16_t>(format::kYawSteps / 10)};
    turned.houseToRoot = rotationMatrix(yaw);
    turned.houseOrigin = {1.0, 0.0, 7.0};  // the turned house lies inside the cell
    root.redirections.push_back({1, turned.houseOrigin, yaw});
    root.cell(0, 0, 0) = Cell::redirect(0);
    h.addBlock(root);
    h.addBlock(turned.roof.h.blocks[0]);
    turned.h = h;
  }
  std::mt19937_64 rng(77);
  long long index = 0, totalRays = 0;
  for (const House& house : houses) {
    const auto s = makeScene(house.name, house.h, kCityOrigin);
    ASSERT_TRUE(s);
    double displacement = 0;
    for (const glm::dvec3& d : s->delta) displacement = std::max(displacement, d.x + d.y + d.z);
    displacement *= dagDepth(s->model) + 1;
    const Block& block = house.roof.h.blocks[0];
    const auto toRoot = [&](const glm::dvec3& p) { return house.houseOrigin + house.houseToRoot * p; };
    std::array<long long, 2> leaks{0, 0}, modelLeaks{0, 0};
    for (int i = 0; i < 250000; ++i) {
      const Lookup lookup = i % 2 == 0 ? Lookup::Exact : Lookup::Heuristic;
      const double margin = lookup == Lookup::Exact ? 1e-3 : 1e-3 + displacement;
      // A target in the roof layers most of the time, where the plane cells are.
      glm::dvec3 target;
      const bool onSeam = i % 4 >= 2;
      do {
        target = {uniform(rng, house.roof.lo.x, house.roof.hi.x),
                  uniform(rng, i % 3 == 0 ? 1.0 : house.roof.eaves, 6.6),
                  uniform(rng, house.roof.lo.z, house.roof.hi.z)};
        if (onSeam) target.x = block.boundsM[0][1 + static_cast<std::size_t>(rng() % 8)];
      } while (house.roof.depthInside(target) < margin);
      Ray ray = s->rayFromOutside(rng, s->toWorld(toRoot(target)), index++);
      if (onSeam && i % 8 >= 6) {
        // The whole ray in the seam plane x = target.x of the house.
        const glm::dvec3 from =
            target + 20.0 * glm::normalize(glm::dvec3(0.0, uniform(rng, 0.1, 1), uniform(rng, -1, 1)));
        if (house.roof.contains(from)) continue;
        ray = rayThrough(ray.index, s->toWorld(toRoot(from)), s->toWorld(toRoot(target)));
      } else if (i % 10 == 1 || i % 10 == 4) {
        // Grazing the roof plane that bounds the target: in it, tilted down by 1e-6 to 1e-3 rad.
        const CutPlane& plane = house.roof.cut.planes[static_cast<std::size_t>(rng() % 2)];
        const glm::dvec3 along = glm::normalize(glm::cross(plane.normal, randomDirection(rng)));
        const double angle = std::pow(10.0, uniform(rng, -6, -3));
        const glm::dvec3 dir = glm::normalize(std::cos(angle) * along - std::sin(angle) * plane.normal);
        const glm::dvec3 from = target - 25.0 * dir;
        if (house.roof.contains(from)) continue;
        ray = rayThrough(ray.index, s->toWorld(toRoot(from)), s->toWorld(toRoot(target)));
      }
      ++totalRays;
      const double reach = glm::length(s->toWorld(toRoot(target)) - ray.origin);
      const auto leaked = [&](const RayResult& result) { return !result.hit || result.distanceM > reach; };
      const auto mode = static_cast<std::size_t>(lookup == Lookup::Exact ? 0 : 1);
      const RayResult cast = s->cast(ray, lookup);
      if (!leaked(cast)) continue;
      if (leaked(s->exact(ray, lookup).result)) {
        ++modelLeaks[mode];
      } else if (++leaks[mode] <= 10) {
        ADD_FAILURE() << "a ray passed through the roof to a point " << reach << " m away:\n  "
                      << describe(*s, ray, s->exact(ray, lookup).result, cast, lookup);
      }
    }
    std::printf(
        "%s: leaks of the caster %lld in exact lookup, %lld in heuristic lookup; of the exact path %lld, %lld\n",
        house.name.c_str(), leaks[0], leaks[1], modelLeaks[0], modelLeaks[1]);
    EXPECT_EQ(leaks[0] + leaks[1], 0) << house.name;
    EXPECT_EQ(modelLeaks[0] + modelLeaks[1], 0) << house.name << ": the scene is not closed";
  }
  std::printf("%lld rays aimed inside closed plane-cell roofs\n", totalRays);
  EXPECT_GE(totalRays, 950000);
}

}  // namespace
}  // namespace nut::stress
