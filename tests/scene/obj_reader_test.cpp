// The OBJ + MTL reader (scene/obj.hpp) as the reference renderers read a whole file: polygons,
// materials and opacity, repeated corners, line ends, and every error naming the file and line.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/resource.h>

#include <glm/geometric.hpp>

#include <nut/png_io.hpp>
#include <scene/obj.hpp>

#include "test_files.hpp"

namespace nut::scene {
namespace {

namespace fs = std::filesystem;

fs::path outputDir() { return testing::testOutputDir("obj_reader"); }

std::string writeFile(const std::string& name, const std::string& text) {
  return testing::writeTestFile("obj_reader", name, text);
}

// The whole file as one mesh; its warnings in `warnings`.
std::vector<std::string> warnings;
Result<TriangleMesh> readWhole(const std::string& path) {
  warnings.clear();
  return readObjMesh(path, warnings);
}

TEST(ObjReader, ReadsTheTwoMaterialCube) {
  auto mesh = readWhole(std::string(NUT_SOURCE_DIR) + "/tests/data/two_material_cube.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(mesh->positions.size(), 8u);
  ASSERT_EQ(mesh->triangles.size(), 12u);  // 6 quads, fanned
  ASSERT_EQ(mesh->triangleMaterial.size(), 12u);
  EXPECT_EQ(mesh->bounds().min, glm::dvec3(0.0));
  EXPECT_EQ(mesh->bounds().max, glm::dvec3(1.0));
  int roof = 0;
  for (std::size_t t = 0; t < 12; ++t) {
    const Material& m = mesh->materials[mesh->triangleMaterial[t]];
    const std::string& name = mesh->materialNames[mesh->triangleMaterial[t]];
    // The roof is the only face with all corners at y = 1.
    bool top = true;
    for (std::uint32_t v : mesh->triangles[t]) top = top && mesh->positions[v].y == 1.0;
    if (top) {
      ++roof;
      EXPECT_EQ(name, "roof");
      EXPECT_EQ(m, (Material{255, 204, 102, 255, 0}));
    } else {
      EXPECT_EQ(name, "wall");
      EXPECT_EQ(m, (Material{102, 153, 204, 255, 0}));
    }
  }
  EXPECT_EQ(roof, 2);
}

TEST(ObjReader, FansConvexPolygonsAndReadsOpacity) {
  writeFile("pentagon.mtl", "newmtl glass\nKd 0.2 0.4 0.6\nd 0.25\nnewmtl tinted\nKd 1 1 1\nTr 0.75\n");
  const std::string path = writeFile("pentagon.obj",
                                     "mtllib pentagon.mtl\nv 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nv 9 9 9\n"
                                     "usemtl glass\nf 1 2 3 4 5\nusemtl tinted\nf 1 2 3\n");
  auto mesh = readWhole(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_EQ(mesh->triangles.size(), 4u);
  EXPECT_EQ(mesh->triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh->triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(mesh->triangles[2], (std::array<std::uint32_t, 3>{0, 3, 4}));
  EXPECT_EQ(mesh->materials[mesh->triangleMaterial[0]], (Material{51, 102, 153, 64, 0}));  // round(63.75)
  EXPECT_EQ(mesh->materials[mesh->triangleMaterial[3]].opacity, 64);                      // Tr = 1 - d
  // Bounds cover the vertices faces use; vertex 6 is used by none.
  EXPECT_EQ(mesh->bounds().min, glm::dvec3(-1, 0, 0));
  EXPECT_EQ(mesh->bounds().max, glm::dvec3(3, 2, 0));
}

TEST(ObjReader, NonConvexPolygonsKeepTheirShape) {
  // An L-shaped floor (area 18 m^2) written from the corner whose fan would cover the notch too
  // (30 m^2 of triangles, a third of them outside the L).
  const std::string path =
      writeFile("l_floor.obj", "v 6 0 0\nv 6 0 2\nv 2 0 2\nv 2 0 5\nv 0 0 5\nv 0 0 0\nf 1 6 5 4 3 2\n");
  auto mesh = readWhole(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_EQ(mesh->triangles.size(), 4u);
  double area = 0;
  for (const auto& t : mesh->triangles) {
    const glm::dvec3 n =
        glm::cross(mesh->positions[t[1]] - mesh->positions[t[0]], mesh->positions[t[2]] - mesh->positions[t[0]]);
    EXPECT_GT(n.y, 0) << "every triangle faces the face's way (up)";
    area += 0.5 * glm::length(n);
  }
  EXPECT_NEAR(area, 18.0, 1e-12);
}

TEST(ObjReader, ACornerRepeatingTheOneBeforeItIsLeftOut) {
  // "f 1 2 2 3 4 1": a square with its second corner written twice and its first closing it
  // again; read as the square, two triangles with no flat one, as the converter reads it.
  const std::string path = writeFile("repeats.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 2 3 4 1\nf 1 1 2\n");
  auto mesh = readWhole(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_EQ(mesh->triangles.size(), 2u);  // "f 1 1 2" has two corners left: no face
  EXPECT_EQ(mesh->triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh->triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

TEST(ObjReader, ReadsCrlfLineEnds) {
  auto mesh = readWhole(writeFile("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_EQ(mesh->triangles.size(), 1u);
  EXPECT_EQ(mesh->positions[1], glm::dvec3(1, 0, 0));
}

TEST(ObjReader, MissingMtlWarnsAndUsesTheDefaultColour) {
  const std::string path = writeFile("no_mtl.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl brick\nf 1 2 3\n");
  auto mesh = readWhole(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("nowhere.mtl"), std::string::npos) << warnings[0];
  ASSERT_EQ(mesh->triangles.size(), 1u);
  EXPECT_EQ(mesh->materials[mesh->triangleMaterial[0]], kDefaultMaterial);
  EXPECT_EQ(kDefaultMaterial, (Material{200, 200, 200, 255, 0}));
}

TEST(ObjReader, MissingFileIsAnError) {
  const std::string path = (outputDir() / "does_not_exist.obj").string();
  auto mesh = readWhole(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().message.rfind(path + ": cannot open", 0), 0u) << mesh.error().message;
  auto folder = readWhole(outputDir().string());
  ASSERT_FALSE(folder.ok());
  EXPECT_EQ(folder.error().message, outputDir().string() + ": is a directory, not a file");
}

TEST(ObjReader, NonFiniteVertexNamesTheLineAndVertex) {
  const std::string path = writeFile("nan.obj", "# comment\nv 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
  auto mesh = readWhole(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().message, path + ":3: vertex 2 has a non-finite coordinate 'nan'");

  const std::string huge = writeFile("huge.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nv 0 1e999 0\nf 1 2 3\n");
  auto mesh2 = readWhole(huge);
  ASSERT_FALSE(mesh2.ok());
  EXPECT_EQ(mesh2.error().message, huge + ":4: vertex 3 has a non-finite coordinate '1e999'");

  // Too small for a double is zero, as a double holds it.
  auto tiny = readWhole(writeFile("tiny.obj", "v 0 0 0\nv 1 -1e-999 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_TRUE(tiny.ok()) << tiny.error().message;
  EXPECT_EQ(tiny->positions[1], glm::dvec3(1, 0, 0));

  const std::string junk = writeFile("junk.obj", "v 0 0 0\nv 1 0x 0\nv 0 1\nf 1 2 3\n");
  auto mesh3 = readWhole(junk);
  ASSERT_FALSE(mesh3.ok());
  EXPECT_EQ(mesh3.error().message, junk + ":2: vertex 2 has a coordinate that is not a number: '0x'");

  const std::string shortLine = writeFile("short.obj", "v 0 0 0\nv 1 0\nf 1 2 1\n");
  auto mesh4 = readWhole(shortLine);
  ASSERT_FALSE(mesh4.ok());
  EXPECT_EQ(mesh4.error().message, shortLine + ":2: vertex 2 has 2 coordinates, expected 3");
}

TEST(ObjReader, NoFacesIsAnError) {
  const std::string path = writeFile("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  auto mesh = readWhole(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().message, path + ": no faces (the file has 3 vertices)");
}

TEST(ObjReader, FaceIndexOutOfRangeIsAnError) {
  const std::string path = writeFile("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  auto mesh = readWhole(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_NE(mesh.error().message.find("range.obj:4: face refers to vertex 7, but only 3 vertices precede it"), std::string::npos)
      << mesh.error().message;
}

// Text in memory reads as the file would: MTL files are asked for by their path beside the OBJ.
TEST(ObjReader, ReadsTextInMemoryAskingForItsMtlFiles) {
  std::vector<std::string> asked;
  const MtlReader readMtl = [&](const std::string& path) -> Result<std::string> {
    asked.push_back(path);
    if (path == "city/red.mtl") return std::string("newmtl red\nKd 1 0 0\n");
    return Error{path + ": no such file"};
  };
  const std::string obj = "mtllib red.mtl blue.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
  auto contents = readObjText(obj, "city/x.obj", readMtl);
  ASSERT_TRUE(contents.ok()) << contents.error().message;
  EXPECT_EQ(asked, (std::vector<std::string>{"city/red.mtl", "city/blue.mtl"}));
  ASSERT_EQ(contents->objects.size(), 1u);
  const TriangleMesh& mesh = contents->objects[0];
  EXPECT_EQ(mesh.name, "x");
  ASSERT_EQ(mesh.triangleMaterial.size(), 1u);
  EXPECT_EQ(mesh.materials.at(mesh.triangleMaterial[0]).r, 255);
  ASSERT_EQ(contents->warnings.size(), 1u);
  EXPECT_EQ(contents->warnings[0], "city/blue.mtl: no such file; its materials use the default grey");
}

// Peak resident memory of this process so far, in bytes (Linux reports ru_maxrss in KiB).
std::uint64_t peakRssBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024;
}

// Each object gets its own compact vertex list, in memory linear in the file: 50,000 vertices and
// 5,000 objects of one triangle each (a 0.5 MB file) stay under 64 MiB of growth in peak resident
// memory, where a file-sized vertex map per object would take 5,000 x 50,000 x 4 B = 1 GB.
TEST(ObjReader, ManyObjectsOverManyVerticesStayLinear) {
  constexpr int kVertices = 50000, kObjects = 5000;
  std::string obj;
  for (int v = 0; v < kVertices; ++v) obj += "v " + std::to_string(v) + " 0 " + std::to_string(v % 7) + "\n";
  for (int o = 0; o < kObjects; ++o)
    obj += "o part" + std::to_string(o) + "\nf " + std::to_string(o + 1) + " " + std::to_string(o + 2) + " " +
           std::to_string(kVertices - o) + "\n";
  const std::uint64_t before = peakRssBytes();
  auto contents = readObjText(obj, "many.obj", readTextFile);
  const std::uint64_t grown = peakRssBytes() - before;
  ASSERT_TRUE(contents.ok()) << contents.error().message;
  ASSERT_EQ(contents->objects.size(), static_cast<std::size_t>(kObjects));
  const TriangleMesh& last = contents->objects.back();
  EXPECT_EQ(last.name, "part" + std::to_string(kObjects - 1));
  ASSERT_EQ(last.positions.size(), 3u);
  EXPECT_EQ(last.positions[0], glm::dvec3(kObjects - 1, 0, (kObjects - 1) % 7));
  EXPECT_EQ(last.positions[2], glm::dvec3(kVertices - kObjects, 0, (kVertices - kObjects) % 7));
  EXPECT_EQ(last.triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_LT(grown, std::uint64_t{64} << 20);
}

}  // namespace
}  // namespace nut::scene
