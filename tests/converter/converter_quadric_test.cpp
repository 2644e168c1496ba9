// Quarter-cylinder cells of the mesh converter (converter/solid.hpp): a box building with one and
// with four round vertical corners (radius 1 m, 32 segments) converts with each corner as
// QuarterCylinder cells, over 99 % of its surface as NUT, no corner face in the complementary mesh,
// and renders like its source (at least 99 % of the pixels of every view within 8/255; diff images
// in the test output folder, converter_quadric/, when not). Corners that are no quarter cylinder (a
// radius shrinking with height, a wavy arc) stay in the complementary mesh; bevels of two or four
// facets become wedge cells. Corners whose
// cross-section window recesses cut (the grid is global) become sub-blocks of their own, and so
// do the house sample's round corners and drum. A hemispherical dome on a box's roof converts as
// four SphereOctant cells (sub-blocks where a chimney's boundaries cut them), a flatter cap or a
// wavy dome stays in the complementary mesh, and so does nothing of the house's dome.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <nut/solids.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

using testing::cellsOf;
using testing::nutFraction;

constexpr double W = 10, H = 6, D = 8;  // x, y (up), z
constexpr int kSegments = 32;

// Radius of a corner's arc at angle t (0..1 along the arc) and height y.
using Radius = std::function<double(double t, double y)>;

// The box [0, W] x [0, H] x [0, D] with its four vertical corners rounded by `segments` facets
// each (a null radius keeps the corner sharp): corner c lies at +x+z, -x+z, -x-z, +x-z for
// c = 0..3; every face points outwards.
// One material: the 1 m strips along the walls that the corners' boundaries cut would show the
// wall's material on the roof (a cell has one material, and a roof strip a sixth of the wall's area
// is below the share that separates materials), which is not what these tests are about.
TriangleMesh roundedBox(const std::array<Radius, 4>& corners, int segments = kSegments) {
  TriangleMesh mesh;
  mesh.name = "rounded";
  mesh.materials = {Material{220, 200, 170}};
  mesh.materialNames = {"wall"};
  // The footprint, counter-clockwise from +x towards +z, at both heights.
  std::array<std::vector<glm::dvec3>, 2> rings;
  for (int level = 0; level < 2; ++level) {
    const double y = level * H;
    for (int c = 0; c < 4; ++c) {
      const double sx = c == 0 || c == 3 ? 1 : -1, sz = c < 2 ? 1 : -1;
      const glm::dvec2 box(sx > 0 ? W : 0, sz > 0 ? D : 0);
      if (!corners[static_cast<std::size_t>(c)]) {
        rings[static_cast<std::size_t>(level)].emplace_back(box.x, y, box.y);
        continue;
      }
      for (int i = 0; i <= segments; ++i) {
        const double t = static_cast<double>(i) / segments, angle = 0.5 * std::numbers::pi * (c + t);
        const double r = corners[static_cast<std::size_t>(c)](t, y);
        const double r0 = corners[static_cast<std::size_t>(c)](0.0, y);  // the axis stays put at each height
        rings[static_cast<std::size_t>(level)].emplace_back(box.x - sx * r0 + r * std::cos(angle), y, box.y - sz * r0 + r * std::sin(angle));
      }
    }
  }
  const auto n = static_cast<std::uint32_t>(rings[0].size());
  for (const auto& ring : rings) mesh.positions.insert(mesh.positions.end(), ring.begin(), ring.end());
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangleMaterial.push_back(0);
  };
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    add(i, n + j, j);
    add(i, n + i, n + j);
  }
  // Caps as fans from the centre (the footprint is star-shaped about it).
  const auto bottom = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.emplace_back(W / 2, 0, D / 2);
  mesh.positions.emplace_back(W / 2, H, D / 2);
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    add(bottom, i, j);
    add(bottom + 1, n + j, n + i);
  }
  return mesh;
}

const Radius kRound = [](double, double) { return 1.0; };

// Two triangles for the quad p0 p1 p2 p3 (a convex loop), turned to face along `normal`.
void addQuad(TriangleMesh& mesh, const std::array<glm::dvec3, 4>& p, const glm::dvec3& normal) {
  const bool flip = glm::dot(glm::cross(p[1] - p[0], p[2] - p[0]), normal) < 0;
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), p.begin(), p.end());
  for (const std::array<std::uint32_t, 3> t : {std::array<std::uint32_t, 3>{0, 1, 2}, std::array<std::uint32_t, 3>{0, 2, 3}}) {
    mesh.triangles.push_back(flip ? std::array<std::uint32_t, 3>{base + t[0], base + t[2], base + t[1]}
                                  : std::array<std::uint32_t, 3>{base + t[0], base + t[1], base + t[2]});
    mesh.triangleMaterial.push_back(0);
  }
}

// The rounded box with a window recess (1.5 to 3.5 m high, 2 m wide, in the middle) in each
// straight wall, 0.3, 0.2, 0.25 and 0.14 m deep in the +z, -z, +x and -x walls: each recess's back
// is a boundary that runs through the two corners beside it, so no corner is one cell across.
TriangleMesh roundedBoxWithRecesses() {
  TriangleMesh mesh = roundedBox({kRound, kRound, kRound, kRound});
  // The walls' own quads (every corner lies on the wall's plane) give way to walls with a hole.
  std::vector<std::array<std::uint32_t, 3>> kept;
  const auto onWall = [&](const glm::dvec3& q) { return q.x == 0 || q.x == W || q.z == 0 || q.z == D; };
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const bool wall = onWall(a) && onWall(b) && onWall(c) && ((a.x == b.x && b.x == c.x) || (a.z == b.z && b.z == c.z));
    if (!wall) kept.push_back(t);
  }
  mesh.triangles = kept;
  mesh.triangleMaterial.assign(kept.size(), 0);
  struct Wall {
    int a;          // normal axis (0 x, 2 z)
    double at, out; // plane and outward sign
    double depth;
  };
  const double y0 = 1.5, y1 = 3.5;
  for (const Wall& w : {Wall{2, D, 1, 0.3}, Wall{2, 0, -1, 0.2}, Wall{0, W, 1, 0.25}, Wall{0, 0, -1, 0.14}}) {
    const int t = 2 - w.a;  // along the wall
    const double length = t == 0 ? W : D, t0 = 1, t1 = length - 1, h0 = length / 2 - 1, h1 = length / 2 + 1;
    const auto at = [&](double along, double y, double inset) {
      glm::dvec3 q(0.0);
      q[t] = along;
      q.y = y;
      q[w.a] = w.at - w.out * inset;
      return q;
    };
    glm::dvec3 normal(0.0), alongT(0.0);
    normal[w.a] = w.out;
    alongT[t] = 1;
    addQuad(mesh, {at(t0, 0, 0), at(h0, 0, 0), at(h0, H, 0), at(t0, H, 0)}, normal);
    addQuad(mesh, {at(h1, 0, 0), at(t1, 0, 0), at(t1, H, 0), at(h1, H, 0)}, normal);
    addQuad(mesh, {at(h0, 0, 0), at(h1, 0, 0), at(h1, y0, 0), at(h0, y0, 0)}, normal);
    addQuad(mesh, {at(h0, y1, 0), at(h1, y1, 0), at(h1, H, 0), at(h0, H, 0)}, normal);
    addQuad(mesh, {at(h0, y0, w.depth), at(h1, y0, w.depth), at(h1, y1, w.depth), at(h0, y1, w.depth)}, normal);
    addQuad(mesh, {at(h0, y0, 0), at(h0, y1, 0), at(h0, y1, w.depth), at(h0, y0, w.depth)}, alongT);
    addQuad(mesh, {at(h1, y0, 0), at(h1, y1, 0), at(h1, y1, w.depth), at(h1, y0, w.depth)}, -alongT);
    addQuad(mesh, {at(h0, y0, 0), at(h1, y0, 0), at(h1, y0, w.depth), at(h0, y0, w.depth)}, glm::dvec3(0, 1, 0));
    addQuad(mesh, {at(h0, y1, 0), at(h1, y1, 0), at(h1, y1, w.depth), at(h0, y1, w.depth)}, glm::dvec3(0, -1, 0));
  }
  mesh.name = "recessed";
  return mesh;
}

// Triangles of the complementary mesh whose normal is not along an axis: the corners' faces.
int curvedComplementFaces(const Conversion& c) {
  int count = 0;
  for (const auto& t : c.complement.triangles) {
    const glm::dvec3 normal = glm::cross(c.complement.positions[t[1]] - c.complement.positions[t[0]],
                                         c.complement.positions[t[2]] - c.complement.positions[t[0]]);
    const glm::dvec3 a = glm::abs(normal);
    count += std::max({a.x, a.y, a.z}) < 0.9999 * glm::length(normal);
  }
  return count;
}

// `hniCells`: QuarterCylinder cells in the HNI, fewer than the pieces where sub-blocks of one
// shape turned share one block.
void expectRoundCorners(const TriangleMesh& mesh, int expected, int subBlocks, int hniCells, const std::string& stem) {
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  std::printf("%s: %d quarter-round pieces, %d as cells (%d as sub-blocks), %lld quadric cells, NUT %.2f %%, complement %zu triangles\n",
              stem.c_str(), s.quadrics, s.quadricsAsCells, s.quadricsAsSubBlocks, s.quadricCells, 100 * nutFraction(c),
              c.complement.triangles.size());
  EXPECT_EQ(s.quadrics, expected);
  EXPECT_EQ(s.quadricsAsCells, expected);
  EXPECT_EQ(s.quadricsAsSubBlocks, subBlocks);
  EXPECT_GE(s.quadricCells, expected);
  EXPECT_EQ(cellsOf(c, SolidGroup::QuarterCylinder), hniCells);
  EXPECT_EQ(cellsOf(c, SolidGroup::InverseQuarterCylinder), 0);
  EXPECT_GT(nutFraction(c), 0.99);
  EXPECT_EQ(curvedComplementFaces(c), 0);
  const std::string path = testing::outputDir("converter_quadric") + "/" + stem;
  const testing::Fidelity f = testing::measureFidelity(mesh, {&c}, path, 99.0);
  std::printf("%s: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%)\n", stem.c_str(), f.withinPct[0],
              f.withinPct[1], f.withinPct[2], f.withinPct[3], f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << path << ".view*.diff.png";
}

// The closed box [x0, x1] x [y0, y1] x [z0, z1], every face pointing outwards.
void addBox(TriangleMesh& mesh, const glm::dvec3& lo, const glm::dvec3& hi) {
  for (int a = 0; a < 3; ++a)
    for (const double side : {-1.0, 1.0}) {
      const int u = (a + 1) % 3, v = (a + 2) % 3;
      std::array<glm::dvec3, 4> quad;
      for (int k = 0; k < 4; ++k) {
        glm::dvec3& q = quad[static_cast<std::size_t>(k)];
        q[a] = side > 0 ? hi[a] : lo[a];
        q[u] = k == 1 || k == 2 ? hi[u] : lo[u];
        q[v] = k >= 2 ? hi[v] : lo[v];
      }
      glm::dvec3 normal(0.0);
      normal[a] = side;
      addQuad(mesh, quad, normal);
    }
}

constexpr int kDomeSegments = 16;  // per octant, around and up
constexpr int kDomeRings = 8;
constexpr double kDomeRadius = 2;
const glm::dvec3 kDomeBase(W / 2, H, D / 2);  // the middle of the roof

// A dome on the box's roof, closed by a disk on the roof (facing down): a cap of a sphere whose
// centre lies `sunk` below the roof, its rim the circle of radius kDomeRadius, the distance from
// the centre scaled by wave(azimuth, elevation) (a hemisphere: sunk 0, wave 1).
void addDome(TriangleMesh& mesh, double sunk, const std::function<double(double, double)>& wave) {
  const double sphere = std::hypot(kDomeRadius, sunk), rim = std::asin(sunk / sphere);
  const glm::dvec3 centre = kDomeBase - glm::dvec3(0, sunk, 0);
  const int around = 4 * kDomeSegments;
  const auto base = static_cast<std::uint32_t>(mesh.positions.size());
  for (int j = 0; j < kDomeRings; ++j)
    for (int i = 0; i < around; ++i) {
      const double az = 2 * std::numbers::pi * i / around;
      const double el = rim + (0.5 * std::numbers::pi - rim) * j / kDomeRings;
      const double r = sphere * wave(az, el);
      mesh.positions.push_back(centre + r * glm::dvec3(std::cos(el) * std::cos(az), std::sin(el), std::cos(el) * std::sin(az)));
    }
  const auto pole = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.push_back(centre + glm::dvec3(0, sphere * wave(0, 0.5 * std::numbers::pi), 0));
  mesh.positions.push_back(kDomeBase);  // the disk's centre
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangleMaterial.push_back(0);
  };
  const auto at = [&](int j, int i) { return base + static_cast<std::uint32_t>(j * around + (i % around)); };
  for (int i = 0; i < around; ++i) {
    for (int j = 0; j + 1 < kDomeRings; ++j) {
      add(at(j, i), at(j + 1, i + 1), at(j, i + 1));
      add(at(j, i), at(j + 1, i), at(j + 1, i + 1));
    }
    add(at(kDomeRings - 1, i), pole, at(kDomeRings - 1, i + 1));
    add(pole + 1, at(0, i), at(0, i + 1));
  }
}

TriangleMesh domedBox(double sunk, const std::function<double(double, double)>& wave, bool chimney = false) {
  TriangleMesh mesh;
  mesh.name = "domed";
  mesh.materials = {Material{220, 200, 170}};
  mesh.materialNames = {"wall"};
  addBox(mesh, glm::dvec3(0.0), glm::dvec3(W, H, D));
  addDome(mesh, sunk, wave);
  // Beside the dome, its sides' planes crossing the dome's boxes (x = 4.4, 5.6; y = 7).
  if (chimney) addBox(mesh, glm::dvec3(4.4, H, 6.5), glm::dvec3(5.6, H + 1, 7.5));
  return mesh;
}

const auto kSphere = [](double, double) { return 1.0; };

// `hniCells`: SphereOctant cells in the HNI (octant sub-blocks of one shape turned share one block).
void expectDome(const TriangleMesh& mesh, bool subBlocks, int hniCells, const std::string& stem) {
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  std::printf("%s: %d sphere octants, %d as cells, %lld sphere-octant cells, %zu blocks, NUT %.2f %% (+ %.2f %% hidden), complement %zu triangles\n",
              stem.c_str(), s.sphereOctants, s.sphereOctantsAsCells, s.sphereOctantCells, c.hierarchy.blocks.size(),
              100 * nutFraction(c), 100 * s.hiddenAreaM2 / s.areaM2, c.complement.triangles.size());
  EXPECT_EQ(s.sphereOctants, 4);
  EXPECT_EQ(s.sphereOctantsAsCells, 4);
  EXPECT_EQ(s.sphereOctantCells, 4);
  EXPECT_EQ(cellsOf(c, SolidGroup::SphereOctant), hniCells);
  EXPECT_EQ(cellsOf(c, SolidGroup::InverseSphereOctant), 0);
  EXPECT_EQ(c.hierarchy.blocks.size() > 1, subBlocks);
  EXPECT_EQ(curvedComplementFaces(c), 0);
  // The rest is the dome's base disk and the roof under it, hidden between solid cells.
  EXPECT_EQ(s.complementAreaM2, 0);
  const std::string path = testing::outputDir("converter_quadric") + "/" + stem;
  const testing::Fidelity f = testing::measureFidelity(mesh, {&c}, path, 99.0);
  std::printf("%s: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%)\n", stem.c_str(), f.withinPct[0],
              f.withinPct[1], f.withinPct[2], f.withinPct[3], f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << path << ".view*.diff.png";
}

TEST(SphereOctants, DomeBecomesFourSphereOctantCells) { expectDome(domedBox(0, kSphere), false, 4, "dome"); }

TEST(SphereOctants, DomeCutByBoundariesBecomesSubBlocks) { expectDome(domedBox(0, kSphere, true), true, 1, "dome_chimney"); }

// A cap flatter than a hemisphere (its sphere's centre 1 m below the roof) and a dome whose
// radius waves by 5 cm: neither is an ellipsoid octant within the 1 cm tolerance, so their faces
// stay in the complementary mesh.
TEST(SphereOctants, OtherDomesStayInTheComplementaryMesh) {
  for (const TriangleMesh& mesh : {domedBox(1, kSphere), domedBox(0, [](double az, double el) { return 1 + 0.025 * std::sin(6 * az) * std::cos(el); })}) {
    const Conversion c = testing::convertOrFail(mesh);
    const SolidStats& s = c.report.solid;
    std::printf("other dome: %d sphere octants, %lld sphere-octant cells, complement %zu triangles\n", s.sphereOctants,
                s.sphereOctantCells, c.complement.triangles.size());
    EXPECT_EQ(s.sphereOctants, 0);
    EXPECT_EQ(s.sphereOctantCells, 0);
    EXPECT_EQ(cellsOf(c, SolidGroup::SphereOctant) + cellsOf(c, SolidGroup::InverseSphereOctant), 0);
    EXPECT_EQ(curvedComplementFaces(c), 4 * kDomeSegments * (2 * kDomeRings - 1));
  }
}

TEST(QuarterCylinders, OneRoundCornerBecomesQuarterCylinderCells) {
  expectRoundCorners(roundedBox({kRound, nullptr, nullptr, nullptr}), 1, 0, 1, "one_corner");
}

TEST(QuarterCylinders, FourRoundCornersBecomeQuarterCylinderCells) {
  expectRoundCorners(roundedBox({kRound, kRound, kRound, kRound}), 4, 0, 4, "four_corners");
}

// Corners cut by recesses become sub-blocks, not complementary mesh.
TEST(QuarterCylinders, CornersCutByRecessesBecomeSubBlocks) {
  expectRoundCorners(roundedBoxWithRecesses(), 4, 4, 1, "recessed_corners");
}

// The house sample: four round corners (radius 1.5 m) that window recesses cut and a drum that
// window boundaries cross, all shown by sub-blocks, and the dome's four quarters as sphere
// octants. Fidelity: converter_fidelity_test.
TEST(QuarterCylinders, HouseCornersAndDrumBecomeSubBlocks) {
  auto obj = scene::readObj(std::string(NUT_SOURCE_DIR) + "/samples/obj/house.obj");
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  const Conversion c = testing::convertOrFail(mergeMeshes(obj->objects, "house").value());
  const SolidStats& s = c.report.solid;
  std::printf("house: %d quarter-round pieces, %d as sub-blocks, %d sphere octants, %d shown (%lld cells), NUT %.2f %% "
              "(+ %.2f %% hidden), complement %.2f %%, %zu triangles\n",
              s.quadrics, s.quadricsAsSubBlocks, s.sphereOctants, s.sphereOctantsAsCells, s.sphereOctantCells, 100 * nutFraction(c),
              100 * s.hiddenAreaM2 / s.areaM2, 100 * s.complementAreaM2 / s.areaM2, c.complement.triangles.size());
  EXPECT_EQ(s.quadrics, 8);
  EXPECT_EQ(s.quadricsAsSubBlocks, 8);
  EXPECT_EQ(s.sphereOctants, 4);
  EXPECT_EQ(s.sphereOctantsAsCells, 4);
  EXPECT_EQ(curvedComplementFaces(c), 0);
  EXPECT_LT(s.complementAreaM2, 0.01 * s.areaM2);
  // The four corners, the drum's four quarters and the dome's four octants are each one shape
  // turned: three sub-blocks show all twelve pieces, one QuarterCylinder cell for the corners, one
  // for the drum and one SphereOctant cell for the dome.
  EXPECT_EQ(cellsOf(c, SolidGroup::QuarterCylinder), 2);
  EXPECT_EQ(cellsOf(c, SolidGroup::SphereOctant), 1);
}

// Low-poly bevels on a small building (the box scaled to 2 x 1.2 x 1.6 m, the size of the Kenney
// models): corners of two facets (radius 10 cm) and of four (30 cm) lie within the 1 cm tolerance
// of a quarter cylinder, but each facet turns 22.5 and 11.25 degrees from the cylinder's normal at
// its edges, so a true cylinder in their place would shade unlike the facets (the Kenney models'
// roof rims were drawn round). Their facets become wedge cells instead: no quadric cell, no
// corner face in the complementary mesh, and the box renders like its source.
TEST(QuarterCylinders, BevelsOfFewFacetsStayFaceted) {
  constexpr double kScale = 0.2;
  for (const auto& [segments, radius] : {std::pair{2, 0.1}, std::pair{4, 0.3}}) {
    const Radius bevel = [r = radius / kScale](double, double) { return r; };
    TriangleMesh mesh = roundedBox({bevel, bevel, bevel, bevel}, segments);
    for (glm::dvec3& q : mesh.positions) q *= kScale;
    const Conversion c = testing::convertOrFail(mesh);
    const SolidStats& s = c.report.solid;
    std::printf("%d-facet bevels: %d quarter-round pieces, %lld wedge cells, NUT %.2f %%, complement %zu triangles\n", segments,
                s.quadrics, s.wedgeCells, 100 * nutFraction(c), c.complement.triangles.size());
    EXPECT_EQ(s.quadrics, 0);
    EXPECT_EQ(cellsOf(c, SolidGroup::QuarterCylinder) + cellsOf(c, SolidGroup::InverseQuarterCylinder), 0);
    EXPECT_GE(s.wedgeCells, 4 * segments);
    EXPECT_EQ(curvedComplementFaces(c), 0);
    const std::string path = testing::outputDir("converter_quadric") + "/bevel" + std::to_string(segments);
    const testing::Fidelity f = testing::measureFidelity(mesh, {&c}, path, 99.0);
    EXPECT_GE(f.worstWithinPct, 99.0) << "see " << path << ".view*.diff.png";
  }
}

// The two-facet bevels on the full-size box: their facets are too small a share of the surface to
// pay for a slope's boundaries, so they go to the complementary mesh. The planes of each bevel's
// box are boundaries all the same, so only the corners' cells are trimmed and the walls stay NUT
// (without them the one cell spanning the box was cut by every bevel and trimmed: NUT 0 %).
TEST(QuarterCylinders, SmallBevelsLeaveOnlyTheirCornersToTheMesh) {
  const Radius bevel = [](double, double) { return 0.1; };
  const TriangleMesh mesh = roundedBox({bevel, bevel, bevel, bevel}, 2);
  const Conversion c = testing::convertOrFail(mesh);
  const SolidStats& s = c.report.solid;
  std::printf("small bevels: %d quarter-round pieces, NUT %.2f %%, complement %zu triangles\n", s.quadrics, 100 * nutFraction(c),
              c.complement.triangles.size());
  EXPECT_EQ(s.quadrics, 0);
  EXPECT_GT(nutFraction(c), 0.98);
  EXPECT_EQ(curvedComplementFaces(c), 4 * 2 * 2);  // every facet, two triangles each
  const std::string path = testing::outputDir("converter_quadric") + "/small_bevels";
  const testing::Fidelity f = testing::measureFidelity(mesh, {&c}, path, 99.0);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << path << ".view*.diff.png";
}

// A corner whose radius shrinks from 1 m at the ground to 0.6 m at the top (a quarter cone, its
// faces sloped), and one whose radius waves by 5 cm about 1 m: neither is a quarter cylinder within
// the 1 cm tolerance, so their faces stay in the complementary mesh and no quadric cell appears.
// (With no boundary near the corners the one box cell they cut is trimmed: the mesh shows it all.)
TEST(QuarterCylinders, OtherCurvedCornersStayInTheComplementaryMesh) {
  const Radius cone = [](double, double y) { return 1.0 - 0.4 * y / H; };
  const Radius wavy = [](double t, double) { return 1.0 + 0.05 * std::sin(3 * std::numbers::pi * t); };
  const Conversion c = testing::convertOrFail(roundedBox({cone, wavy, nullptr, nullptr}));
  const SolidStats& s = c.report.solid;
  std::printf("other corners: %d quarter-round pieces, %lld quadric cells, NUT %.2f %%, complement %zu triangles\n", s.quadrics,
              s.quadricCells, 100 * nutFraction(c), c.complement.triangles.size());
  EXPECT_EQ(s.quadrics, 0);
  EXPECT_EQ(s.quadricCells, 0);
  EXPECT_EQ(cellsOf(c, SolidGroup::QuarterCylinder) + cellsOf(c, SolidGroup::InverseQuarterCylinder), 0);
  EXPECT_GE(curvedComplementFaces(c), 2 * 2 * kSegments);  // both corners' sides, two triangles a segment
}

}  // namespace
}  // namespace nut::converter
