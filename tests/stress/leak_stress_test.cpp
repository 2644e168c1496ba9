// No ray leaks through a closed solid: hundreds of thousands of rays from outside aimed at points
// inside closed solids built from many cells (box cells, wrapped tiles, rotated and clipped
// sub-blocks, and convex shapes assembled from wedges, pyramids, quarter cylinders and sphere
// octants that meet along seams) must stop at the solid, never pass on to what lies behind. The
// float ray caster (raycast.hpp) is checked in both lookup modes, and every ray is also compared
// with the exact path (exact_path.hpp) with the tolerances of stress_support.hpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "stress_support.hpp"

namespace nut::stress {
namespace {

const std::vector<Material> kMaterials{
    {200, 60, 40, 255, 0}, {60, 160, 90, 255, 0}, {70, 90, 200, 255, 0}, {230, 210, 80, 255, 0}};

// A closed solid and how to aim at its inside.
struct ClosedSolid {
  std::string name;
  Hierarchy h;
  // A point inside the solid at least `margin` from its surface, or on one of its inner seams.
  std::function<glm::dvec3(std::mt19937_64&, double margin)> target;
  // The planes of the inner seams (axis, coordinate), where rays are also laid.
  std::vector<std::pair<int, double>> seams;
  // Whether the solid stays closed with the heuristic's boundaries. Sub-blocks of exactly their
  // cell's size do not: the heuristic moves the cell's faces (by up to D / (512 M)), not the
  // sub-block, which opens slits between it and its neighbours.
  bool closedInHeuristic = true;
};

// The block of a solid filler: n[a] box cells of unequal sizes along each axis.
Block solidBlock(const glm::dvec3& size, const glm::ivec3& n) {
  std::array<std::vector<double>, 3> sizes;
  for (int a = 0; a < 3; ++a) {
    double total = 0;
    for (int i = 0; i < n[a]; ++i) total += 1.0 + 0.3 * i;
    for (int i = 0; i < n[a]; ++i) sizes[a].push_back(size[a] * (1.0 + 0.3 * i) / total);
  }
  Block b = Block::fromSizes(sizes);
  for (std::size_t i = 0; i < b.cells.size(); ++i) b.cells[i] = Cell::box(static_cast<std::uint16_t>(i % kMaterials.size()));
  return b;
}

// The offset that puts the rotated box [0, size] at the cell's minimum corner.
glm::dvec3 fitOffset(const Rotation& rotation, const glm::dvec3& size) {
  const glm::dmat3 r = rotationMatrix(rotation);
  glm::dvec3 lowest(0.0);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 p = r * (size * glm::dvec3(corner & 1, corner >> 1 & 1, corner >> 2 & 1));
    lowest = glm::min(lowest, p);
  }
  return -lowest;
}

// Ways to make a cell solid.
enum class Filler {
  Box,         // a box cell
  Tiles,       // a sub-block of box cells wrapped along all axes, offset (the tiles do not divide the cell)
  QuarterYaw,  // a sub-block 2 cm larger than the cell, turned by a quarter yaw and clipped (a quarter yaw
               // is not an exact quarter turn: cos(pi / 2) is 6e-17 in double)
  Yaw45,       // a sub-block twice the cell's size, turned by 45 degrees and clipped
  NestedTiles, // a sub-block 2 cm larger than the cell, clipped, whose own cells hold wrapped tiles
  CubeFit,     // a sub-block of exactly the cell's size, turned by a cube rotation to fill it
  NestedFit,   // a sub-block of exactly the cell's size whose own cells hold wrapped tiles
};

// A 6 x 6 x 6 block of unequal cells whose inner 4 x 4 x 4 cells are solid, filled in turn by the
// given fillers.
ClosedSolid compositeCube(const std::string& name, const std::vector<Filler>& fillers) {
  ClosedSolid c;
  c.name = name;
  c.h.materials = kMaterials;
  Block root = Block::fromSizes({{{1.0, 0.5, 0.75, 2.0, 0.625, 1.0},
                                  {0.8, 1.5, 0.6, 1.25, 0.9, 1.0},
                                  {1.0, 0.7, 1.3, 0.55, 1.6, 0.9}}});
  c.h.addBlock(Block{});  // the root, set below
  const BlockId tile = c.h.addBlock(solidBlock({0.3, 0.25, 0.35}, {2, 2, 2}));
  const auto nestedTiles = [&](const glm::dvec3& size) {
    Block nested = Block::fromSizes({{{0.4 * size.x, 0.6 * size.x}, {size.y}, {0.5 * size.z, 0.5 * size.z}}});
    nested.redirections.push_back({tile, {0.02, 0.0, 0.13}, {}, {true, true, true}});
    for (Cell& cell : nested.cells) cell = Cell::redirect(0);
    return c.h.addBlock(nested);
  };
  std::size_t next = 0;
  std::mt19937_64 rng(91);
  for (int z = 1; z <= 4; ++z)
    for (int y = 1; y <= 4; ++y)
      for (int x = 1; x <= 4; ++x) {
        const glm::dvec3 size{root.boundsM[0][x + 1] - root.boundsM[0][x], root.boundsM[1][y + 1] - root.boundsM[1][y],
                              root.boundsM[2][z + 1] - root.boundsM[2][z]};
        const glm::dvec3 larger = size + 0.02;
        Redirection r;
        switch (fillers[next++ % fillers.size()]) {
          case Filler::Box:
            root.cell(x, y, z) = Cell::box(static_cast<std::uint16_t>(x % 4));
            continue;
          case Filler::Tiles:
            r = {tile, {0.07, 0.11, -0.05}, {}, {true, true, true}};
            break;
          case Filler::QuarterYaw: {
            const Rotation rotation{0, 16384};
            const glm::dvec3 turned{larger.z, larger.y, larger.x};
            r = {c.h.addBlock(solidBlock(turned, {2, 3, 2})), 0.5 * size - rotationMatrix(rotation) * (0.5 * turned),
                 rotation, {false, false, false}};
            break;
          }
          case Filler::Yaw45: {
            const double side = 2.0 * std::max({size.x, size.y, size.z});
            const Rotation rotation{0, 8192};
            r = {c.h.addBlock(solidBlock(glm::dvec3(side), {3, 2, 3})),
                 0.5 * size - rotationMatrix(rotation) * glm::dvec3(0.5 * side), rotation, {false, false, false}};
            break;
          }
          case Filler::NestedTiles:
            r = {nestedTiles(larger), glm::dvec3(-0.01), {}, {false, false, false}};
            break;
          case Filler::CubeFit: {
            // The target's axes are the cell's axes turned back: its size is |R^T| size.
            const Rotation rotation{static_cast<std::uint8_t>(rng() % 24), 0};
            const glm::dmat3 turn = glm::transpose(rotationMatrix(rotation));
            glm::dvec3 turned;
            for (int a = 0; a < 3; ++a)
              turned[a] = std::abs(turn[0][a]) * size.x + std::abs(turn[1][a]) * size.y + std::abs(turn[2][a]) * size.z;
            r = {c.h.addBlock(solidBlock(turned, {2, 3, 2})), fitOffset(rotation, turned), rotation, {false, false, false}};
            break;
          }
          case Filler::NestedFit:
            r = {nestedTiles(size), glm::dvec3(0.0), {}, {false, false, false}};
            break;
        }
        root.cell(x, y, z) = Cell::redirect(static_cast<std::uint32_t>(root.redirections.size()));
        root.redirections.push_back(r);
      }
  for (int a = 0; a < 3; ++a)
    for (int i = 2; i <= 4; ++i) c.seams.push_back({a, root.boundsM[a][i]});
  const glm::dvec3 lo{root.boundsM[0][1], root.boundsM[1][1], root.boundsM[2][1]};
  const glm::dvec3 hi{root.boundsM[0][5], root.boundsM[1][5], root.boundsM[2][5]};
  c.h.blocks[0] = std::move(root);
  c.target = [lo, hi](std::mt19937_64& r, double margin) {
    glm::dvec3 p;
    for (int a = 0; a < 3; ++a) p[a] = uniform(r, lo[a] + margin, hi[a] - margin);
    return p;
  };
  return c;
}

// A convex solid assembled from 2 x 2 x 2 (or, extruded along one axis, 2 x 2 x n) pieces that all
// have their right-angle corner or edge at the common centre: pyramids make an octahedron, sphere
// octants an ellipsoid, quarter cylinders an elliptic cylinder, wedges a kite prism. Cells are
// unequal, so the pieces meet along the seams with different slopes. A 1 m empty layer surrounds
// them.
enum class Shape { Octahedron, Ellipsoid, Cylinder, KitePrism };

ClosedSolid convexShape(Shape shape) {
  const std::array<std::array<double, 2>, 3> halves{{{0.7, 1.3}, {1.1, 0.6}, {0.9, 1.5}}};  // - and + half-axes
  const int extruded = shape == Shape::Cylinder ? 2 : shape == Shape::KitePrism ? 0 : -1;
  const std::vector<double> extrusion{0.5, 1.0, 0.7};
  std::array<std::vector<double>, 3> sizes;
  for (int a = 0; a < 3; ++a) {
    sizes[a].push_back(1.0);
    if (a == extruded)
      sizes[a].insert(sizes[a].end(), extrusion.begin(), extrusion.end());
    else
      sizes[a].insert(sizes[a].end(), halves[a].begin(), halves[a].end());
    sizes[a].push_back(1.0);
  }
  ClosedSolid c;
  c.h.materials = kMaterials;
  Block b = Block::fromSizes(sizes);
  glm::dvec3 centre;
  for (int a = 0; a < 3; ++a) {
    centre[a] = a == extruded ? 1.0 + 0.5 * (0.5 + 1.0 + 0.7) : 1.0 + halves[a][0];
    if (a != extruded) c.seams.push_back({a, centre[a]});
  }
  const glm::ivec3 n{b.cellCount(0), b.cellCount(1), b.cellCount(2)};
  for (int z = 1; z + 1 < n.z; ++z)
    for (int y = 1; y + 1 < n.y; ++y)
      for (int x = 1; x + 1 < n.x; ++x) {
        // Whether the centre is at the cell's maximum side, per axis.
        const glm::ivec3 low{x == 1, y == 1, z == 1};
        Solid solid;
        switch (shape) {
          case Shape::Octahedron: solid = makeSolid(SolidGroup::Pyramid, low.x | low.y << 1 | low.z << 2); break;
          case Shape::Ellipsoid: solid = makeSolid(SolidGroup::SphereOctant, low.x | low.y << 1 | low.z << 2); break;
          case Shape::Cylinder: solid = makeSolid(SolidGroup::QuarterCylinder, 2 * 4 + (low.x | low.y << 1)); break;
          case Shape::KitePrism: solid = makeSolid(SolidGroup::Wedge, 0 * 4 + (low.y | low.z << 1)); break;
        }
        b.cell(x, y, z) = Cell::solidCell(solid, static_cast<std::uint16_t>((x + y + z) % 4));
      }
  c.name = shape == Shape::Octahedron ? "octahedron of 8 pyramids"
           : shape == Shape::Ellipsoid ? "ellipsoid of 8 sphere octants"
           : shape == Shape::Cylinder  ? "elliptic cylinder of quarter cylinders"
                                       : "kite prism of wedges";
  // The inradius about the centre: the distance to the nearest face (octahedron, kite), or the
  // shortest half-axis (ellipsoid, cylinder), or half the extrusion.
  double inradius = 0.5 * (0.5 + 1.0 + 0.7);
  for (const double a : halves[0])
    for (const double bb : halves[1])
      for (const double cc : halves[2]) {
        switch (shape) {
          case Shape::Octahedron: inradius = std::min(inradius, 1.0 / std::sqrt(1 / (a * a) + 1 / (bb * bb) + 1 / (cc * cc))); break;
          case Shape::Ellipsoid: inradius = std::min({inradius, a, bb, cc}); break;
          case Shape::Cylinder: inradius = std::min({inradius, a, bb}); break;
          case Shape::KitePrism: inradius = std::min(inradius, bb * cc / std::hypot(bb, cc)); break;
        }
      }
  c.h.addBlock(b);
  // A point of the solid (a random piece, a random point of its cell inside it), moved towards the
  // centre: for a convex solid containing the ball of radius r about the centre, the point
  // centre + (1 - mu) (q - centre) lies at least mu r inside.
  c.target = [centre, inradius, n, block = b](std::mt19937_64& r, double margin) {
    while (true) {
      glm::ivec3 cell;
      for (int a = 0; a < 3; ++a) cell[a] = 1 + static_cast<int>(r() % static_cast<std::uint64_t>(n[a] - 2));
      glm::dvec3 lo, size, unit;
      for (int a = 0; a < 3; ++a) {
        lo[a] = block.boundsM[a][cell[a]];
        size[a] = block.boundsM[a][cell[a] + 1] - lo[a];
        unit[a] = uniform(r, 0, 1);
      }
      if (!solidContains(block.cell(cell.x, cell.y, cell.z).solid, unit)) continue;
      const double mu = margin / inradius;
      return centre + (1 - mu) * (lo + unit * size - centre);
    }
  };
  return c;
}

// Closed solids of every construction, hit by 100,000 rays each from random places outside, aimed
// at random points at least a margin inside (1 mm; in heuristic lookup also the largest distance
// the heuristic moves a surface), half of them on an inner seam and a quarter of those with the
// whole ray in the seam's plane. Every ray must hit before it reaches its target point, in both
// lookup modes: a ray that gets further has leaked through a crack between cells, tiles or pieces.
// A leak of the caster where the exact path on the same model (the heuristic model in heuristic
// lookup) stops is a failure; so is any leak of the exact path itself, which means the scene is
// not closed. The exception, counted and printed: sub-blocks of exactly their cell's size are not
// closed with the heuristic's boundaries (ClosedSolid::closedInHeuristic), and rays in or along a
// seam plane pass through the slits there in both renderers. Each ray is also compared with the
// exact path (hit distances and shading).
TEST(Stress, NoLeaksThroughClosedSolids) {
  std::vector<ClosedSolid> solids;
  solids.push_back(compositeCube("composite cube", {Filler::Box, Filler::Tiles, Filler::QuarterYaw, Filler::Box,
                                                    Filler::Yaw45, Filler::NestedTiles}));
  solids.push_back(compositeCube("composite cube of exact fits", {Filler::Box, Filler::CubeFit, Filler::NestedFit}));
  solids.back().closedInHeuristic = false;
  for (const Shape shape : {Shape::Octahedron, Shape::Ellipsoid, Shape::Cylinder, Shape::KitePrism})
    solids.push_back(convexShape(shape));
  std::mt19937_64 rng(92);
  long long index = 0, totalRays = 0;
  for (const ClosedSolid& solid : solids) {
    const auto s = makeScene(solid.name, solid.h, glm::dvec3(2.5e5, 31.0, -6.0e5));
    ASSERT_TRUE(s);
    double displacement = 0;
    for (const glm::dvec3& d : s->delta) displacement = std::max(displacement, d.x + d.y + d.z);
    displacement *= dagDepth(s->model) + 1;
    Comparison comparison(solid.name);
    std::array<long long, 2> leaks{0, 0}, modelLeaks{0, 0};  // per lookup mode
    for (int i = 0; i < 100000; ++i) {
      const Lookup aim = i % 2 == 0 ? Lookup::Exact : Lookup::Heuristic;
      glm::dvec3 target = solid.target(rng, aim == Lookup::Exact ? 1e-3 : 1e-3 + displacement);
      Ray ray = s->rayFromOutside(rng, s->toWorld(target), index++);
      const bool inSeam = i % 8 >= 6;
      if (i % 4 >= 2) {
        const auto [axis, plane] = solid.seams[rng() % solid.seams.size()];
        target[axis] = plane;
        glm::dvec3 from = ray.origin;
        if (inSeam) from[axis] = s->toWorld(target)[axis];
        ray = rayThrough(ray.index, from, s->toWorld(target));
      }
      // A ray in a seam plane meets the solid on an edge, where the normal is either face's.
      comparison.check(*s, ray, {.compare = inSeam ? Compare::Distance : Compare::Shading});
      const double reach = glm::length(s->toWorld(target) - ray.origin);
      const auto leaked = [&](const RayResult& r) { return !r.hit || r.distanceM > reach; };
      for (const Lookup lookup : {Lookup::Exact, Lookup::Heuristic}) {
        if (lookup == Lookup::Heuristic && aim == Lookup::Exact) continue;  // the heuristic needs the larger margin
        const auto mode = static_cast<std::size_t>(lookup == Lookup::Exact ? 0 : 1);
        const Reference exact = s->exact(ray, lookup);
        if (leaked(exact.result)) ++modelLeaks[mode];
        const RayResult cast = s->cast(ray, lookup);
        if (leaked(cast) && !leaked(exact.result) && ++leaks[mode] <= 10)
          ADD_FAILURE() << "a ray passed through the closed solid to a point " << reach << " m away:\n  "
                        << describe(*s, ray, exact.result, cast, lookup);
      }
      ++totalRays;
    }
    comparison.report();
    std::printf("%s: leaks of the caster (where the exact path on the same model stops): %lld in exact lookup, %lld "
                "in heuristic lookup; leaks of the exact path itself: %lld on the model, %lld on the heuristic model "
                "(margin %.4g m in exact lookup, %.4g m in heuristic)\n",
                solid.name.c_str(), leaks[0], leaks[1], modelLeaks[0], modelLeaks[1], 1e-3, 1e-3 + displacement);
    EXPECT_EQ(leaks[0] + leaks[1], 0) << solid.name;
    EXPECT_EQ(modelLeaks[0], 0) << solid.name << ": the scene is not closed";
    if (solid.closedInHeuristic) {
      EXPECT_EQ(modelLeaks[1], 0) << solid.name << ": not closed with the heuristic's boundaries";
    }
  }
  std::printf("%lld rays aimed inside closed solids\n", totalRays);
}

}  // namespace
}  // namespace nut::stress
