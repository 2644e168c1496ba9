// Quarter-cylinder cells of the mesh converter (converter/solid.hpp): a box building with one and
// with four round vertical corners (radius 1 m, 32 segments) converts with each corner as
// QuarterCylinder cells, over 99 % of its surface as NUT, no corner face in the complementary mesh,
// and renders like its source (at least 99 % of the pixels of every view within 8/255; diff images
// in the test output folder, converter_quadric/, when not). Corners that are no quarter cylinder (a
// radius shrinking with height, a wavy arc) stay in the complementary mesh.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>

#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <converter/mesh.hpp>
#include <nut/solids.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

constexpr double W = 10, H = 6, D = 8;  // x, y (up), z
constexpr int kSegments = 32;

// Radius of a corner's arc at angle t (0..1 along the arc) and height y.
using Radius = std::function<double(double t, double y)>;

// The box [0, W] x [0, H] x [0, D] with its four vertical corners rounded (a null radius keeps the
// corner sharp): corner c lies at +x+z, -x+z, -x-z, +x-z for c = 0..3; every face points outwards.
// One material: the 1 m strips along the walls that the corners' boundaries cut would show the
// wall's material on the roof (a cell has one material, and a roof strip a sixth of the wall's area
// is below the share that separates materials), which is not what these tests are about.
Mesh roundedBox(const std::array<Radius, 4>& corners) {
  Mesh mesh;
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
      for (int i = 0; i <= kSegments; ++i) {
        const double t = static_cast<double>(i) / kSegments, angle = 0.5 * std::numbers::pi * (c + t);
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

Conversion convert(const Mesh& mesh) {
  auto c = convertMesh(mesh);
  EXPECT_TRUE(c.ok()) << c.error().message;
  return c.ok() ? std::move(*c) : Conversion{};
}

double nutFraction(const Conversion& c) { return c.report.solid.nutAreaM2 / c.report.solid.areaM2; }

// Cells of the HNI per solid group (every block, as stored).
int cellsOf(const Conversion& c, SolidGroup group) {
  int count = 0;
  for (const Block& block : c.hierarchy.blocks)
    for (const Cell& cell : block.cells) count += cell.kind == CellKind::Solid && solidGroup(cell.solid) == group;
  return count;
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

void expectRoundCorners(const std::array<Radius, 4>& corners, int expected, const std::string& stem) {
  const Mesh mesh = roundedBox(corners);
  const Conversion c = convert(mesh);
  const SolidStats& s = c.report.solid;
  std::printf("%s: %d quarter-round pieces, %d as cells, %lld quadric cells, NUT %.2f %%, complement %zu triangles\n",
              stem.c_str(), s.quadrics, s.quadricsAsCells, s.quadricCells, 100 * nutFraction(c), c.complement.triangles.size());
  EXPECT_EQ(s.quadrics, expected);
  EXPECT_EQ(s.quadricsAsCells, expected);
  EXPECT_GE(s.quadricCells, expected);
  EXPECT_GE(cellsOf(c, SolidGroup::QuarterCylinder), expected);
  EXPECT_EQ(cellsOf(c, SolidGroup::InverseQuarterCylinder), 0);
  EXPECT_GT(nutFraction(c), 0.99);
  EXPECT_EQ(curvedComplementFaces(c), 0);
  const std::string path = testing::outputDir("converter_quadric") + "/" + stem;
  const testing::Fidelity f = testing::measureFidelity(mesh, {&c}, path, 99.0);
  std::printf("%s: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%)\n", stem.c_str(), f.withinPct[0],
              f.withinPct[1], f.withinPct[2], f.withinPct[3], f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << path << ".view*.diff.png";
}

TEST(QuarterCylinders, OneRoundCornerBecomesQuarterCylinderCells) {
  expectRoundCorners({kRound, nullptr, nullptr, nullptr}, 1, "one_corner");
}

TEST(QuarterCylinders, FourRoundCornersBecomeQuarterCylinderCells) {
  expectRoundCorners({kRound, kRound, kRound, kRound}, 4, "four_corners");
}

// A corner whose radius shrinks from 1 m at the ground to 0.6 m at the top (a quarter cone, its
// faces sloped), and one whose radius waves by 5 cm about 1 m: neither is a quarter cylinder within
// the 1 cm tolerance, so their faces stay in the complementary mesh and no quadric cell appears.
// (With no boundary near the corners the one box cell they cut is trimmed: the mesh shows it all.)
TEST(QuarterCylinders, OtherCurvedCornersStayInTheComplementaryMesh) {
  const Radius cone = [](double, double y) { return 1.0 - 0.4 * y / H; };
  const Radius wavy = [](double t, double) { return 1.0 + 0.05 * std::sin(3 * std::numbers::pi * t); };
  const Conversion c = convert(roundedBox({cone, wavy, nullptr, nullptr}));
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
