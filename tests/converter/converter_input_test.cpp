// Mesh converter, first steps: the OBJ + MTL reader and its errors (file:line), objects and
// materials, z-up; the mesh checks and orientation repair; the generalized winding number against
// its exact sum; the solid grid on analytic meshes (a box, a box tilted by half a degree, an open
// box, walls standing on a base plate, a gable roof of wedges, a thin sheet and a wall's fin left
// to the complementary mesh); the city manifest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <converter/mesh_check.hpp>
#include <converter/solid.hpp>
#include <converter/winding.hpp>
#include <nut/hni.hpp>
#include <nut/raycast.hpp>
#include <scene/city.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

namespace fs = std::filesystem;

std::string writeFile(const std::string& name, const std::string& text) {
  const fs::path path = fs::path(testing::outputDir("converter_input")) / name;
  std::ofstream(path) << text;
  return path.string();
}

// An axis-aligned box [lo, hi] as OBJ text (outward faces, one material per face pair), after
// `rotateDeg` degrees about the vertical axis through the box centre.
std::string boxObj(glm::dvec3 lo, glm::dvec3 hi, double rotateDeg = 0, const std::string& mtllib = "") {
  const glm::dvec3 c = 0.5 * (lo + hi);
  const double t = rotateDeg * std::numbers::pi / 180.0;
  std::string obj = mtllib.empty() ? "" : "mtllib " + mtllib + "\n";
  char line[160];
  for (int i = 0; i < 8; ++i) {
    glm::dvec3 p((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
    const glm::dvec3 d = p - c;
    p = c + glm::dvec3(d.x * std::cos(t) + d.z * std::sin(t), d.y, -d.x * std::sin(t) + d.z * std::cos(t));
    std::snprintf(line, sizeof line, "v %.9f %.9f %.9f\n", p.x, p.y, p.z);
    obj += line;
  }
  // Quads counter-clockwise seen from outside (1-based corners: bit 0 x, bit 1 y, bit 2 z).
  obj += mtllib.empty() ? "" : "usemtl wall\n";
  obj += "f 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\n";
  obj += mtllib.empty() ? "" : "usemtl roof\n";
  obj += "f 1 3 4 2\nf 5 6 8 7\n";
  return obj;
}

// boxObj's text for a box that follows `verticesBefore` vertices in its file: OBJ indices count
// from the file's start, so its faces' corners are renumbered after them.
std::string boxObjAfter(int verticesBefore, glm::dvec3 lo, glm::dvec3 hi) {
  std::string out;
  std::istringstream lines(boxObj(lo, hi));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("f ", 0) == 0) {
      std::istringstream corners(line.substr(2));
      line = "f";
      for (int corner; corners >> corner;) {
        line += ' ';
        line += std::to_string(corner + verticesBefore);
      }
    }
    out += line;
    out += '\n';
  }
  return out;
}

// The OBJ text with every face's corners in reverse order (every face turned over).
std::string reversedFaces(const std::string& obj) {
  std::string out;
  std::istringstream lines(obj);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("f ", 0) == 0) {
      std::istringstream corners(line.substr(2));
      const std::vector<std::string> c{std::istream_iterator<std::string>(corners), {}};
      line = "f";
      for (auto it = c.rbegin(); it != c.rend(); ++it) {
        line += ' ';
        line += *it;
      }
    }
    out += line;
    out += '\n';
  }
  return out;
}

// A conversion of OBJ text.
Result<Conversion> convertText(const std::string& name, const std::string& text, const ConvertOptions& options = {}) {
  auto obj = scene::readObj(writeFile(name, text));
  if (!obj) return obj.error();
  return convertMesh(mergeMeshes(obj->objects, name).value(), options);
}

TEST(ObjInput, ReadsObjectsMaterialsAndNegativeIndices) {
  writeFile("two.mtl", "newmtl red\nKd 1 0 0\nnewmtl half\nKd 0.5 0.5 0.5\nd 0.5\n");
  const std::string path = writeFile("two.obj",
                                     "mtllib two.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                     "o first\nusemtl red\nf 1 2 3 4\n"
                                     "o second\nusemtl half\nf -4/1/1 -2/2/2 -1\nusemtl missing\nf 1 2 3\n");
  auto obj = scene::readObj(path);
  ASSERT_TRUE(obj.ok()) << obj.error().message;
  ASSERT_EQ(obj->objects.size(), 2u);
  EXPECT_EQ(obj->objects[0].name, "first");
  EXPECT_EQ(obj->objects[0].triangles.size(), 2u);  // the quad as a fan
  EXPECT_EQ(obj->objects[1].name, "second");
  EXPECT_EQ(obj->objects[1].triangles.size(), 2u);
  const TriangleMesh& second = obj->objects[1];
  EXPECT_EQ(second.materials[second.triangleMaterial[0]], (Material{128, 128, 128, 128, 0}));
  EXPECT_EQ(second.materials[second.triangleMaterial[1]], kDefaultMaterial);
  ASSERT_EQ(obj->warnings.size(), 1u);
  EXPECT_NE(obj->warnings[0].find("two.obj:12: material 'missing'"), std::string::npos) << obj->warnings[0];
  EXPECT_EQ(obj->objects[0].materials[obj->objects[0].triangleMaterial[0]], (Material{255, 0, 0, 255, 0}));
}

// A conversion of an axis-aligned solid read from polygons: closed, consistently turned, no face
// lost as degenerate, `solidCells` of its `cells` filled, and its whole surface `areaM2` in them.
void expectClosedSolid(const Result<Conversion>& c, std::array<int, 3> cells, int solidCells, double areaM2) {
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_TRUE(c->report.check.closed());
  EXPECT_EQ(c->report.check.inconsistentEdges, 0u);
  EXPECT_EQ(c->report.check.degenerate, 0u);
  EXPECT_EQ(c->report.solid.cells, cells);
  EXPECT_EQ(c->report.solid.solidCells, solidCells);
  EXPECT_NEAR(c->report.solid.areaM2, areaM2, 1e-9);
  EXPECT_NEAR(c->report.solid.nutAreaM2, areaM2, 1e-9);
}

TEST(ObjInput, NonConvexFacesKeepTheirShape) {
  // An L-shaped prism 3 m tall whose floor and roof are single six-corner faces, written from the
  // corner whose fan would also cover the notch: read as its shape, it is closed and fills the
  // three cells of the L, and the notch's cell stays empty.
  const std::string obj =
      "v 6 0 0\nv 6 0 2\nv 2 0 2\nv 2 0 5\nv 0 0 5\nv 0 0 0\n"
      "v 6 3 0\nv 6 3 2\nv 2 3 2\nv 2 3 5\nv 0 3 5\nv 0 3 0\n"
      "f 1 2 3 4 5 6\nf 7 12 11 10 9 8\n"
      "f 1 7 8 2\nf 2 8 9 3\nf 3 9 10 4\nf 4 10 11 5\nf 5 11 12 6\nf 6 12 7 1\n";
  expectClosedSolid(convertText("l_prism", obj), {2, 1, 2}, 3, 2 * 18.0 + 3 * 22.0);  // floor, roof, walls
}

TEST(ObjInput, AFaceWithAHoleJoinedByABridgeKeepsItsHole) {
  // A 9 m square block around a 3 m courtyard, 3 m tall, whose floor and roof are each one face:
  // the outline, a bridge to the courtyard's outline run the other way, and back. The bridge's
  // ends are corners met twice; they must stay, or the face crosses itself.
  const std::string obj =
      "v 0 0 0\nv 9 0 0\nv 9 0 9\nv 0 0 9\nv 3 0 3\nv 6 0 3\nv 6 0 6\nv 3 0 6\n"
      "v 0 3 0\nv 9 3 0\nv 9 3 9\nv 0 3 9\nv 3 3 3\nv 6 3 3\nv 6 3 6\nv 3 3 6\n"
      "f 1 2 3 4 1 5 8 7 6 5\nf 13 14 15 16 13 9 12 11 10 9\n"
      "f 1 9 10 2\nf 2 10 11 3\nf 3 11 12 4\nf 4 12 9 1\n"
      "f 5 13 16 8\nf 8 16 15 7\nf 7 15 14 6\nf 6 14 13 5\n";
  // All cells but the courtyard's; floor, roof, outer and courtyard walls.
  expectClosedSolid(convertText("courtyard", obj), {3, 1, 3}, 8, 2 * 72.0 + 4 * 27.0 + 4 * 9.0);
}

TEST(ObjInput, GroupsSplitObjectsWhenThereIsNoO) {
  auto obj = scene::readObj(writeFile("groups.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\ng a\nf 1 2 3\ng b\nf 1 3 2\ng a\nf 2 1 3\n"));
  ASSERT_TRUE(obj.ok());
  ASSERT_EQ(obj->objects.size(), 2u);
  EXPECT_EQ(obj->objects[0].triangles.size(), 2u);  // both "g a" runs
  EXPECT_EQ(obj->objects[1].name, "b");
}

TEST(ObjInput, ZUpTurnsToYUp) {
  auto obj = scene::readObj(writeFile("zup.obj", "v 1 2 3\nv 0 0 0\nv 1 0 0\nf 1 2 3\n"), {true});
  ASSERT_TRUE(obj.ok());
  EXPECT_EQ(obj->objects[0].positions[0], glm::dvec3(1, 3, -2));
}

TEST(ObjInput, KeepsLargeCoordinatesInDoublePrecision) {
  auto obj = scene::readObj(writeFile("city.obj", "v 2678219.001 395.002 -1243078.003\nv 2678220 395 -1243078\nv 2678219 396 -1243078\nf 1 2 3\n"));
  ASSERT_TRUE(obj.ok());
  EXPECT_EQ(obj->objects[0].positions[0], glm::dvec3(2678219.001, 395.002, -1243078.003));
}

struct BadObj {
  const char* name;
  const char* text;
  const char* expected;  // part of the message
};

class ObjErrors : public ::testing::TestWithParam<BadObj> {};

TEST_P(ObjErrors, NameTheFileAndLine) {
  const BadObj& c = GetParam();
  auto obj = scene::readObj(writeFile(std::string(c.name) + ".obj", c.text));
  ASSERT_FALSE(obj.ok());
  EXPECT_NE(obj.error().message.find(c.expected), std::string::npos) << obj.error().message;
}

INSTANTIATE_TEST_SUITE_P(
    Bad, ObjErrors,
    ::testing::Values(BadObj{"nan", "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "nan.obj:2: vertex 2 has a non-finite coordinate 'nan'"},
                      BadObj{"inf", "v 0 0 0\nv 1 -inf 0\nv 0 1 0\nf 1 2 3\n", "inf.obj:2: vertex 2 has a non-finite coordinate"},
                      BadObj{"word", "v 0 0 zero\n", "word.obj:1: vertex 1 has a coordinate that is not a number: 'zero'"},
                      BadObj{"short", "v 0 0\n", "short.obj:1: vertex 1 has 2 coordinates, expected 3"},
                      BadObj{"range", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", "range.obj:4: face refers to vertex 4, but only 3"},
                      BadObj{"zero", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "zero.obj:4: face corner '0' is not a vertex index"},
                      BadObj{"noface", "v 0 0 0\nv 1 0 0\n", "no faces (the file has 2 vertices)"},
                      BadObj{"empty", "", "no faces"}),
    [](const ::testing::TestParamInfo<BadObj>& p) { return std::string(p.param.name); });

TEST(ObjInput, UnreadableFilesAreErrors) {
  EXPECT_FALSE(scene::readObj("/nonexistent/building.obj").ok());
  EXPECT_NE(scene::readObj(testing::outputDir("converter_input")).error().message.find("is a directory"), std::string::npos);
}

TEST(ConvertErrors, OnlyDegenerateFacesIsRefused) {
  auto c = convertText("flat", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("degenerate"), std::string::npos) << c.error().message;
}

TEST(ConvertErrors, AFlatMeshEnclosesNothing) {
  auto c = convertText("sheet", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n");
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.error().message.find("flat along y"), std::string::npos) << c.error().message;
}

// Spans past the format's 16.8 km per axis are named, also where metres stop fitting millimetres
// in 64 bits (a huge span once read as "flat").
TEST(ConvertErrors, AMeshLargerThanAnHniIsRefusedNamingTheAxis) {
  for (const char* far : {"1e300", "100000"}) {
    auto c = convertText("far", boxObj({0, 0, 0}, {1, 1, 1}) + "v 0 0 " + far + "\nf 1 2 9\n");
    ASSERT_FALSE(c.ok()) << far;
    EXPECT_NE(c.error().message.find("spans"), std::string::npos) << c.error().message;
    EXPECT_NE(c.error().message.find("along z"), std::string::npos) << c.error().message;
  }
}

// A grid above SolidOptions::maxCells is refused with its size and what to change, not
// allocated: three boxes apart have 6 boundaries along x (0, 1, 2, 3, 3.5, 4) and 2 along y and
// z, 5 x 1 x 1 cells.
TEST(ConvertErrors, AGridAboveTheCellLimitIsRefusedWithItsSize) {
  const std::string threeBoxes =
      boxObj({0, 0, 0}, {1, 1, 1}) + boxObjAfter(8, {2, 0, 0}, {3, 1, 1}) + boxObjAfter(16, {3.5, 0, 0}, {4, 1, 1});
  ConvertOptions options;
  options.solid.maxCells = 3;
  auto c = convertText("cells", threeBoxes, options);
  ASSERT_FALSE(c.ok());
  const std::string expected = "cells: the grid would have 5 x 1 x 1 cells, more than 3; raise --tolerance";
  EXPECT_EQ(c.error().message.rfind(expected, 0), 0u) << c.error().message;
  options.solid.maxCells = 64;
  EXPECT_TRUE(convertText("cells", threeBoxes, options).ok());
}

// Messy soups on a small lattice (coincident and collinear corners, duplicate, flipped and
// crossing faces, open and non-manifold edges, slopes of every ratio) either convert to an HNI
// that validates and decodes, or fail with a message naming the mesh. 150 seeded soups.
TEST(ConvertStress, RandomSoupsConvertToValidHnisOrFailNamingTheMesh) {
  std::mt19937_64 rng(9);
  int converted = 0;
  ConvertOptions options;
  options.solid.threads = 1;
  for (int soup = 0; soup < 150; ++soup) {
    std::string text;
    char line[64];
    const int vertices = 4 + static_cast<int>(rng() % 14);
    const auto coordinate = [&] {
      const std::uint64_t kind = rng() % 12;
      const auto step = static_cast<double>(rng() % 9);
      return kind < 9 ? std::fmod(step, 4.0) : kind == 9 ? 0.5 * std::fmod(step, 7.0) : kind == 10 ? 1e-4 * std::fmod(step, 3.0) : 0.3333 * step;
    };
    for (int v = 0; v < vertices; ++v) {
      const double x = coordinate(), y = coordinate(), z = coordinate();
      std::snprintf(line, sizeof line, "v %.4f %.4f %.4f\n", x, y, z);
      text += line;
    }
    const int faces = 4 + static_cast<int>(rng() % 16);
    for (int f = 0; f < faces; ++f) {
      text += 'f';
      for (int corner = 0, corners = 3 + static_cast<int>(rng() % 2); corner < corners; ++corner) {
        std::snprintf(line, sizeof line, " %d", 1 + static_cast<int>(rng() % static_cast<std::uint64_t>(vertices)));
        text += line;
      }
      text += '\n';
    }
    const std::string name = "soup" + std::to_string(soup);
    auto c = convertText(name, text, options);
    if (!c.ok()) {
      EXPECT_NE(c.error().message.find(name), std::string::npos) << c.error().message;
      continue;
    }
    ++converted;
    const Status valid = validate(c->image);
    ASSERT_TRUE(valid.ok()) << name << ": " << valid.error().message << "\n" << text;
    EXPECT_TRUE(decode(c->image).ok()) << name;
  }
  EXPECT_GT(converted, 100);  // the soups mostly enclose something
}

TEST(MeshCheck, FindsOpenEdgesNonManifoldEdgesAndFlippedFaces) {
  auto obj = scene::readObj(writeFile("checked.obj", boxObj({0, 0, 0}, {1, 1, 1}) +
                                                  // A fin on the edge x=0..1, y=0, z=0: that edge gets 3 faces.
                                                  "v 0 0 -1\nf 1 2 9\n"));
  ASSERT_TRUE(obj.ok());
  TriangleMesh mesh = obj->objects[0];
  MeshCheck check = checkAndRepair(mesh);
  EXPECT_EQ(check.nonManifoldEdges, 1u);
  EXPECT_EQ(check.boundaryEdges, 2u);  // the fin's two free edges
  EXPECT_FALSE(check.closed());

  // A closed box with one face turned: repaired, and the box turned inside out is turned back.
  std::string flipped = boxObj({0, 0, 0}, {1, 1, 1});
  flipped.replace(flipped.find("f 1 5 7 3"), 9, "f 3 7 5 1");
  auto obj2 = scene::readObj(writeFile("flipped.obj", flipped));
  ASSERT_TRUE(obj2.ok());
  TriangleMesh box = obj2->objects[0];
  check = checkAndRepair(box);
  EXPECT_GT(check.inconsistentEdges, 0u);
  EXPECT_EQ(check.flippedTriangles, 2u);
  EXPECT_TRUE(check.closed());
  const WindingNumber w(box.positions, box.triangles);
  EXPECT_NEAR(w.exact(glm::dvec3(0.5)), 1.0, 1e-9);
}

// Walls and a roof without a floor, every face turned inwards: an open piece, so its volume does
// not say which way it faces, but the winding number on either side of its faces does (-1 and 0
// about a shell facing in). All ten triangles are turned out and the conversion is a solid box;
// left facing in, the inside would have w = -1 and the grid would be empty. The same shell facing
// out is left as it is.
TEST(MeshCheck, TurnsAnOpenShellFacingInwardsOut) {
  std::string outwards = boxObj({0, 0, 0}, {4, 3, 2});
  outwards.erase(outwards.find("f 1 2 6 5\n"), 10);  // the floor
  const std::string inwards = reversedFaces(outwards);
  for (const bool facingIn : {false, true}) {
    auto obj = scene::readObj(writeFile(facingIn ? "shell_in.obj" : "shell_out.obj", facingIn ? inwards : outwards));
    ASSERT_TRUE(obj.ok());
    TriangleMesh mesh = obj->objects[0];
    const MeshCheck check = checkAndRepair(mesh);
    EXPECT_EQ(check.flippedTriangles, facingIn ? 10u : 0u);
    EXPECT_GT(WindingNumber(mesh.positions, mesh.triangles).exact(glm::dvec3(2, 1.5, 1)), 0.5);
    auto c = convertText(facingIn ? "shell_in" : "shell_out", facingIn ? inwards : outwards);
    ASSERT_TRUE(c.ok()) << c.error().message;
    EXPECT_EQ(c->report.solid.solidCells, 1) << (facingIn ? "facing in" : "facing out");
  }
}

// A box whose top is two quads meeting the front and back edges at T-junctions: one open piece
// (those edges are used once each) but a closed surface. Turned inside out, its volume says so
// and the whole is turned back, for the occupancy step takes w >= 1/2 as inside.
TEST(MeshCheck, TurnsAClosedSurfaceWithTJunctionsInsideOutBack) {
  std::string box = boxObj({0, 0, 0}, {2, 1, 1});
  box.replace(box.find("f 3 7 8 4\n"), 10, "f 3 7 10 9\nf 9 10 8 4\n");
  box.insert(box.find("f "), "v 1 1 0\nv 1 1 1\n");
  for (const bool insideOut : {false, true}) {
    auto obj = scene::readObj(writeFile("tbox.obj", insideOut ? reversedFaces(box) : box));
    ASSERT_TRUE(obj.ok());
    TriangleMesh mesh = obj->objects[0];
    const MeshCheck check = checkAndRepair(mesh);
    EXPECT_FALSE(check.closed());
    EXPECT_TRUE(check.closedSurface);
    EXPECT_EQ(check.flippedTriangles, insideOut ? 14u : 0u);
    EXPECT_NEAR(WindingNumber(mesh.positions, mesh.triangles).exact(glm::dvec3(1, 0.5, 0.5)), 1.0, 1e-9);
  }
}

// The same box with its T-junction vertices moved up off the edges they meet, as turning a mesh
// and writing it with a few decimals moves them: half a millimetre off, the surface is still
// closed (matched exactly, it was not); 5 mm off, the slit is an opening.
TEST(MeshCheck, TJunctionsWithinAMillimetreOfTheirEdgesCloseTheSurface) {
  for (const double offM : {0.0005, 0.005}) {
    std::string box = boxObj({0, 0, 0}, {2, 1, 1});
    box.replace(box.find("f 3 7 8 4\n"), 10, "f 3 7 10 9\nf 9 10 8 4\n");
    char vertices[96];
    std::snprintf(vertices, sizeof vertices, "v 1 %.6f 0\nv 1 %.6f 1\n", 1 + offM, 1 + offM);
    box.insert(box.find("f "), vertices);
    auto obj = scene::readObj(writeFile("tbox_off.obj", box));
    ASSERT_TRUE(obj.ok());
    TriangleMesh mesh = obj->objects[0];
    const MeshCheck check = checkAndRepair(mesh);
    EXPECT_EQ(check.closedSurface, offM < 1e-3) << offM << " m off";
    EXPECT_EQ(check.flippedTriangles, 0u) << offM << " m off";
  }
}

// A 10 m box whose +x wall has a 2 m window opening, with reveals 0.3 m deep leading into the
// building, and a pane across the opening modelled facing in (as Ingolstadt's glass is). The
// pane's edges are each shared by the wall, a reveal and the pane, so it is a piece of its own,
// and next to it the rest of the mesh is at about 1/2 on both sides whichever way it faces; 0.7 m
// out, the rest is outside air in front and the building behind, so the pane is turned to face
// out and the room behind it is inside. Left facing in, the air in front would be inside.
TEST(MeshCheck, TurnsAPaneModelledFacingIntoItsWindowOut) {
  std::string obj = boxObj({0, 0, 0}, {10, 10, 10});
  obj.erase(obj.find("f 2 4 8 6\n"), 10);  // the +x wall, made again below with the opening
  std::vector<glm::dvec3> points;
  const auto vertex = [&](glm::dvec3 p) {
    points.push_back(p);
    char line[96];
    std::snprintf(line, sizeof line, "v %g %g %g\n", p.x, p.y, p.z);
    obj += line;
    return 8 + static_cast<int>(points.size());  // OBJ index, after the box's 8
  };
  const auto quad = [&](std::array<int, 4> c, glm::dvec3 facing) {
    const auto at = [&](int i) { return points[static_cast<std::size_t>(i - 9)]; };
    if (glm::dot(glm::cross(at(c[1]) - at(c[0]), at(c[2]) - at(c[0])), facing) < 0) std::swap(c[1], c[3]);
    obj += "f " + std::to_string(c[0]) + ' ' + std::to_string(c[1]) + ' ' + std::to_string(c[2]) + ' ' + std::to_string(c[3]) + '\n';
  };
  const double at[4] = {0, 4, 6, 10};
  int wall[4][4], reveal[2][2];
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) wall[i][j] = vertex({10, at[i], at[j]});
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) reveal[i][j] = vertex({9.7, at[i + 1], at[j + 1]});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (i != 1 || j != 1) quad({wall[i][j], wall[i + 1][j], wall[i + 1][j + 1], wall[i][j + 1]}, {1, 0, 0});
  quad({wall[1][1], wall[1][2], reveal[0][1], reveal[0][0]}, {0, 1, 0});
  quad({wall[2][1], wall[2][2], reveal[1][1], reveal[1][0]}, {0, -1, 0});
  quad({wall[1][1], wall[2][1], reveal[1][0], reveal[0][0]}, {0, 0, 1});
  quad({wall[1][2], wall[2][2], reveal[1][1], reveal[0][1]}, {0, 0, -1});
  quad({wall[1][1], wall[2][1], wall[2][2], wall[1][2]}, {-1, 0, 0});  // the pane, facing in

  auto read = scene::readObj(writeFile("pane_in.obj", obj));
  ASSERT_TRUE(read.ok()) << read.error().message;
  TriangleMesh mesh = read->objects[0];
  const MeshCheck check = checkAndRepair(mesh);
  EXPECT_EQ(check.nonManifoldEdges, 4u);
  int paneTriangles = 0;
  for (const auto& t : mesh.triangles) {
    const glm::dvec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    const glm::dvec3 centroid = (a + b + c) / 3.0;
    if (centroid.x != 10 || centroid.y < 4 || centroid.y > 6 || centroid.z < 4 || centroid.z > 6) continue;
    ++paneTriangles;
    EXPECT_GT(glm::cross(b - a, c - a).x, 0) << "a pane triangle still faces into the building";
  }
  EXPECT_EQ(paneTriangles, 2);
  const WindingNumber w(mesh.positions, mesh.triangles);
  EXPECT_LT(w.exact({10.05, 5, 5}), 0.5);  // in front of the pane
  EXPECT_GT(w.exact({9.95, 5, 5}), 0.5);   // in the opening behind it
}

TEST(MeshCheck, RemovesDegenerateFaces) {
  auto obj = scene::readObj(writeFile("degenerate.obj", boxObj({0, 0, 0}, {1, 1, 1}) + "v 0.5 0 0\nf 1 9 2\n"));
  ASSERT_TRUE(obj.ok());
  TriangleMesh mesh = obj->objects[0];
  const MeshCheck check = checkAndRepair(mesh);
  EXPECT_EQ(check.degenerate, 1u);
  EXPECT_EQ(mesh.triangles.size(), 12u);
}

TEST(WindingNumber, FastMatchesExactAndClassifiesABox) {
  // A box, whole and with one side missing: the fast sum must follow the exact one.
  auto obj = scene::readObj(writeFile("winding.obj", boxObj({0, 0, 0}, {4, 3, 2})));
  ASSERT_TRUE(obj.ok());
  const TriangleMesh& m = obj->objects[0];
  std::vector<std::array<std::uint32_t, 3>> open(m.triangles.begin() + 2, m.triangles.end());  // one side missing
  for (const auto& tris : {m.triangles, open}) {
    const WindingNumber w(m.positions, tris);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> d(-2.0, 6.0);
    for (int i = 0; i < 500; ++i) {
      const glm::dvec3 q(d(rng), d(rng), d(rng));
      EXPECT_NEAR(w(q), w.exact(q), 0.03) << q.x << " " << q.y << " " << q.z;  // far-field expansions
    }
  }
  const WindingNumber closed(m.positions, m.triangles);
  EXPECT_NEAR(closed.exact(glm::dvec3(2, 1.5, 1)), 1.0, 1e-9);
  EXPECT_NEAR(closed.exact(glm::dvec3(5, 1.5, 1)), 0.0, 1e-9);
  EXPECT_NEAR(closed(glm::dvec3(2, 1.5, 1)), 1.0, 0.03);
  EXPECT_NEAR(closed(glm::dvec3(5, 1.5, 1)), 0.0, 0.03);
}

TEST(WindingNumber, FastMatchesExactNextToTheSurface) {
  // Where the converter asks: near faces (cell centres, cell corners 2 % inside a cut cell). On
  // the box and on the box with one side missing: points on its faces moved by N(0, 5 cm) along
  // each axis, where the far field is least accurate, and points 1 mm in front of and behind a
  // face, where the triangles next to the point subtend nearly a hemisphere each (the product of
  // a leaf's tangents turns past the negative real axis: a turn lost would be an error of 1).
  auto obj = scene::readObj(writeFile("winding_near.obj", boxObj({0, 0, 0}, {4, 3, 2})));
  ASSERT_TRUE(obj.ok());
  const TriangleMesh& m = obj->objects[0];
  std::vector<std::array<std::uint32_t, 3>> open(m.triangles.begin() + 2, m.triangles.end());
  for (const auto& tris : {m.triangles, open}) {
    const WindingNumber w(m.positions, tris);
    std::mt19937 rng(11);
    std::uniform_int_distribution<std::size_t> pick(0, tris.size() - 1);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> offset(0.0, 0.05);
    for (int i = 0; i < 400; ++i) {
      const auto& t = tris[pick(rng)];
      const glm::dvec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
      double u = unit(rng), v = unit(rng);
      if (u + v > 1) u = 1 - u, v = 1 - v;
      const glm::dvec3 onFace = a + u * (b - a) + v * (c - a);
      const glm::dvec3 normal = glm::normalize(glm::cross(b - a, c - a));
      for (const glm::dvec3& q : {onFace + glm::dvec3(offset(rng), offset(rng), offset(rng)), onFace + 0.001 * normal,
                                  onFace - 0.001 * normal})
        EXPECT_NEAR(w(q), w.exact(q), 0.01) << q.x << " " << q.y << " " << q.z;
    }
  }
}

TEST(SolidGrid, ABoxIsOneSolidCell) {
  auto c = convertText("box", boxObj({10, 20, 30}, {14, 23, 32}));
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_TRUE(c->report.check.closedSurface);
  EXPECT_EQ(c->originM, glm::dvec3(10, 20, 30));
  EXPECT_EQ(c->report.solid.cells, (std::array<int, 3>{1, 1, 1}));
  EXPECT_EQ(c->report.solid.solidCells, 1);
  EXPECT_NEAR(c->report.solid.nutAreaM2, c->report.solid.areaM2, 1e-9);
  EXPECT_TRUE(c->complement.triangles.empty());
}

TEST(SolidGrid, FacesTiltedByHalfADegreeStillCluster) {
  // A 10 m box turned by 0.5 degrees: each wall spans 8.7 cm across its plane.
  auto c = convertText("tilted", boxObj({0, 0, 0}, {10, 3, 10}, 0.5));
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->report.solid.planes, (std::array<int, 3>{2, 2, 2}));
  EXPECT_EQ(c->report.solid.cells[1], 1);
  EXPECT_GT(c->report.solid.nutAreaM2, 0.99 * c->report.solid.areaM2);
}

// A flat roof flush with the wall tops around it: the faces meet in one plane, so no face plane
// marks where the roof's material ends. The strip of wall top must keep its own colour.
TEST(SolidGrid, CoplanarFacesOfTwoMaterialsGetABoundaryBetweenThem) {
  writeFile("flush.mtl", "newmtl wall\nKd 0.8 0.8 0.8\nnewmtl roof\nKd 0.5 0.2 0.1\n");
  std::string obj = "mtllib flush.mtl\n";
  int base = 0;
  char line[160];
  // A quad as two triangles, corners counter-clockwise seen from where it faces.
  const auto quad = [&](const char* material, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d) {
    obj += std::string("usemtl ") + material + "\n";
    for (const glm::dvec3& p : {a, b, c, d}) {
      std::snprintf(line, sizeof line, "v %.3f %.3f %.3f\n", p.x, p.y, p.z);
      obj += line;
    }
    std::snprintf(line, sizeof line, "f %d %d %d\nf %d %d %d\n", base + 1, base + 2, base + 3, base + 1, base + 3, base + 4);
    obj += line;
    base += 4;
  };
  const double L = 10, H = 3, s = 0.3;
  quad("wall", {0, 0, L}, {L, 0, L}, {L, H, L}, {0, H, L});  // +z
  quad("wall", {L, 0, 0}, {0, 0, 0}, {0, H, 0}, {L, H, 0});  // -z
  quad("wall", {L, 0, L}, {L, 0, 0}, {L, H, 0}, {L, H, L});  // +x
  quad("wall", {0, 0, 0}, {0, 0, L}, {0, H, L}, {0, H, 0});  // -x
  quad("wall", {0, 0, 0}, {L, 0, 0}, {L, 0, L}, {0, 0, L});  // bottom
  // The top: the roof inset by s, and the four strips of wall top around it (T-junctions).
  quad("roof", {s, H, L - s}, {L - s, H, L - s}, {L - s, H, s}, {s, H, s});
  quad("wall", {0, H, L}, {L, H, L}, {L, H, L - s}, {0, H, L - s});
  quad("wall", {0, H, s}, {L, H, s}, {L, H, 0}, {0, H, 0});
  quad("wall", {0, H, L - s}, {s, H, L - s}, {s, H, s}, {0, H, s});
  quad("wall", {L - s, H, L - s}, {L, H, L - s}, {L, H, s}, {L - s, H, s});
  auto c = convertText("flush", obj);
  ASSERT_TRUE(c.ok()) << c.error().message;
  // The top's T-junctions leave edges used once, yet every edge cancels along its line.
  EXPECT_GT(c->report.check.boundaryEdges, 0u);
  EXPECT_TRUE(c->report.check.closedSurface);
  EXPECT_GE(c->report.solid.materialBoundaries, 4);
  // Straight down onto the wall top's strip, its outer edge, and the roof.
  const HniRayCaster caster(c->image, c->originM);
  const auto colourAt = [&](double x, double z) {
    return caster.trace({x, 10.0, z}, {0, -1, 0}, 0.0, RayCastOptions{}).colour;
  };
  EXPECT_EQ(colourAt(0.2, 5), colourAt(0.05, 5));
  EXPECT_EQ(colourAt(5, 0.2), colourAt(5, 0.05));
  EXPECT_NE(colourAt(0.2, 5), colourAt(5, 5));
  EXPECT_EQ(colourAt(0.4, 5), colourAt(5, 5));
}

TEST(SolidGrid, AnOpenBoxIsStillSolid) {
  // The bottom is missing (a shell on the ground): the winding number still finds the inside.
  std::string obj = boxObj({0, 0, 0}, {4, 3, 2});
  obj.erase(obj.find("f 1 3 4 2\n"), 10);
  auto c = convertText("openbox", obj);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_FALSE(c->report.check.closed());
  EXPECT_FALSE(c->report.check.closedSurface);
  EXPECT_EQ(c->report.solid.solidCells, 1);
}

TEST(SolidGrid, WallsStandingOnABasePlateEncloseASolid) {
  // A closed base plate and a closed roof slab, and between them four walls that are single
  // quads standing on the plate (as game-asset buildings are made). Every vertical line crosses
  // the plate and the slab only, so counting crossings would leave the room between them empty;
  // the walls' winding number makes it inside.
  std::string obj =
      "v 0 0.2 0\nv 4 0.2 0\nv 4 0.2 4\nv 0 0.2 4\nv 0 3 0\nv 4 3 0\nv 4 3 4\nv 0 3 4\n"
      "f 1 5 6 2\nf 3 7 8 4\nf 4 8 5 1\nf 2 6 7 3\n";
  obj += boxObjAfter(8, {0, 0, 0}, {4, 0.2, 4});
  obj += boxObjAfter(16, {0, 3, 0}, {4, 3.2, 4});
  auto c = convertText("walls_on_plate", obj);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_FALSE(c->report.check.closedSurface);
  EXPECT_EQ(c->report.solid.cells, (std::array<int, 3>{1, 3, 1}));
  EXPECT_EQ(c->report.solid.solidCells, 3);
  // A ray at mid-height towards the front wall stops on it, in the wall's plane.
  const HniRayCaster caster(c->image, c->originM);
  const RayResult hit = caster.trace({2, 1.5, 10}, {0, 0, -1}, 0.0, RayCastOptions{});
  EXPECT_TRUE(hit.hit);
  EXPECT_NEAR(hit.distanceM, 6.0, 1e-3);
}

TEST(SolidGrid, AGableRoofBecomesWedges) {
  // A 6 x 2 x 4 box with a gable roof 2 m high, ridge along x.
  const std::string obj =
      "v 0 0 0\nv 6 0 0\nv 6 0 4\nv 0 0 4\nv 0 2 0\nv 6 2 0\nv 6 2 4\nv 0 2 4\nv 0 4 2\nv 6 4 2\n"
      "f 1 2 3 4\n"            // bottom (seen from below: counter-clockwise facing -y)
      "f 1 5 6 2\nf 4 3 7 8\n"  // front z=0 and back z=4 walls
      "f 1 4 8 9 5\nf 2 6 10 7 3\n"  // gable ends with the triangle on top
      "f 5 9 10 6\nf 8 7 10 9\n";    // roof slopes
  auto c = convertText("gable", obj);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->report.solid.slopesAsWedges, 2);
  EXPECT_EQ(c->report.solid.wedgeCells, 2);
  EXPECT_TRUE(c->complement.triangles.empty());
  EXPECT_NEAR(c->report.solid.nutAreaM2, c->report.solid.areaM2, 1e-6);
}

TEST(SolidGrid, AThinSheetGoesToTheComplementaryMesh) {
  // A closed box and a free-standing sign: a single quad with nothing behind it.
  const std::string obj = boxObj({0, 0, 0}, {2, 2, 2}) + "v 3 0 1\nv 4 0 1\nv 4 1 1\nv 3 1 1\nf 9 10 11 12\n";
  auto c = convertText("sheet", obj);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_NEAR(c->report.solid.complementAreaM2, 1.0, 1e-6);
  EXPECT_EQ(c->complement.triangles.size(), 2u);
}

TEST(SolidGrid, AFacePartlyUncoveredGoesToTheMeshInNoMoreTrianglesThanItsOwn) {
  // A box whose +x wall runs on as a fin 2 m past the box: the fin (6 of the wall's 36 m^2) has
  // nothing behind it. A second box far off adds the planes y = 1, 2 and z = 10.5, 11.5, so the
  // fin spans 3 x 3 cells. Each wall triangle's part of the fin, clipped to those cells, would
  // take up to three triangles; the mesh takes a triangle whole instead (its part over the box
  // then drawn twice) unless its part of the fin is one triangle.
  std::string obj = "v 0 0 0\nv 10 0 0\nv 0 3 0\nv 10 3 0\nv 0 0 10\nv 10 0 10\nv 0 3 10\nv 10 3 10\n";
  obj += "v 10 0 12\nv 10 3 12\n";                     // 9, 10: the fin's far edge
  obj += "f 1 5 7 3\nf 1 2 6 5\nf 3 7 8 4\nf 1 3 4 2\nf 5 6 8 7\n";  // -x, -y, +y, -z, +z
  obj += "f 2 4 10 9\n";                                 // +x wall and fin: one quad, x = 10
  obj += boxObjAfter(10, {20, 1, 10.5}, {21, 2, 11.5});  // the far box
  auto c = convertText("fin", obj);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_EQ(c->report.solid.planes[1], 4);  // y = 0, 1, 2, 3
  EXPECT_NEAR(c->report.solid.complementAreaM2, 6.0, 1e-6);
  const TriangleMesh& mesh = c->complement;
  EXPECT_LE(mesh.triangles.size(), 2u);
  EXPECT_NEAR(mesh.area(), 6.0 + c->report.solid.drawnTwiceAreaM2, 1e-6);
  EXPECT_GT(c->report.solid.drawnTwiceAreaM2, 0.0);
  for (const auto& t : mesh.triangles)
    for (std::uint32_t v : t) EXPECT_NEAR(mesh.positions[v].x + c->originM.x, 10.0, 1e-9);
  // The mesh covers the whole fin: points on a 0.1 m lattice over it each lie in a triangle.
  const auto inTriangle = [&](double y, double z) {
    for (const auto& t : mesh.triangles) {
      glm::dvec2 p[3];
      for (int k = 0; k < 3; ++k) p[k] = glm::dvec2(mesh.positions[t[k]].y, mesh.positions[t[k]].z) + glm::dvec2(c->originM.y, c->originM.z);
      const auto side = [&](int k) {
        const glm::dvec2 e = p[(k + 1) % 3] - p[k], q = glm::dvec2(y, z) - p[k];
        return e.x * q.y - e.y * q.x;
      };
      const double s0 = side(0), s1 = side(1), s2 = side(2);
      if ((s0 >= 0 && s1 >= 0 && s2 >= 0) || (s0 <= 0 && s1 <= 0 && s2 <= 0)) return true;
    }
    return false;
  };
  int uncovered = 0;
  for (double y = 0.05; y < 3; y += 0.1)
    for (double z = 10.05; z < 12; z += 0.1) uncovered += !inTriangle(y, z);
  EXPECT_EQ(uncovered, 0);
  std::vector<glm::dvec3> sorted = mesh.positions;
  std::sort(sorted.begin(), sorted.end(), [](const glm::dvec3& a, const glm::dvec3& b) {
    return a.x != b.x ? a.x < b.x : a.y != b.y ? a.y < b.y : a.z < b.z;
  });
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "a corner stored twice";
}

TEST(SolidGrid, ATallCellCutByTheMeshsRoofDoesNotPokeThroughIt) {
  // A 10 m shed under a roof rising from 10.0 m at z = 0 to 10.4 m at z = 6, left to the mesh
  // (no wedges); a post far off puts a boundary at y = 10.15, so the shed's cells of the first
  // metre (z < 1, the post's depth) reach 8-15 cm above the roof. The corners that decide whether
  // such a cut cell stays solid are sampled 2 cm inside it (2 % of its 10.15 m height hid the
  // poke once): from above, the HNI shows nothing above the roof (a cell cut away leaves its
  // walls to the mesh).
  std::string obj =
      "v 0 0 0\nv 10 0 0\nv 10 0 6\nv 0 0 6\nv 0 10 0\nv 10 10 0\nv 10 10.4 6\nv 0 10.4 6\n"
      "f 1 2 3 4\nf 1 5 6 2\nf 4 3 7 8\nf 1 4 8 5\nf 2 6 7 3\nf 5 8 7 6\n";
  obj += boxObjAfter(8, {20, 0, 0}, {21, 10.15, 1});  // the post
  ConvertOptions options;
  options.solid.wedges = false;
  auto c = convertText("shed", obj, options);
  ASSERT_TRUE(c.ok()) << c.error().message;
  EXPECT_GT(c->complement.area(), 60.0);  // the roof
  const HniRayCaster caster(c->image, c->originM);
  for (const double z : {0.25, 0.5, 0.75, 2.0, 4.0, 5.75}) {
    const double roof = 10.0 + 0.4 * z / 6.0;
    const RayResult hit = caster.trace({5, 20, z}, {0, -1, 0}, 0.0, RayCastOptions{});
    EXPECT_TRUE(!hit.hit || hit.distanceM >= 20.0 - roof - 1e-3) << "a cell pokes through the roof at z = " << z;
  }
  EXPECT_NEAR(c->report.solid.nutAreaM2 + c->report.solid.complementAreaM2 + c->report.solid.hiddenAreaM2,
              c->report.solid.areaM2, 1e-6);
}


}  // namespace
}  // namespace nut::converter
