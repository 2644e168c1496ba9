// A facade turned against the rest of its building, as survey noise leaves it (Ingolstadt's +x
// facade is 0.5 degrees off): its wall, reveals and panes chain into one plane cluster spanning
// centimetres, which the converter splits into steps (solid_grid.cpp, clusterIntervals). Every
// pane must then be drawn at its own depth, within the tolerance, and in its own colour.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <nut/raycast.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

using glm::dvec3;

constexpr std::uint16_t kWall = 0, kGlass = 1;
constexpr double kLength = 12, kHeight = 6, kFront = 8;  // z, y, and x of the facade at z = 0
constexpr double kRecess = 0.02;                          // panes behind the facade
constexpr double kWindowWidth = 0.8;
const double kTurn = std::tan(0.5 * std::numbers::pi / 180.0);

// Where the turned facade is at z.
double facadeX(double z) { return kFront + z * kTurn; }

struct Window {
  double za, zb, ya, yb;
  double paneX() const { return facadeX(0.5 * (za + zb)) - kRecess; }
};

// Two rows of eight windows, 1.4 m apart: the panes' depths step 1.2 cm from one to the next,
// across 8.6 cm of the facade's 10.5 cm drift.
std::vector<Window> windows() {
  std::vector<Window> out;
  for (int k = 0; k < 8; ++k) {
    const double zc = 1.0 + 1.4 * k;
    for (const auto& [ya, yb] : {std::pair{1.0, 2.4}, std::pair{3.4, 4.8}})
      out.push_back({zc - 0.5 * kWindowWidth, zc + 0.5 * kWindowWidth, ya, yb});
  }
  return out;
}

// A closed building: an axis-aligned box whose +x facade is turned by half a degree about the
// vertical, with the windows recessed into it (T-junctions where the facade's strips meet).
TriangleMesh turnedFacadeBuilding() {
  TriangleMesh m;
  m.name = "turned_facade";
  m.materials = {Material{200, 190, 180, 255, 0}, Material{60, 90, 160, 255, 0}};
  m.materialNames = {"wall", "glass"};
  const auto quad = [&](dvec3 a, dvec3 b, dvec3 c, dvec3 d, dvec3 outward, std::uint16_t material) {
    if (glm::dot(glm::cross(b - a, c - a), outward) < 0) std::swap(b, d);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    m.positions.insert(m.positions.end(), {a, b, c, d});
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
    m.triangleMaterial.insert(m.triangleMaterial.end(), {material, material});
  };
  const auto onFacade = [](double y, double z) { return dvec3(facadeX(z), y, z); };
  const double F0 = facadeX(0), FL = facadeX(kLength);
  quad({0, 0, 0}, {0, kHeight, 0}, {0, kHeight, kLength}, {0, 0, kLength}, {-1, 0, 0}, kWall);
  quad({0, 0, 0}, {F0, 0, 0}, {F0, kHeight, 0}, {0, kHeight, 0}, {0, 0, -1}, kWall);
  quad({0, 0, kLength}, {FL, 0, kLength}, {FL, kHeight, kLength}, {0, kHeight, kLength}, {0, 0, 1}, kWall);
  quad({0, 0, 0}, {F0, 0, 0}, {FL, 0, kLength}, {0, 0, kLength}, {0, -1, 0}, kWall);
  quad({0, kHeight, 0}, {F0, kHeight, 0}, {FL, kHeight, kLength}, {0, kHeight, kLength}, {0, 1, 0}, kWall);
  // The facade in strips: full height between the window columns, around the two rows in them.
  const dvec3 out(1, 0, 0);
  double z = 0;
  const auto strip = [&](double za, double zb, double ya, double yb) {
    quad(onFacade(ya, za), onFacade(ya, zb), onFacade(yb, zb), onFacade(yb, za), out, kWall);
  };
  for (const Window& w : windows()) {
    if (w.ya > 2) continue;  // one column per window of the lower row
    strip(z, w.za, 0, kHeight);
    strip(w.za, w.zb, 0, 1.0);
    strip(w.za, w.zb, 2.4, 3.4);
    strip(w.za, w.zb, 4.8, kHeight);
    z = w.zb;
  }
  strip(z, kLength, 0, kHeight);
  for (const Window& w : windows()) {
    const double P = w.paneX();
    quad({P, w.ya, w.za}, {facadeX(w.za), w.ya, w.za}, {facadeX(w.zb), w.ya, w.zb}, {P, w.ya, w.zb}, {0, 1, 0}, kWall);
    quad({P, w.yb, w.za}, {facadeX(w.za), w.yb, w.za}, {facadeX(w.zb), w.yb, w.zb}, {P, w.yb, w.zb}, {0, -1, 0}, kWall);
    quad({P, w.ya, w.za}, {facadeX(w.za), w.ya, w.za}, {facadeX(w.za), w.yb, w.za}, {P, w.yb, w.za}, {0, 0, 1}, kWall);
    quad({P, w.ya, w.zb}, {facadeX(w.zb), w.ya, w.zb}, {facadeX(w.zb), w.yb, w.zb}, {P, w.yb, w.zb}, {0, 0, -1}, kWall);
    quad({P, w.ya, w.za}, {P, w.yb, w.za}, {P, w.yb, w.zb}, {P, w.ya, w.zb}, out, kGlass);
  }
  return m;
}

TEST(TurnedFacade, EveryPaneIsAtItsDepthInItsColour) {
  const TriangleMesh mesh = turnedFacadeBuilding();
  const Conversion c = testing::convertOrFail(mesh);
  ASSERT_FALSE(c.image.pixels.empty());
  EXPECT_TRUE(c.report.check.closedSurface);
  const HniRayCaster caster(c.image, c.originM);
  // Straight at the facade along -x, from in front of it: where the surface is, and its colour.
  constexpr double kEyeX = 20;
  const auto look = [&](double y, double z) { return caster.trace({kEyeX, y, z}, {-1, 0, 0}, 0.0, RayCastOptions{Lookup::Exact}); };
  const double tol = ConvertOptions{}.solid.toleranceM;
  const RayResult wall = look(0.5, 1.0);
  ASSERT_TRUE(wall.hit);
  EXPECT_NEAR(kEyeX - wall.distanceM, facadeX(1.0), tol);
  const RayResult firstPane = look(1.7, 1.0);
  ASSERT_TRUE(firstPane.hit);
  EXPECT_NE(firstPane.colour, wall.colour);
  EXPECT_GT(firstPane.colour[2], firstPane.colour[0]);  // glass is blue, the wall is not
  for (const Window& w : windows()) {
    const double y = 0.5 * (w.ya + w.yb), z = 0.5 * (w.za + w.zb);
    const RayResult pane = look(y, z);
    ASSERT_TRUE(pane.hit) << "pane at z = " << z;
    EXPECT_NEAR(kEyeX - pane.distanceM, w.paneX(), tol) << "pane at y = " << y << ", z = " << z;
    EXPECT_EQ(pane.colour, firstPane.colour) << "pane at y = " << y << ", z = " << z;
  }
  // The wall between the columns: the steps are up to twice the tolerance apart, and the wall
  // between two of them is drawn at one or the other.
  for (double zWall = 0.3; zWall < kLength; zWall += 1.4) {
    const RayResult r = look(3.0, zWall);
    ASSERT_TRUE(r.hit);
    EXPECT_NEAR(kEyeX - r.distanceM, facadeX(zWall), 2 * tol) << "wall at z = " << zWall;
    EXPECT_EQ(r.colour, wall.colour) << "wall at z = " << zWall;
  }
}

// From the four fidelity views, against the source mesh traced with Embree.
TEST(TurnedFacade, RendersLikeTheSourceMesh) {
  const TriangleMesh mesh = turnedFacadeBuilding();
  const Conversion c = testing::convertOrFail(mesh);
  const std::string stem = testing::outputDir("converter_drift") + "/turned_facade";
  const testing::Fidelity f = testing::measureFidelity(mesh, {&c}, stem, 99.0);
  for (double pct : f.withinPct) std::printf("%.2f %% ", pct);
  std::printf("within 8/255\n");
  EXPECT_GE(f.worstWithinPct, 99.0) << "diff images: " << stem << ".view*.diff.png";
}

}  // namespace
}  // namespace nut::converter
