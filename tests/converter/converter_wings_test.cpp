// A wing turned against its building (converter/wings.hpp): an L-shaped building made in the test,
// a box with a wing meeting it at 30 degrees, pilasters along the wing, is cut where the wing
// begins, and each part is converted in its own frame; the HNI then shows the pilasters as cells
// (in one frame their sides are mesh), takes fewer bytes with its complementary mesh than the
// building converted in one frame, and renders like the source mesh (at least 99 % of the pixels of every
// view within 8/255; diff images in the test output folder, converter_wings/, when not). Clipping a
// mesh to a half-space keeps its area, split between the two sides.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include <converter/align.hpp>
#include <converter/convert.hpp>
#include <converter/wings.hpp>
#include <nut/png_io.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

constexpr double kWingDeg = 30;
constexpr double kMainLengthM = 20, kMainHeightM = 9, kMainDepthM = 10;
constexpr double kWingLengthM = 12, kWingHeightM = 6, kWingFromM = 2, kWingToM = 8;

// Adds a vertical prism over a convex footprint (x, z), its faces turned away from its centre.
void addPrism(TriangleMesh& mesh, const std::vector<glm::dvec2>& footprint, double height, std::uint16_t wall, std::uint16_t roof) {
  glm::dvec3 centre(0.0, 0.5 * height, 0.0);
  for (const glm::dvec2& p : footprint) centre += glm::dvec3(p.x, 0.0, p.y) / static_cast<double>(footprint.size());
  const auto add = [&](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, std::uint16_t material) {
    if (glm::dot(glm::cross(b - a, c - a), (a + b + c) / 3.0 - centre) < 0) std::swap(b, c);
    const auto first = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.insert(mesh.positions.end(), {a, b, c});
    mesh.triangles.push_back({first, first + 1, first + 2});
    mesh.triangleMaterial.push_back(material);
  };
  const std::size_t n = footprint.size();
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec2 p = footprint[i], q = footprint[(i + 1) % n];
    const glm::dvec3 p0(p.x, 0.0, p.y), q0(q.x, 0.0, q.y), p1(p.x, height, p.y), q1(q.x, height, q.y);
    add(p0, q0, q1, wall);
    add(p0, q1, p1, wall);
  }
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const glm::dvec2 a = footprint[0], b = footprint[i], c = footprint[i + 1];
    add({a.x, height, a.y}, {b.x, height, b.y}, {c.x, height, c.y}, roof);
    add({a.x, 0.0, a.y}, {b.x, 0.0, b.y}, {c.x, 0.0, c.y}, wall);
  }
}

// A box 20 x 9 x 10 m and, against its +x face between z = 2 and 8 m, a wing 6 m high running
// away at 30 degrees (yaw convention: x turned towards -z), its far end square to it, with
// pilasters along its sides. The solids touch on the box's face and the wing's sides.
TriangleMesh lShapedBuilding() {
  TriangleMesh mesh;
  mesh.name = "l_shaped";
  mesh.materials = {{170, 165, 150, 255, 0}, {140, 60, 50, 255, 0}, {230, 225, 210, 255, 0}};
  mesh.materialNames = {"wall", "roof", "pilaster"};
  addPrism(mesh, {{0, 0}, {kMainLengthM, 0}, {kMainLengthM, kMainDepthM}, {0, kMainDepthM}}, kMainHeightM, 0, 1);
  const double turn = kWingDeg * std::numbers::pi / 180;
  const glm::dvec2 along(std::cos(turn), -std::sin(turn));
  const glm::dvec2 p0(kMainLengthM, kWingFromM), p1(kMainLengthM, kWingToM);
  // The far end is square to the wing: the side from p1 runs further by the width's share along it.
  const double longer = kWingLengthM - glm::dot(p1 - p0, along);
  addPrism(mesh, {p0, p0 + kWingLengthM * along, p1 + longer * along, p1}, kWingHeightM, 0, 1);
  // Pilasters along both sides of the wing, 0.5 m wide and 0.3 m deep, every 2 m: in the
  // building's frame each of their sides is a slope of its own.
  const glm::dvec2 out(-along.y, along.x);  // from p0's side towards p1's
  for (int i = 0; i < 5; ++i) {
    const double from = 1.5 + 2.0 * i;
    for (const auto& [base, away] : {std::pair{p0, -out}, std::pair{p1 + (longer - kWingLengthM) * along, out}}) {
      const glm::dvec2 a = base + from * along, b = a + 0.5 * along;
      addPrism(mesh, {a, b, b + 0.3 * away, a + 0.3 * away}, kWingHeightM, 2, 1);
    }
  }
  return mesh;
}

double area(const TriangleMesh& mesh) { return mesh.area(); }

TEST(TurnedWing, IsFoundWhereItBegins) {
  const TriangleMesh mesh = lShapedBuilding();
  const auto cut = findTurnedWing(mesh, 1.0, 0.01, 0.1);
  ASSERT_TRUE(cut.has_value());
  EXPECT_NEAR(yawDegrees(cut->yaw), kWingDeg, 0.01);
  EXPECT_EQ(cut->axis, 0);
  EXPECT_TRUE(cut->wingAbove);
  EXPECT_NEAR(cut->atM, kMainLengthM + 0.02, 1e-9);  // two tolerances past the box's face
  EXPECT_GT(cut->wingShare, 0.2);
}

TEST(TurnedWing, IsNotFoundOnABoxOrATurnWithinTwoTolerances) {
  TriangleMesh box;
  box.materials = {kDefaultMaterial};
  addPrism(box, {{0, 0}, {4, 0}, {4, 3}, {0, 3}}, 3, 0, 0);
  EXPECT_FALSE(findTurnedWing(box, 1.0, 0.01, 0.1).has_value());
  TriangleMesh nearlyStraight = box;
  const double turn = 1.5 * std::numbers::pi / 180;
  const glm::dvec2 along(std::cos(turn), -std::sin(turn));
  addPrism(nearlyStraight, {{4, 1}, glm::dvec2(4, 1) + 6.0 * along, glm::dvec2(4, 2) + 6.0 * along, {4, 2}}, 3, 0, 0);
  EXPECT_FALSE(findTurnedWing(nearlyStraight, 1.0, 0.01, 0.1).has_value());
}

TEST(ClipToHalfSpace, SplitsTheAreaBetweenTheSides) {
  const TriangleMesh mesh = lShapedBuilding();
  for (const int axis : {0, 1, 2}) {
    const double at = 0.5 * (mesh.bounds().min[axis] + mesh.bounds().max[axis]) + 0.123;
    const TriangleMesh above = clipToHalfSpace(mesh, axis, at, true), below = clipToHalfSpace(mesh, axis, at, false);
    EXPECT_NEAR(area(above) + area(below), area(mesh), 1e-9 * area(mesh)) << "axis " << axis;
    EXPECT_GT(area(above), 0) << "axis " << axis;
    EXPECT_GT(area(below), 0) << "axis " << axis;
    for (const glm::dvec3& p : above.positions) EXPECT_GE(p[axis], at);
    for (const glm::dvec3& p : below.positions) EXPECT_LE(p[axis], at);
    EXPECT_EQ(above.triangles.size(), above.triangleMaterial.size());
  }
}

TEST(TurnedWing, ConvertsInItsOwnFrameAndRendersLikeTheSource) {
  const TriangleMesh mesh = lShapedBuilding();
  ConvertOptions oneFrame;
  oneFrame.turnedWings = false;
  const Conversion plain = testing::convertOrFail(mesh, oneFrame);
  Conversion winged = testing::convertOrFail(mesh);
  const WingReport& wing = winged.report.wing;
  std::printf("l_shaped: wing turned by %.2f deg, cut at %c = %.3f m; NUT surface %.2f %% in one frame (%zu complementary "
              "triangles), %.2f %% with the wing apart (%zu); HNI + complement %llu B -> %llu B\n",
              wing.yawDeg, "xyz"[wing.axis], wing.cutM, 100 * testing::nutFraction(plain), plain.complement.triangles.size(),
              100 * testing::nutFraction(winged), winged.complement.triangles.size(),
              static_cast<unsigned long long>(wing.bytesWithout), static_cast<unsigned long long>(wing.bytesWith));
  ASSERT_TRUE(wing.found);
  ASSERT_TRUE(wing.applied);
  EXPECT_LT(wing.bytesWith, wing.bytesWithout);

  // The root has a cell for each part; the wing's redirects with its yaw.
  const Block& root = winged.hierarchy.blocks[winged.hierarchy.root];
  ASSERT_EQ(root.cells.size(), 2u);
  ASSERT_EQ(root.redirections.size(), 2u);
  EXPECT_NEAR(root.boundsM[0][1] + winged.originM.x, kMainLengthM + 0.02, 0.001);
  EXPECT_EQ(root.redirections[root.cells[1].redirection].rotation.yaw, findTurnedWing(mesh, 1.0, 0.01, 0.1)->yaw);

  // In one frame the pilasters' sides are left to the mesh; apart, only the wing's face against
  // the box (inside the building) and the slivers of its sides between that face and the cut, two
  // tolerances on, where the box's frame shows the building.
  EXPECT_GT(testing::nutFraction(winged), testing::nutFraction(plain) + 0.05);
  EXPECT_LT(winged.complement.triangles.size(), plain.complement.triangles.size() / 4);
  for (const glm::dvec3& p : winged.complement.positions) {
    EXPECT_GE(p.x, kMainLengthM - 1e-6);
    EXPECT_LE(p.x, kMainLengthM + 0.02 + 1e-6);
  }

  const std::string stem = testing::outputDir("converter_wings") + "/l_shaped";
  ASSERT_TRUE(writeConversion(winged, stem + ".hni.png", stem + ".complement.obj").ok());
  const testing::Fidelity f = testing::measureFidelity(mesh, {&winged}, stem, 99.0);
  std::printf("l_shaped, wing apart: within 8/255: %.2f %% %.2f %% %.2f %% %.2f %% (worst %.2f %%)\n", f.withinPct[0],
              f.withinPct[1], f.withinPct[2], f.withinPct[3], f.worstWithinPct);
  EXPECT_GE(f.worstWithinPct, 99.0) << "see " << stem << ".view*.diff.png";
  const Camera view = testing::fidelityViews(mesh.bounds(), 640, 360)[0];
  EXPECT_TRUE(writePng(stem + ".nut.png", testing::renderConversions({&winged}, view)).ok());
  EXPECT_TRUE(writePng(stem + ".mesh.png", testing::renderMesh(mesh, view)).ok());
}

}  // namespace
}  // namespace nut::converter
