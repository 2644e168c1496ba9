// The exact path (exact_path.hpp) checked against answers worked out by hand (hit distances,
// normals and colours of boxes, wedges, wrapped tiles, rotated, clipped and translucent content)
// and, on random hierarchies, against point location along the ray. These tests make it
// trustworthy as the ground truth of the float ray caster's accuracy tests, independently of that
// caster.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include <nut/exact_path.hpp>

#include "random_hierarchy.hpp"

namespace nut {
namespace {

constexpr double kTolerance = 1e-9;  // metres: double rounding on coordinates near 1e6 m is ~1e-10

// The shading formula of docs/RENDERING.md, written out here rather than taken from nut::shade.
std::array<std::uint8_t, 3> shadeByHand(const Material& m, glm::dvec3 n, const glm::dvec3& dir) {
  if (glm::dot(n, dir) > 0) n = -n;
  const glm::dvec3 light = glm::normalize(glm::dvec3(0.35, 0.8, 0.5));
  const double f = 0.35 + 0.65 * std::max(0.0, glm::dot(n, light));
  return {static_cast<std::uint8_t>(std::lround(m.r * f)), static_cast<std::uint8_t>(std::lround(m.g * f)),
          static_cast<std::uint8_t>(std::lround(m.b * f))};
}

glm::dvec3 axisVector(int axis, double sign = 1.0) {
  glm::dvec3 v(0.0);
  v[axis] = sign;
  return v;
}

// A hierarchy whose root is `root`; further blocks are added by the caller.
Hierarchy withRoot(Block root, std::vector<Material> materials) {
  Hierarchy h;
  h.materials = std::move(materials);
  h.addBlock(std::move(root));
  return h;
}

const Material kRed{200, 60, 40, 255, 0};
const Material kBlue{30, 90, 220, 255, 0};
const glm::dvec3 kFarOrigin{1.0e6 + 0.25, -3.5, -2.0e6 + 0.125};

TEST(ExactPath, SingleBoxFromEverySide) {
  Block b = Block::fromSizes({{{2.0}, {3.0}, {4.0}}});
  b.cell(0, 0, 0) = Cell::box(0);
  const Hierarchy h = withRoot(b, {kRed});
  const glm::dvec3 size{2.0, 3.0, 4.0};
  for (int axis = 0; axis < 3; ++axis) {
    for (const double side : {-1.0, 1.0}) {
      // A point F on the face (away from its edges) and a slanted ray entering through it.
      glm::dvec3 face = 0.3 * size;
      face[axis] = side > 0 ? size[axis] : 0.0;
      const glm::dvec3 dir = glm::normalize(axisVector(axis, -side) + 0.3 * axisVector((axis + 1) % 3) -
                                            0.2 * axisVector((axis + 2) % 3));
      const glm::dvec3 origin = kFarOrigin + face - 7.5 * dir;
      const RayResult r = traceExact(h, kFarOrigin, origin, dir);
      ASSERT_TRUE(r.hit) << "axis " << axis << " side " << side;
      EXPECT_NEAR(r.distanceM, 7.5, kTolerance);
      EXPECT_EQ(r.normal, axisVector(axis, side));
      EXPECT_EQ(r.colour, shadeByHand(kRed, axisVector(axis, side), dir));
      EXPECT_FALSE(r.capped);

      // The same ray moved sideways past the face misses; so does the ray turned around.
      const glm::dvec3 beside = origin + 1.5 * size[(axis + 1) % 3] * axisVector((axis + 1) % 3);
      const RayResult miss = traceExact(h, kFarOrigin, beside, dir);
      EXPECT_FALSE(miss.hit);
      EXPECT_EQ(miss.colour, kBackground);
      EXPECT_FALSE(traceExact(h, kFarOrigin, origin, -dir).hit);
    }
  }
}

TEST(ExactPath, RayStartingInsideASolidHitsAtItsOrigin) {
  Block b = Block::fromSizes({{{2.0}, {3.0}, {4.0}}});
  b.cell(0, 0, 0) = Cell::box(0);
  const Hierarchy h = withRoot(b, {kRed});
  const glm::dvec3 dir = glm::normalize(glm::dvec3(1, 2, 3));
  const RayResult r = traceExact(h, kFarOrigin, kFarOrigin + glm::dvec3(1, 1, 1), dir);
  ASSERT_TRUE(r.hit);
  EXPECT_EQ(r.distanceM, 0.0);
  EXPECT_NEAR(glm::dot(r.normal, -dir), 1.0, 1e-12);
}

TEST(ExactPath, StretchedWedgeHasTheSlopeOfItsCell) {
  // Wedge along z with its right-angle edge at x = 0, y = 0: x/4 + y/2 <= 1 in a 4 x 2 x 1 cell,
  // a slope whose normal is (1/4, 1/2, 0) normalised.
  Block b = Block::fromSizes({{{4.0}, {2.0}, {1.0}}});
  b.cell(0, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::Wedge, 2 * 4 + 0), 0);
  const Hierarchy h = withRoot(b, {kRed});
  const glm::dvec3 dir{0, -1, 0};
  const RayResult r = traceExact(h, glm::dvec3(0.0), glm::dvec3(2.0, 5.0, 0.5), dir);
  ASSERT_TRUE(r.hit);
  EXPECT_NEAR(r.distanceM, 5.0 - 1.0, kTolerance);  // surface at y = 2 (1 - 2/4) = 1
  const glm::dvec3 expected = glm::normalize(glm::dvec3(0.25, 0.5, 0.0));
  EXPECT_NEAR(glm::length(r.normal - expected), 0.0, 1e-12);
  EXPECT_EQ(r.colour, shadeByHand(kRed, expected, dir));
  // Along -z at x = 3 the slope is at y = 0.5: below it the ray meets the z = 1 face, above it nothing.
  const RayResult below = traceExact(h, glm::dvec3(0.0), glm::dvec3(3.0, 0.25, 5.0), glm::dvec3(0, 0, -1));
  ASSERT_TRUE(below.hit);
  EXPECT_NEAR(below.distanceM, 4.0, kTolerance);
  EXPECT_EQ(below.normal, glm::dvec3(0, 0, 1));
  EXPECT_FALSE(traceExact(h, glm::dvec3(0.0), glm::dvec3(3.0, 0.75, 5.0), glm::dvec3(0, 0, -1)).hit);
}

// Root: one 10 m cell redirecting to a 2 m block whose first 1 m cell is a box, so the solid
// occupies [2k + offset, 2k + 1 + offset] along each wrapped axis.
Hierarchy tiledCubes(const glm::dvec3& offset, std::array<bool, 3> wrap) {
  Block root = Block::fromSizes({{{10.0}, {10.0}, {10.0}}});
  root.redirections.push_back({1, offset, {}, wrap});
  root.cell(0, 0, 0) = Cell::redirect(0);
  Hierarchy h = withRoot(root, {kRed});
  Block tile = Block::fromSizes({{{1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}}});
  tile.cell(0, 0, 0) = Cell::box(0);
  h.addBlock(tile);
  return h;
}

TEST(ExactPath, WrappedTilesRepeatWithTheTargetSize) {
  const Hierarchy h = tiledCubes(glm::dvec3(0.0), {true, true, true});
  const glm::dvec3 down{0, -1, 0};
  // From above at (x, z): a tile column where both x and z are in a solid interval, else a gap.
  for (int ix = 0; ix < 20; ++ix) {
    for (int iz = 0; iz < 20; ++iz) {
      const double x = 0.25 + 0.5 * ix, z = 0.25 + 0.5 * iz;
      const bool solid = std::fmod(x, 2.0) < 1.0 && std::fmod(z, 2.0) < 1.0;
      const RayResult r = traceExact(h, glm::dvec3(0.0), glm::dvec3(x, 12.0, z), down);
      ASSERT_EQ(r.hit, solid) << "x " << x << " z " << z;
      if (solid) {
        EXPECT_NEAR(r.distanceM, 3.0, kTolerance);  // top tile: [8, 9]
        EXPECT_EQ(r.normal, glm::dvec3(0, 1, 0));
      }
    }
  }
  // A diagonal ray through the gaps and tiles: entering at (0, 0.5, 0.5) along +x first meets x = 0.
  const RayResult along = traceExact(h, glm::dvec3(0.0), glm::dvec3(-5.0, 0.5, 0.5), glm::dvec3(1, 0, 0));
  ASSERT_TRUE(along.hit);
  EXPECT_NEAR(along.distanceM, 5.0, kTolerance);
  // From inside a gap row (y in [1, 2]) nothing is ever met.
  EXPECT_FALSE(traceExact(h, glm::dvec3(0.0), glm::dvec3(-5.0, 1.5, 0.5), glm::dvec3(1, 0, 0)).hit);
}

TEST(ExactPath, WrapOffsetAndUnwrappedAxis) {
  // Offset 0.5 along x (tiles at [0.5, 1.5] + 2k); y does not wrap: only target y in [0, 2) exists.
  const Hierarchy h = tiledCubes(glm::dvec3(0.5, 0.0, 0.0), {true, false, true});
  const RayResult r = traceExact(h, glm::dvec3(0.0), glm::dvec3(-5.0, 0.5, 0.5), glm::dvec3(1, 0, 0));
  ASSERT_TRUE(r.hit);
  EXPECT_NEAR(r.distanceM, 5.5, kTolerance);
  EXPECT_EQ(r.normal, glm::dvec3(-1, 0, 0));
  // From above: the only layer is y in [0, 1].
  const RayResult top = traceExact(h, glm::dvec3(0.0), glm::dvec3(4.75, 12.0, 6.5), glm::dvec3(0, -1, 0));
  ASSERT_TRUE(top.hit);
  EXPECT_NEAR(top.distanceM, 11.0, kTolerance);
  // x = 0.25 lies in target x = -0.25 = 1.75 (mod 2): a gap.
  EXPECT_FALSE(traceExact(h, glm::dvec3(0.0), glm::dvec3(0.25, 12.0, 0.5), glm::dvec3(0, -1, 0)).hit);
}

// Root: one 20 m cell redirecting, with rotation `rotation` and offset (10, 10, 10), to a 3 x 4 x 5
// block of 2 x 2 x 2 cells whose only solid is the corner cell (1, 1, 1) = [1, 3] x [1, 4] x [1, 5].
Hierarchy rotatedCorner(Rotation rotation) {
  Block root = Block::fromSizes({{{20.0}, {20.0}, {20.0}}});
  root.redirections.push_back({1, glm::dvec3(10.0), rotation, {false, false, false}});
  root.cell(0, 0, 0) = Cell::redirect(0);
  Hierarchy h = withRoot(root, {kRed});
  Block target = Block::fromSizes({{{1.0, 2.0}, {1.0, 3.0}, {1.0, 4.0}}});
  target.cell(1, 1, 1) = Cell::box(0);
  h.addBlock(target);
  return h;
}

TEST(ExactPath, EveryCubeRotationPlacesTheCornerWhereTheMatrixSays) {
  const glm::dvec3 lo{1, 1, 1}, hi{3, 4, 5};
  const glm::dvec3 emptyCorner{0.5, 0.5, 0.5};  // centre of cell (0, 0, 0), which is empty
  for (int index = 0; index < 24; ++index) {
    const Hierarchy h = rotatedCorner({static_cast<std::uint8_t>(index), 0});
    const glm::dmat3 m(cubeRotationMatrix(index));
    // The solid's world box: the offset plus the rotated corners (a signed permutation maps the
    // box to a box whose corners are images of corners).
    const glm::dvec3 a = glm::dvec3(10.0) + m * lo, b = glm::dvec3(10.0) + m * hi;
    const glm::dvec3 boxMin = glm::min(a, b), boxMax = glm::max(a, b);
    const glm::dvec3 centre = 0.5 * (boxMin + boxMax);
    for (int axis = 0; axis < 3; ++axis) {
      for (const double side : {-1.0, 1.0}) {
        const glm::dvec3 dir = axisVector(axis, -side);
        const glm::dvec3 origin = centre - 30.0 * dir;
        const RayResult r = traceExact(h, kFarOrigin, kFarOrigin + origin, dir);
        ASSERT_TRUE(r.hit) << "rotation " << index << " axis " << axis << " side " << side;
        const double face = side > 0 ? boxMax[axis] : boxMin[axis];
        EXPECT_NEAR(r.distanceM, std::abs(face - origin[axis]), kTolerance) << "rotation " << index;
        EXPECT_EQ(r.normal, axisVector(axis, side)) << "rotation " << index;
        // Through the rotated centre of the empty corner cell along the same axis: nothing.
        const glm::dvec3 empty = glm::dvec3(10.0) + m * emptyCorner;
        EXPECT_FALSE(traceExact(h, kFarOrigin, kFarOrigin + empty - 30.0 * dir, dir).hit)
            << "rotation " << index << " axis " << axis;
      }
    }
  }
}

TEST(ExactPath, YawQuarterTurnEqualsTheCubeRotation) {
  // A quarter turn counter-clockwise about +y takes x to -z and z to x (docs/FORMAT.md).
  const glm::dmat3 quarter(glm::dvec3(0, 0, -1), glm::dvec3(0, 1, 0), glm::dvec3(1, 0, 0));
  int cube = -1;
  for (int i = 0; i < 24; ++i)
    if (glm::dmat3(cubeRotationMatrix(i)) == quarter) cube = i;
  ASSERT_GE(cube, 0);
  const Hierarchy yawed = rotatedCorner({0, 16384});
  const Hierarchy cubed = rotatedCorner({static_cast<std::uint8_t>(cube), 0});
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    // Rays from a ring around the solid (world box [11, 15] x [11, 14] x [7, 9]) towards points
    // spread over that box and a margin around it.
    const double angle = 0.1 * i;
    const glm::dvec3 origin{13.0 + 25.0 * std::cos(angle), 4.0 + 0.03 * i, 8.0 + 25.0 * std::sin(angle)};
    const glm::dvec3 aim{10.0 + 6.0 * std::fmod(0.37 * i, 1.0), 10.0 + 5.0 * std::fmod(0.61 * i, 1.0),
                         6.0 + 4.0 * std::fmod(0.83 * i, 1.0)};
    const glm::dvec3 dir = glm::normalize(aim - origin);
    const RayResult a = traceExact(yawed, glm::dvec3(0.0), origin, dir);
    const RayResult b = traceExact(cubed, glm::dvec3(0.0), origin, dir);
    ASSERT_EQ(a.hit, b.hit) << "ray " << i;
    if (!a.hit) continue;
    ++hits;
    EXPECT_NEAR(a.distanceM, b.distanceM, 1e-9) << "ray " << i;
    EXPECT_NEAR(glm::length(a.normal - b.normal), 0.0, 1e-9) << "ray " << i;
    EXPECT_EQ(a.colour, b.colour) << "ray " << i;
  }
  EXPECT_GT(hits, 100);  // the rays really do test the solid
}

// Root: two 2 m cells along x; cell 0 shows a 5 x 2 x 2 box block that reaches into cell 1's space.
Hierarchy targetLargerThanItsCell() {
  Block root = Block::fromSizes({{{2.0, 2.0}, {2.0}, {2.0}}});
  root.redirections.push_back({1, glm::dvec3(0.0), {}, {false, false, false}});
  root.cell(0, 0, 0) = Cell::redirect(0);
  Hierarchy h = withRoot(root, {kRed});
  Block big = Block::fromSizes({{{5.0}, {2.0}, {2.0}}});
  big.cell(0, 0, 0) = Cell::box(0);
  h.addBlock(big);
  return h;
}

TEST(ExactPath, TargetLargerThanItsCellIsClipped) {
  // Cell 1's space is empty and must stay empty.
  const Hierarchy h = targetLargerThanItsCell();
  const glm::dvec3 down{0, 0, -1};
  EXPECT_FALSE(traceExact(h, kFarOrigin, kFarOrigin + glm::dvec3(3.0, 1.0, 10.0), down).hit);
  const RayResult inside = traceExact(h, kFarOrigin, kFarOrigin + glm::dvec3(1.0, 1.0, 10.0), down);
  ASSERT_TRUE(inside.hit);
  EXPECT_NEAR(inside.distanceM, 8.0, kTolerance);
  // From +x the ray crosses the empty cell and meets the clip face x = 2, facing +x.
  const glm::dvec3 dir = glm::normalize(glm::dvec3(-1.0, 0.1, 0.0));
  const glm::dvec3 origin = kFarOrigin + glm::dvec3(2.0, 1.0, 1.0) - 8.0 * dir;
  const RayResult clipped = traceExact(h, kFarOrigin, origin, dir);
  ASSERT_TRUE(clipped.hit);
  EXPECT_NEAR(clipped.distanceM, 8.0, kTolerance);
  EXPECT_EQ(clipped.normal, glm::dvec3(1, 0, 0));
  EXPECT_EQ(clipped.colour, shadeByHand(kRed, glm::dvec3(1, 0, 0), dir));
}

TEST(ExactPath, TranslucentCellCompositesFrontToBack) {
  // Along -z: a half-opaque blue cell in front of an opaque red one.
  Block b = Block::fromSizes({{{1.0}, {1.0}, {1.0, 1.0}}});
  b.cell(0, 0, 0) = Cell::box(0);
  b.cell(0, 0, 1) = Cell::box(1);
  Material glass = kBlue;
  glass.opacity = 128;
  const Hierarchy h = withRoot(b, {kRed, glass});
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.1, -0.2, -1.0));
  const glm::dvec3 front = glm::dvec3(0.5, 0.5, 2.0);
  const RayResult r = traceExact(h, glm::dvec3(0.0), front - 4.0 * dir, dir);
  ASSERT_TRUE(r.hit);
  EXPECT_NEAR(r.distanceM, 4.0 + 1.0 / -dir.z, kTolerance);  // the opaque face is at z = 1
  const double alpha = 128.0 / 255.0;
  const auto glassColour = shadeByHand(glass, glm::dvec3(0, 0, 1), dir);
  const auto redColour = shadeByHand(kRed, glm::dvec3(0, 0, 1), dir);
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(r.colour[i], std::lround(alpha * glassColour[i] + (1 - alpha) * redColour[i]))
        << "channel " << i;

  // Glass alone: composited over the background, and no hit.
  Block pane = Block::fromSizes({{{1.0}, {1.0}, {1.0}}});
  pane.cell(0, 0, 0) = Cell::box(0);
  const RayResult alone = traceExact(withRoot(pane, {glass}), glm::dvec3(0.0), glm::dvec3(0.5, 0.5, 5.0),
                                     glm::dvec3(0, 0, -1));
  EXPECT_FALSE(alone.hit);
  const auto paneColour = shadeByHand(glass, glm::dvec3(0, 0, 1), glm::dvec3(0, 0, -1));
  for (std::size_t i = 0; i < 3; ++i)
    EXPECT_EQ(alone.colour[i], std::lround(alpha * paneColour[i] + (1 - alpha) * kBackground[i]));
}

TEST(ExactPath, SliversThinnerThanTheMinimumThicknessAreIgnored) {
  // An inverse quarter cylinder along x with its edge at z = 1: y^2 + (1 - z)^2 >= 1. Its top face
  // y = 1 belongs to the solid, but at z = 0.99 the solid below it is only 5e-5 m thick.
  Block b = Block::fromSizes({{{1.0}, {1.0}, {1.0}}});
  b.cell(0, 0, 0) = Cell::solidCell(makeSolid(SolidGroup::InverseQuarterCylinder, 0 * 4 + 2), 0);
  const Hierarchy h = withRoot(b, {kRed});
  const glm::dvec3 origin{0.5, 5.0, 0.99}, down{0, -1, 0};
  const RayResult sliver = traceExact(h, glm::dvec3(0.0), origin, down);
  ASSERT_TRUE(sliver.hit);
  EXPECT_NEAR(sliver.distanceM, 4.0, kTolerance);
  EXPECT_EQ(sliver.normal, glm::dvec3(0, 1, 0));
  EXPECT_TRUE(traceExact(h, glm::dvec3(0.0), origin, down, {.minThicknessM = 1e-5}).hit);
  EXPECT_FALSE(traceExact(h, glm::dvec3(0.0), origin, down, {.minThicknessM = 1e-4}).hit);
  // A thick part of the same solid stays: at z = 0.5 it spans y in [0.866, 1].
  EXPECT_TRUE(traceExact(h, glm::dvec3(0.0), glm::dvec3(0.5, 5.0, 0.5), down, {.minThicknessM = 0.1}).hit);
}

TEST(ExactPath, PathologicalTilingAndDepthAreCapped) {
  // A 0.01 mm tile in a 10 m cell: 10^6 copies per axis would have to be visited.
  Block root = Block::fromSizes({{{10.0}, {10.0}, {10.0}}});
  root.redirections.push_back({1, glm::dvec3(0.0), {}, {true, true, true}});
  root.cell(0, 0, 0) = Cell::redirect(0);
  Hierarchy h = withRoot(root, {kRed});
  Block tile = Block::fromSizes({{{1e-5}, {1e-5}, {1e-5}}});
  h.addBlock(tile);  // empty: the ray would go all the way through
  const glm::dvec3 dir = glm::normalize(glm::dvec3(1, 1, 1));
  const RayResult r = traceExact(h, glm::dvec3(0.0), glm::dvec3(-1.0), dir);
  EXPECT_TRUE(r.capped);
  EXPECT_FALSE(r.hit);
  EXPECT_EQ(r.colour, kCappedColour);
  // The same scene with the redirection one level too deep for maxDepth = 0.
  const RayResult shallow = traceExact(h, glm::dvec3(0.0), glm::dvec3(-1.0), dir, {.maxDepth = 0});
  EXPECT_TRUE(shallow.capped);
}

TEST(ExactPath, ReportsTheSurfaceForErrorBounds) {
  const Hierarchy h = rotatedCorner({5, 0});
  const glm::dmat3 m(cubeRotationMatrix(5));
  const glm::dvec3 dir = glm::normalize(glm::dvec3(0.2, -1.0, 0.1));
  const glm::dvec3 aim = glm::dvec3(10.0) + m * glm::dvec3(2.0, 2.5, 3.0);  // the solid's centre
  ExactSurface surface;
  const RayResult r = traceExact(h, glm::dvec3(0.0), aim - 20.0 * dir, dir, {.surface = &surface});
  ASSERT_TRUE(r.hit);
  // A face of the solid's cell in block 1, below the root's cell: both blocks are on the path.
  ASSERT_EQ(surface.path.size(), 2u);
  EXPECT_EQ(surface.path[0].block, 0u);
  EXPECT_EQ(surface.path[0].normal, r.normal);
  EXPECT_EQ(surface.path[1].block, 1u);
  EXPECT_NEAR(glm::length(m * surface.path[1].normal - r.normal), 0.0, 1e-12);
  EXPECT_LT(glm::dot(r.normal, dir), 0.0);
}

TEST(ExactPath, ReportsAClipFaceAsTheSurfaceOfTheClippingBlock) {
  // The clip face x = 2 is a boundary of the root.
  const Hierarchy h = targetLargerThanItsCell();
  ExactSurface surface;
  const RayResult r = traceExact(h, glm::dvec3(0.0), glm::dvec3(10.0, 1.0, 1.0), glm::dvec3(-1, 0, 0),
                                 {.surface = &surface});
  ASSERT_TRUE(r.hit);
  ASSERT_EQ(surface.path.size(), 1u);
  EXPECT_EQ(surface.path[0].block, 0u);
  EXPECT_EQ(surface.path[0].normal, glm::dvec3(1, 0, 0));
}

// Whether the point p of block b's frame lies inside an opaque solid: point location by the model's
// semantics alone (wrap by modulo, linear search for the cell, solidContains), with nothing in
// common with the exact path's interval walk.
bool insideOpaque(const Hierarchy& h, BlockId b, glm::dvec3 p, const std::array<bool, 3>& wrap) {
  const Block& block = h.blocks[b];
  glm::ivec3 cell(0);
  glm::dvec3 cellMin(0.0), cellSize(0.0);
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = block.boundsM[a];
    if (wrap[a]) p[a] -= std::floor(p[a] / bounds.back()) * bounds.back();
    if (p[a] < 0 || p[a] >= bounds.back()) return false;
    while (p[a] >= bounds[static_cast<std::size_t>(cell[a]) + 1]) ++cell[a];
    cellMin[a] = bounds[static_cast<std::size_t>(cell[a])];
    cellSize[a] = bounds[static_cast<std::size_t>(cell[a]) + 1] - cellMin[a];
  }
  const Cell& c = block.cell(cell.x, cell.y, cell.z);
  if (c.kind == CellKind::Solid)
    return h.materials[c.material].opacity == 255 && solidContains(c.solid, (p - cellMin) / cellSize);
  if (c.kind == CellKind::Redirection) {
    const Redirection& r = block.redirections[c.redirection];
    const glm::dmat3 inverse = glm::transpose(rotationMatrix(r.rotation));
    return insideOpaque(h, r.target, inverse * (p - cellMin - r.offsetM), r.wrap);
  }
  return false;
}

TEST(ExactPath, RandomHierarchiesAgreeWithPointLocation) {
  // Along every ray, sampled points before the hit are outside every opaque solid, and the point
  // just past the hit is inside one. (Sampling cannot see solids thinner than its step, so this
  // checks that no thick solid is skipped and that every hit is real.)
  int hits = 0;
  for (std::uint64_t seed = 100; seed < 200; ++seed) {
    const Hierarchy h = testing::randomHierarchy(seed);
    const glm::dvec3 size = h.blocks[h.root].sizeM();
    const double scale = glm::length(size);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < 40; ++i) {
      const glm::dvec3 origin = size * glm::dvec3(unit(rng), unit(rng), unit(rng)) +
                                scale * glm::dvec3(unit(rng) - 0.5, unit(rng) - 0.5, 2.0);
      const glm::dvec3 dir = glm::normalize(size * glm::dvec3(unit(rng), unit(rng), unit(rng)) - origin);
      const glm::dvec3 world = kFarOrigin + origin;
      // The ray actually traced, whose origin is rounded near 1e6 m, relative to the root.
      const glm::dvec3 local = world - kFarOrigin;
      const RayResult r = traceExact(h, kFarOrigin, world, dir);
      ASSERT_FALSE(r.capped);
      const double end = r.hit ? r.distanceM : 4.0 * scale;
      for (int k = 0; k < 2000; ++k) {
        const double t = end * (k + 0.5) / 2000 * (1 - 1e-9);
        ASSERT_FALSE(insideOpaque(h, h.root, local + t * dir, {false, false, false}))
            << "seed " << seed << " ray " << i << ": solid at t = " << t << " before the hit at " << end;
      }
      if (!r.hit) continue;
      ++hits;
      EXPECT_TRUE(insideOpaque(h, h.root, local + (r.distanceM + 1e-9 * scale) * dir, {false, false, false}))
          << "seed " << seed << " ray " << i << ": nothing just past the hit at " << r.distanceM
          << ", origin " << local.x << " " << local.y << " " << local.z << " dir " << dir.x << " " << dir.y
          << " " << dir.z;
    }
  }
  EXPECT_GT(hits, 1000);
}

TEST(ExactPath, RandomHierarchiesGiveConsistentResults) {
  // Sanity over every feature at once: hits lie inside the root box and face the ray.
  int hits = 0;
  for (std::uint64_t seed = 0; seed < 40; ++seed) {
    const Hierarchy h = testing::randomHierarchy(seed);
    const glm::dvec3 size = h.blocks[h.root].sizeM();
    for (int i = 0; i < 50; ++i) {
      const double angle = 0.7 * i;
      const glm::dvec3 away{std::cos(angle), 0.3, std::sin(angle)};
      const glm::dvec3 origin = 0.5 * size + 2.0 * glm::length(size) * away;
      const glm::dvec3 dir = glm::normalize(size * glm::dvec3(0.02 * i, 0.5, 1.0 - 0.02 * i) - origin);
      const RayResult r = traceExact(h, glm::dvec3(0.0), origin, dir);
      ASSERT_FALSE(r.capped) << "seed " << seed << " ray " << i;
      EXPECT_GT(r.iterations, 0) << "seed " << seed << " ray " << i;
      if (!r.hit) continue;
      ++hits;
      const glm::dvec3 p = origin + r.distanceM * dir;
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(p[a], -1e-9 * glm::length(size)) << "seed " << seed << " ray " << i;
        EXPECT_LE(p[a], size[a] * (1 + 1e-9)) << "seed " << seed << " ray " << i;
      }
      EXPECT_LE(glm::dot(r.normal, dir), 0.0);
      EXPECT_NEAR(glm::length(r.normal), 1.0, 1e-9);
    }
  }
  EXPECT_GT(hits, 500);
}

}  // namespace
}  // namespace nut
