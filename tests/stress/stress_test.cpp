// Stress tests of the float ray caster (raycast.hpp) against the exact path (exact_path.hpp) on
// rays and cameras that random rays almost never produce: rays along axes, in boundary planes and
// through edges and corners, grazing rays, cameras inside blocks, centimetre cells in half-kilometre
// blocks, and city-sized world coordinates. Every scene is compared in both lookup modes with the
// tolerances of stress_support.hpp; hierarchy_stress_test.cpp and leak_stress_test.cpp hold the
// other stress scenarios.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <nut/camera.hpp>

#include "../random_hierarchy.hpp"
#include "stress_support.hpp"

namespace nut::stress {
namespace {

const std::vector<Material> kMaterials{
    {200, 60, 40, 255, 0}, {60, 160, 90, 255, 0}, {70, 90, 200, 255, 0}, {230, 210, 80, 255, 0}};

// A block of unequal cells filled in a fixed pseudo-random pattern: a quarter empty, the rest boxes,
// wedges and quarter cylinders of every orientation.
Block patternedBlock(const std::array<std::vector<double>, 3>& sizes, std::uint64_t seed) {
  Block b = Block::fromSizes(sizes);
  std::mt19937_64 rng(seed);
  for (Cell& c : b.cells) {
    const auto material = static_cast<std::uint16_t>(rng() % kMaterials.size());
    switch (rng() % 8) {
      case 0:
      case 1: break;
      case 2:
      case 3:
      case 4: c = Cell::box(material); break;
      case 5:
      case 6: c = Cell::solidCell(makeSolid(SolidGroup::Wedge, static_cast<int>(rng() % 12)), material); break;
      default: c = Cell::solidCell(makeSolid(SolidGroup::QuarterCylinder, static_cast<int>(rng() % 12)), material);
    }
  }
  return b;
}

Hierarchy oneBlock(Block b) {
  Hierarchy h;
  h.materials = kMaterials;
  h.addBlock(std::move(b));
  return h;
}

// Every boundary of an axis and the quarter points between them.
std::vector<double> boundariesAndQuarters(const std::vector<double>& bounds) {
  std::vector<double> out;
  for (std::size_t i = 0; i + 1 < bounds.size(); ++i)
    for (int k = 0; k < 4; ++k) out.push_back(bounds[i] + k * (bounds[i + 1] - bounds[i]) / 4);
  out.push_back(bounds.back());
  return out;
}

// Rays along axes, in boundary planes, and through the edges and corners of a multi-cell block:
// guards against cell lookups that pick a different side of a boundary than the exact path's
// convention (a coordinate on a boundary belongs to the cell above it), against steps that stall
// or skip a cell when two boundaries are crossed at once, and against division by the exact zeros
// of such directions. Every boundary is a binary fraction of a metre and the root origin an integer,
// so a ray placed on a boundary is exactly on it for both renderers. Only distances are compared:
// at an edge the normal is either face's, and a ray in a boundary plane may touch a wedge or a
// quarter cylinder along a line of zero thickness, whose normal is a matter of rounding.
TEST(Stress, AxisAlignedRaysAlongBoundariesEdgesAndCorners) {
  const Hierarchy h = oneBlock(patternedBlock({{{0.5, 1.25, 0.75, 1.0}, {0.625, 1.0, 0.875}, {1.0, 0.5, 1.5, 0.75}}}, 1));
  const auto s = makeScene("boundary grid", h, glm::dvec3(-3.0, 0.0, 5.0));
  ASSERT_TRUE(s);
  const Block& b = s->model.blocks[0];
  const glm::dvec3 size = s->rootSize();
  std::array<std::vector<double>, 3> lattice;
  for (int a = 0; a < 3; ++a) lattice[a] = boundariesAndQuarters(b.boundsM[a]);
  std::mt19937_64 rng(11);
  long long index = 0;

  // Along +-x, +-y, +-z from outside, at every pair of boundary and quarter positions of the other
  // axes: in cell interiors, in boundary planes, along cell edges and along the block's faces.
  Comparison along("rays along the axes");
  for (int a = 0; a < 3; ++a)
    for (const double sign : {1.0, -1.0})
      for (const double p : lattice[(a + 1) % 3])
        for (const double q : lattice[(a + 2) % 3]) {
          glm::dvec3 local;
          local[a] = sign > 0 ? -1.0 : size[a] + 1.0;
          local[(a + 1) % 3] = p;
          local[(a + 2) % 3] = q;
          glm::dvec3 dir(0.0);
          dir[a] = sign;
          along.check(*s, {index++, s->toWorld(local), dir}, {.compare = Compare::Distance});
        }
  along.report();

  // Through the corners where eight cells meet and along the edges where four meet, from random
  // places outside.
  Comparison corners("rays through cell corners and edges");
  const auto boundary = [&](int a) { return b.boundsM[a][rng() % b.boundsM[a].size()]; };
  for (int i = 0; i < 20000; ++i) {
    glm::dvec3 target{boundary(0), boundary(1), boundary(2)};
    if (i % 2 == 1) target[i % 3] = uniform(rng, 0, size[i % 3]);  // on an edge, not a corner
    corners.check(*s, s->rayFromOutside(rng, s->toWorld(target), index++), {.compare = Compare::Distance});
  }
  corners.report();

  // Directions with exact zero components: in a plane of constant coordinate (a boundary or a
  // quarter position), at random angles and along the plane's diagonals.
  Comparison planar("rays with zero direction components");
  for (int i = 0; i < 20000; ++i) {
    const int a = static_cast<int>(rng() % 3), u = (a + 1) % 3, v = (a + 2) % 3;
    glm::dvec3 target{uniform(rng, 0, size.x), uniform(rng, 0, size.y), uniform(rng, 0, size.z)};
    target[a] = lattice[a][rng() % lattice[a].size()];
    glm::dvec3 dir(0.0);
    if (i % 4 == 0) {
      dir[u] = rng() % 2 ? 1.0 : -1.0;
      dir[v] = rng() % 2 ? 1.0 : -1.0;
      target[u] = lattice[u][rng() % lattice[u].size()];  // the diagonal through a lattice line
    } else {
      const double angle = uniform(rng, 0, 2 * std::numbers::pi);
      dir[u] = std::cos(angle);
      dir[v] = std::sin(angle);
    }
    dir = glm::normalize(dir);
    planar.check(*s, {index++, s->toWorld(target - 8.0 * dir), dir}, {.compare = Compare::Distance});
  }
  planar.report();
}

// A flat face, the rays to graze it and the targets on it.
struct GrazedFace {
  const char* name;
  glm::dvec3 normal;          // outward
  glm::dvec3 tangentU, tangentV;
  std::function<glm::dvec3(std::mt19937_64&)> target;  // a local point on the face
  bool descending = false;    // only rays that move down (so that they come from above the target)
};

// Rays nearly parallel to faces, at 1e-3 to 1e-6 rad: a slab top made of many box cells (the ray
// skims across cell boundaries just above solid cells), a tower's side face inside the block, the
// block's own side face (the hit is where the ray enters the root box), and a ramp of wedges whose
// slope continues across cells. Guards against float rounding that lets a ray dip under a face and
// travel inside the solid, or stop a long way early. At such angles a float position error e moves
// the hit by e / angle along the ray, so the distance tolerance is the float position tolerance
// over |n . d| without the floor of random rays (minCosine 0).
TEST(Stress, GrazingRays) {
  Block slab = Block::fromSizes({{{2, 2, 2, 2}, {1, 1, 1, 1}, {2, 2, 2, 2}}});
  for (int x = 0; x < 4; ++x)
    for (int z = 0; z < 4; ++z)
      for (int y = 0; y < 4; ++y)
        if (y < 2 || (x == 1 && z >= 1 && z <= 2)) slab.cell(x, y, z) = Cell::box(static_cast<std::uint16_t>((x + z) % 4));
  // A ramp along x: wedges extruded along x with the right angle at y = 0, z = 0, so the slope
  // y / 2 + z / 5 = 1 runs through four cells of unequal length.
  Block ramp = Block::fromSizes({{{1.5, 2.5, 1.0, 3.0}, {2.0}, {5.0}}});
  for (int x = 0; x < 4; ++x) ramp.cell(x, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::Wedge, 0), 1);
  const auto slabScene = makeScene("slab with tower", oneBlock(slab), glm::dvec3(250.0, 10.0, -75.0));
  const auto rampScene = makeScene("wedge ramp", oneBlock(ramp), glm::dvec3(250.0, 10.0, -75.0));
  ASSERT_TRUE(slabScene && rampScene);

  const glm::dvec3 x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  const glm::dvec3 slope = glm::normalize(glm::dvec3(0, 1 / 2.0, 1 / 5.0));
  const std::vector<std::pair<const Scene*, GrazedFace>> faces{
      {slabScene.get(),
       {"slab top", y, x, z,
        [](std::mt19937_64& rng) {
          glm::dvec3 p{uniform(rng, 0.5, 7.5), 2.0, uniform(rng, 0.5, 7.5)};
          if (p.x > 1.9 && p.x < 4.1 && p.z > 1.9 && p.z < 6.1) p.x = uniform(rng, 4.5, 7.5);  // not under the tower
          return p;
        }}},
      {slabScene.get(),
       {"tower side", x, y, z,
        [](std::mt19937_64& rng) { return glm::dvec3(4.0, uniform(rng, 2.2, 3.8), uniform(rng, 2.2, 5.8)); }, true}},
      {slabScene.get(),
       {"block side", x, y, z,
        [](std::mt19937_64& rng) { return glm::dvec3(8.0, uniform(rng, 0.2, 1.8), uniform(rng, 0.5, 7.5)); }}},
      {rampScene.get(),
       {"wedge ramp", slope, x, glm::normalize(glm::dvec3(0, -2, 5)), [](std::mt19937_64& rng) {
          const double zz = uniform(rng, 0.3, 4.7);
          return glm::dvec3(uniform(rng, 0.3, 7.7), 2.0 * (1.0 - zz / 5.0), zz);
        }}}};
  std::mt19937_64 rng(22);
  long long index = 0;
  for (const auto& [scene, face] : faces) {
    Comparison grazing(std::string("rays grazing the ") + face.name);
    for (int i = 0; i < 10000; ++i) {
      const glm::dvec3 target = face.target(rng);
      const double azimuth = uniform(rng, 0, 2 * std::numbers::pi);
      glm::dvec3 along = std::cos(azimuth) * face.tangentU + std::sin(azimuth) * face.tangentV;
      if (face.descending && along.y > 0) along = -along;
      const double angle = std::pow(10.0, uniform(rng, -6, -3));
      const glm::dvec3 dir = glm::normalize(std::cos(angle) * along - std::sin(angle) * face.normal);
      grazing.check(*scene, {index++, scene->toWorld(target) - 15.0 * dir, dir},
                    {.compare = Compare::Distance, .minCosine = 0});
    }
    grazing.report();
  }
}

// Cameras inside the root block: in empty cells, exactly on cell boundaries (planes, edges,
// corners, the root's faces), inside redirection cells (in the sub-block's empty and solid cells,
// and outside its box), and inside solids. The documented behaviour, which both renderers share:
// the ray starts in the cell that holds the camera (on a boundary, the cell it moves into) and
// tests it from t = 0, so a camera inside a solid sees that solid at distance 0 with the normal
// facing the ray (-dir) and the solid's colour shaded with it. Guards against a caster that only
// starts at the first boundary, or lands on the wrong side of the boundary the camera sits on.
TEST(Stress, CamerasInsideBlocks) {
  Hierarchy h;
  h.materials = kMaterials;
  Block root = Block::fromSizes({{{2.0, 1.5, 2.5}, {1.25, 2.0, 1.5}, {1.75, 2.25, 1.5}}});
  root.cell(0, 0, 0) = Cell::box(0);
  root.cell(2, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::Wedge, 1), 1);
  root.cell(0, 0, 2) = Cell::box(2);
  root.cell(2, 0, 2) = Cell::box(3);
  root.cell(1, 0, 2) = Cell::solidCell(makeSolid(SolidGroup::QuarterCylinder, 6), 1);
  root.cell(2, 2, 2) = Cell::solidCell(makeSolid(SolidGroup::Pyramid, 3), 2);
  root.cell(0, 2, 0) = Cell::solidCell(makeSolid(SolidGroup::SphereOctant, 5), 3);
  root.cell(2, 1, 0) = Cell::box(1);
  root.redirections.push_back({1, {0.5, 0.25, 0.5}, {}, {false, false, false}});
  root.redirections.push_back({1, {0.125, 0.0, 0.25}, {7, 0}, {true, true, true}});
  root.cell(1, 1, 1) = Cell::redirect(0);
  root.cell(0, 1, 1) = Cell::redirect(1);
  h.addBlock(root);
  Block sub = Block::fromSizes({{{0.5, 0.5}, {0.75, 0.75}, {0.5, 0.75}}});
  sub.cell(0, 0, 0) = Cell::box(2);
  sub.cell(1, 1, 1) = Cell::solidCell(makeSolid(SolidGroup::Wedge, 9), 0);
  sub.cell(1, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::QuarterCylinder, 2), 3);
  h.addBlock(sub);
  const auto s = makeScene("cameras inside", h, glm::dvec3(40.0, 0.0, 12.0));
  ASSERT_TRUE(s);
  const Block& b = s->model.blocks[0];
  std::mt19937_64 rng(33);
  long long index = 0;

  const auto randomCell = [&](const std::function<bool(const Cell&)>& wanted) {
    while (true) {
      const glm::ivec3 c(static_cast<int>(rng() % 3), static_cast<int>(rng() % 3), static_cast<int>(rng() % 3));
      if (wanted(b.cell(c.x, c.y, c.z))) return c;
    }
  };
  const auto pointIn = [&](const glm::ivec3& c, double margin) {
    glm::dvec3 p;
    for (int a = 0; a < 3; ++a) p[a] = uniform(rng, b.boundsM[a][c[a]] + margin, b.boundsM[a][c[a] + 1] - margin);
    return p;
  };
  const auto fromCamera = [&](Comparison& comparison, const glm::dvec3& camera) {
    for (int k = 0; k < 8; ++k) comparison.check(*s, {index++, s->toWorld(camera), randomDirection(rng)});
  };

  Comparison empty("cameras in empty cells");
  for (int i = 0; i < 2000; ++i)
    fromCamera(empty, pointIn(randomCell([](const Cell& c) { return c.kind == CellKind::Empty; }), 0.0));
  empty.report();

  Comparison onBoundary("cameras on cell boundaries, edges and corners");
  for (int i = 0; i < 3000; ++i) {
    glm::dvec3 camera = pointIn(randomCell([](const Cell&) { return true; }), 0.0);
    for (int a = 0; a < 3; ++a)
      if (a == i % 3 || rng() % 3 == 0) camera[a] = b.boundsM[a][rng() % b.boundsM[a].size()];
    fromCamera(onBoundary, camera);
  }
  onBoundary.report();

  Comparison redirected("cameras in redirection cells");
  for (int i = 0; i < 3000; ++i)
    fromCamera(redirected, pointIn(randomCell([](const Cell& c) { return c.kind == CellKind::Redirection; }), 0.0));
  redirected.report();

  // Inside solids, at least 1 cm from their surfaces (so that the heuristic's moved boundaries
  // leave the camera inside too).
  Comparison inside("cameras inside solids");
  long long wrong = 0;
  for (int i = 0; i < 3000; ++i) {
    const glm::ivec3 c = randomCell([](const Cell& cell) { return cell.kind == CellKind::Solid; });
    const Cell& cell = b.cell(c.x, c.y, c.z);
    glm::dvec3 camera;
    glm::dvec3 unit;
    const glm::dvec3 lo{b.boundsM[0][c.x], b.boundsM[1][c.y], b.boundsM[2][c.z]};
    const glm::dvec3 size = glm::dvec3{b.boundsM[0][c.x + 1], b.boundsM[1][c.y + 1], b.boundsM[2][c.z + 1]} - lo;
    const auto deepInside = [&] {
      for (const glm::dvec3& offset : {glm::dvec3(0.0), glm::dvec3(0.01, 0, 0), glm::dvec3(-0.01, 0, 0),
                                       glm::dvec3(0, 0.01, 0), glm::dvec3(0, -0.01, 0), glm::dvec3(0, 0, 0.01),
                                       glm::dvec3(0, 0, -0.01)})
        if (!solidContains(cell.solid, unit + offset / size)) return false;
      return true;
    };
    do {
      camera = pointIn(c, 0.01);
      unit = (camera - lo) / size;
    } while (!deepInside());
    const Ray ray{index++, s->toWorld(camera), randomDirection(rng)};
    inside.check(*s, ray);
    const Material& m = s->model.materials[cell.material];
    const auto expected = shade({m.r, m.g, m.b}, -ray.dir, ray.dir);
    for (const Lookup lookup : {Lookup::Exact, Lookup::Heuristic}) {
      const RayResult r = s->cast(ray, lookup);
      if (!r.hit || r.distanceM != 0.0 || glm::dot(r.normal, -ray.dir) < 1 - 1e-6 || r.colour != expected) {
        if (++wrong <= 5)
          ADD_FAILURE() << "a camera inside a solid must see it at distance 0 facing the ray:\n  "
                        << describe(*s, ray, s->exact(ray).result, r, lookup);
      }
    }
  }
  inside.report();
  EXPECT_EQ(wrong, 0);

  // The smallest case of a camera on a boundary: on the face between a box cell and an empty cell,
  // looking into the box at shallower and shallower angles to the face. The box holds the camera,
  // so it is seen at distance 0 facing the ray, whatever the angle. (The caster fails this below
  // about 0.03 rad: its landing probe, a few float ulps of t past the camera, no longer moves the
  // camera off the boundary, so it starts in the empty cell behind, steps into the box at t = 0 and
  // shades it with that boundary's normal. The same rays fail in the tally above.)
  Hierarchy two;
  two.materials = kMaterials;
  Block pair = Block::fromSizes({{{1.0, 1.0}, {1.0}, {1.0}}});
  pair.cell(0, 0, 0) = Cell::box(0);
  two.addBlock(pair);
  const auto face = makeScene("camera on the face of a box", two, glm::dvec3(0.0));
  ASSERT_TRUE(face);
  for (const double across : {-0.5, -0.1, -0.02, -1e-3}) {
    const Ray ray{index++, {1.0, 0.5, 0.5}, glm::normalize(glm::dvec3(across, 0.9, 0.42))};
    const RayResult exact = face->exact(ray).result;
    ASSERT_TRUE(exact.hit && exact.distanceM == 0.0 && glm::dot(exact.normal, -ray.dir) > 1 - 1e-12);
    for (const Lookup lookup : {Lookup::Exact, Lookup::Heuristic}) {
      const RayResult r = face->cast(ray, lookup);
      EXPECT_TRUE(r.hit && r.distanceM == 0.0 && glm::dot(r.normal, -ray.dir) > 1 - 1e-6 && r.colour == exact.colour)
          << describe(*face, ray, exact, r, lookup);
    }
  }
}

// A 500 m root block (the width of a city district) whose 2 m cells redirect to blocks of 1 cm
// cells: a grille of 1 cm slats and, wrapped over a whole 2 m cell, a 4 cm tile of 1 cm solids.
// (One block cannot hold both: the metadata array limits the ratio of block size to cell size, so
// the fine cells live in sub-blocks.) Seen from street level at 3 m, 50 m and 330 m and from
// 2 km away. Guards against losing centimetre detail to the float precision of half-kilometre
// coordinates, beyond what float allows at that scale.
TEST(Stress, CentimetreCellsInHalfKilometreBlocks) {
  Hierarchy h;
  h.materials = kMaterials;
  Block root = Block::fromSizes({{{247.0, 2.0, 2.0, 249.0}, {2.0, 498.0}, {249.0, 2.0, 249.0}}});
  root.redirections.push_back({1, glm::dvec3(0.0), {}, {false, false, false}});
  root.redirections.push_back({2, {0.013, 0.0, 0.007}, {}, {true, true, true}});
  root.cell(1, 0, 1) = Cell::redirect(0);
  root.cell(2, 0, 1) = Cell::redirect(1);
  root.cell(3, 0, 0) = Cell::box(3);  // a district-sized neighbour
  h.addBlock(root);
  // The grille: 200 columns of 1 cm, full-height slats, quarter-round sills and gaps.
  Block grille = Block::fromSizes({{std::vector<double>(200, 0.01), {0.5, 1.5}, {2.0}}});
  for (int i = 0; i < 200; ++i) {
    if (i % 2 == 0) {
      grille.cell(i, 0, 0) = Cell::box(0);
      grille.cell(i, 1, 0) = Cell::box(0);
    } else if (i % 4 == 1) {
      grille.cell(i, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::QuarterCylinder, 2 * 4 + 0), 1);
    }
  }
  h.addBlock(grille);
  Block tile = Block::fromSizes({{{0.01, 0.01, 0.01, 0.01}, {0.01, 0.01}, {0.02}}});
  tile.cell(0, 0, 0) = Cell::box(2);
  tile.cell(2, 1, 0) = Cell::solidCell(makeSolid(SolidGroup::Wedge, 5), 1);
  tile.cell(3, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::SphereOctant, 2), 3);
  h.addBlock(tile);
  const auto s = makeScene("1 cm cells in a 500 m block", h, glm::dvec3(-250.0, 0.0, -250.0));
  ASSERT_TRUE(s);

  // From afar only distances are compared: a float position error e turns the normal of a 1 cm
  // round solid by about sqrt(2 e / 1 cm) near its silhouette, several degrees at 330 m.
  const struct {
    const char* name;
    glm::dvec3 local;
    Compare compare;
  } cameras[] = {{"street level, 3 m", {246.0, 1.7, 246.5}, Compare::Shading},
                 {"street level, 50 m", {200.0, 1.7, 230.0}, Compare::Shading},
                 {"street level, 330 m", {10.0, 1.7, 480.0}, Compare::Distance},
                 {"2 km away", {-1250.0, 400.0, -1000.0}, Compare::Distance}};
  std::mt19937_64 rng(44);
  long long index = 0;
  for (const auto& camera : cameras) {
    Comparison fine(std::string("camera ") + camera.name);
    for (int i = 0; i < 10000; ++i) {
      // Aim at the grille's cell or the wrapped tile's cell.
      const glm::dvec3 cell{i % 3 == 0 ? 249.0 : 247.0, 0.0, 249.0};
      const glm::dvec3 target = cell + glm::dvec3(uniform(rng, 0, 2), uniform(rng, 0, 2), uniform(rng, 0, 2));
      fine.check(*s, rayThrough(index++, s->toWorld(camera.local), s->toWorld(target)), {.compare = camera.compare});
    }
    fine.report();
  }
}

// World coordinates near 10^6 m: the same random hierarchies (random_hierarchy.hpp: every solid,
// rotations, wrapping, shared sub-blocks) and the same rays relative to the root, with the root
// near the world origin and at city-sized offsets. The caster takes the root origin and the rays
// in double and subtracts before going to float, so its accuracy must be the one near the origin:
// the tolerance uses only coordinates relative to the root, and the worst error may not grow.
// Guards against a caster that converts world coordinates to float before subtracting. Distances
// only: the shading of random hierarchies is raycast_accuracy_test's, and its translucent inverse
// solids have slivers at their tangents that float cannot resolve and minThicknessM does not
// remove when the ray meets the same solid again in the cell.
TEST(Stress, WorldCoordinatesNearAMillionMetres) {
  const std::array<glm::dvec3, 4> origins{glm::dvec3(0.0), glm::dvec3(1.0e6, 50.0, -1.0e6),
                                          glm::dvec3(-1.0e6 + 0.3, 1234.567, 7.0e5 + 0.7),
                                          glm::dvec3(3.0e6 + 0.0005, -20.0, 2.5e6)};
  std::vector<Comparison> comparisons;
  for (const glm::dvec3& o : origins) {
    char label[96];
    std::snprintf(label, sizeof label, "root at (%.4f, %.4f, %.4f)", o.x, o.y, o.z);
    comparisons.emplace_back(label);
  }
  for (std::uint64_t seed = 0; seed < 100; ++seed) {
    const Hierarchy h = testing::randomHierarchy(seed);
    std::vector<std::unique_ptr<Scene>> scenes;
    for (const glm::dvec3& o : origins) {
      scenes.push_back(makeScene("random hierarchy " + std::to_string(seed), h, o));
      ASSERT_TRUE(scenes.back());
    }
    std::mt19937_64 rng(seed);
    const Scene& near = *scenes[0];
    for (int i = 0; i < 300; ++i) {
      const glm::dvec3 target = near.rootSize() * glm::dvec3(uniform(rng, 0, 1), uniform(rng, 0, 1), uniform(rng, 0, 1));
      const Ray relative = near.rayFromOutside(rng, target, i);
      for (std::size_t k = 0; k < origins.size(); ++k)
        comparisons[k].check(*scenes[k], {relative.index, origins[k] + relative.origin, relative.dir},
                             {.compare = Compare::Distance});
    }
  }
  for (const Comparison& c : comparisons) c.report();
  for (std::size_t k = 1; k < origins.size(); ++k) {
    EXPECT_LE(comparisons[k].exactLookup().worst(), comparisons[0].exactLookup().worst() + 1.0);
    EXPECT_LE(comparisons[k].heuristicLookup().worst(), comparisons[0].heuristicLookup().worst() + 0.05);
  }
}

}  // namespace
}  // namespace nut::stress
