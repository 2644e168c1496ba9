// The mesh reference renderer: OBJ/MTL reading and its errors, the Embree renderer on analytic
// scenes with known distances and colours, determinism across thread counts, and the image
// comparison behind `nut compare`.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>

#include <meshref/embree_renderer.hpp>
#include <meshref/image_compare.hpp>
#include <meshref/obj.hpp>

namespace nut::meshref {
namespace {

namespace fs = std::filesystem;

fs::path outputDir() {
  const fs::path dir = fs::path(NUT_TEST_OUTPUT_DIR) / "meshref";
  fs::create_directories(dir);
  return dir;
}

std::string writeFile(const std::string& name, const std::string& text) {
  const fs::path path = outputDir() / name;
  std::ofstream(path) << text;
  return path.string();
}

std::array<std::uint8_t, 3> rgb(const Material& m) { return {m.r, m.g, m.b}; }

// An axis-aligned box [lo, hi] as an OBJ: the front face (+z) in material "front", the rest in
// "side", with the MTL beside it.
std::string writeBox(const std::string& name, const glm::dvec3& lo, const glm::dvec3& hi, const std::string& extraMtl = "") {
  writeFile(name + ".mtl", "newmtl front\nKd 0.8 0.2 0.4\nnewmtl side\nKd 0.6 0.6 0.6\n" + extraMtl);
  std::string obj = "mtllib " + name + ".mtl\n";
  char line[128];
  for (int i = 0; i < 8; ++i) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", (i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y,
                  (i & 4) ? hi.z : lo.z);
    obj += line;
  }
  // Vertex v = 1 + (x + 2y + 4z).
  obj += "usemtl front\nf 5 6 8 7\nusemtl side\nf 1 3 4 2\nf 1 5 7 3\nf 2 4 8 6\nf 1 2 6 5\nf 3 7 8 4\n";
  return writeFile(name + ".obj", obj);
}

// ---- OBJ reading ----

TEST(ObjReader, ReadsTheTwoMaterialCube) {
  auto mesh = readObj(std::string(NUT_SOURCE_DIR) + "/tests/data/two_material_cube.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_TRUE(mesh->warnings.empty());
  EXPECT_EQ(mesh->positions.size(), 8u);
  ASSERT_EQ(mesh->triangles.size(), 12u);  // 6 quads, fanned
  ASSERT_EQ(mesh->triangleMaterial.size(), 12u);
  EXPECT_EQ(mesh->bounds.min, glm::dvec3(0.0));
  EXPECT_EQ(mesh->bounds.max, glm::dvec3(1.0));
  int roof = 0;
  for (std::size_t t = 0; t < 12; ++t) {
    const MeshMaterial& m = mesh->materials[mesh->triangleMaterial[t]];
    // The roof is the only face with all corners at y = 1.
    bool top = true;
    for (std::uint32_t v : mesh->triangles[t]) top = top && mesh->positions[v].y == 1.0;
    if (top) {
      ++roof;
      EXPECT_EQ(m.name, "roof");
      EXPECT_EQ(m.material, (Material{255, 204, 102, 255, 0}));
    } else {
      EXPECT_EQ(m.name, "wall");
      EXPECT_EQ(m.material, (Material{102, 153, 204, 255, 0}));
    }
  }
  EXPECT_EQ(roof, 2);
}

TEST(ObjReader, FansConvexPolygonsAndReadsOpacity) {
  writeFile("pentagon.mtl", "newmtl glass\nKd 0.2 0.4 0.6\nd 0.25\nnewmtl tinted\nKd 1 1 1\nTr 0.75\n");
  const std::string path = writeFile("pentagon.obj",
                                     "mtllib pentagon.mtl\nv 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nv 9 9 9\n"
                                     "usemtl glass\nf 1 2 3 4 5\nusemtl tinted\nf 1 2 3\n");
  auto mesh = readObj(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_EQ(mesh->triangles.size(), 4u);
  EXPECT_EQ(mesh->triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh->triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(mesh->triangles[2], (std::array<std::uint32_t, 3>{0, 3, 4}));
  EXPECT_EQ(mesh->materials[mesh->triangleMaterial[0]].material, (Material{51, 102, 153, 64, 0}));  // round(63.75)
  EXPECT_EQ(mesh->materials[mesh->triangleMaterial[3]].material.opacity, 64);                      // Tr = 1 - d
  // Bounds cover the vertices faces use; vertex 6 is used by none.
  EXPECT_EQ(mesh->bounds.min, glm::dvec3(-1, 0, 0));
  EXPECT_EQ(mesh->bounds.max, glm::dvec3(3, 2, 0));
}

TEST(ObjReader, NonConvexPolygonsKeepTheirShape) {
  // An L-shaped floor (area 18 m^2) written from the corner whose fan would cover the notch too
  // (30 m^2 of triangles, a third of them outside the L).
  const std::string path =
      writeFile("l_floor.obj", "v 6 0 0\nv 6 0 2\nv 2 0 2\nv 2 0 5\nv 0 0 5\nv 0 0 0\nf 1 6 5 4 3 2\n");
  auto mesh = readObj(path);
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
  auto mesh = readObj(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_EQ(mesh->triangles.size(), 2u);  // "f 1 1 2" has two corners left: no face
  EXPECT_EQ(mesh->triangles[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(mesh->triangles[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

TEST(ObjReader, ReadsCrlfLineEnds) {
  auto mesh = readObj(writeFile("crlf.obj", "v 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\n"));
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_EQ(mesh->triangles.size(), 1u);
  EXPECT_EQ(mesh->positions[1], glm::dvec3(1, 0, 0));
}

TEST(ObjReader, MissingMtlWarnsAndUsesTheDefaultColour) {
  const std::string path = writeFile("no_mtl.obj", "mtllib nowhere.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl brick\nf 1 2 3\n");
  auto mesh = readObj(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_FALSE(mesh->warnings.empty());
  EXPECT_NE(mesh->warnings[0].find("no_mtl.obj"), std::string::npos) << mesh->warnings[0];
  EXPECT_NE(mesh->warnings[0].find("nowhere.mtl"), std::string::npos) << mesh->warnings[0];
  ASSERT_EQ(mesh->triangles.size(), 1u);
  EXPECT_EQ(mesh->materials[mesh->triangleMaterial[0]].material, kDefaultMeshMaterial);
  EXPECT_EQ(rgb(kDefaultMeshMaterial), (std::array<std::uint8_t, 3>{200, 200, 200}));
}

TEST(ObjReader, MissingFileIsAnError) {
  const std::string path = (outputDir() / "does_not_exist.obj").string();
  auto mesh = readObj(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().message.rfind(path + ": cannot open", 0), 0u) << mesh.error().message;
  auto folder = readObj(outputDir().string());
  ASSERT_FALSE(folder.ok());
  EXPECT_EQ(folder.error().message, outputDir().string() + ": is a directory, not an OBJ file");
}

TEST(ObjReader, NonFiniteVertexNamesTheLineAndVertex) {
  const std::string path = writeFile("nan.obj", "# comment\nv 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n");
  auto mesh = readObj(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().message, path + ":3: vertex 2 has a non-finite coordinate 'nan'");

  const std::string huge = writeFile("huge.obj", "v 0 0 0\nv 1 0 0\nvn 0 0 1\nv 0 1e999 0\nf 1 2 3\n");
  auto mesh2 = readObj(huge);
  ASSERT_FALSE(mesh2.ok());
  EXPECT_EQ(mesh2.error().message, huge + ":4: vertex 3 has a non-finite coordinate '1e999'");

  const std::string junk = writeFile("junk.obj", "v 0 0 0\nv 1 0x 0\nv 0 1\nf 1 2 3\n");
  auto mesh3 = readObj(junk);
  ASSERT_FALSE(mesh3.ok());
  EXPECT_EQ(mesh3.error().message, junk + ":2: vertex 2 has a coordinate that is not a number: '0x'");

  const std::string shortLine = writeFile("short.obj", "v 0 0 0\nv 1 0\nf 1 2 1\n");
  auto mesh4 = readObj(shortLine);
  ASSERT_FALSE(mesh4.ok());
  EXPECT_EQ(mesh4.error().message, shortLine + ":2: vertex 2 has 2 coordinates, expected 3");
}

TEST(ObjReader, NoFacesIsAnError) {
  const std::string path = writeFile("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  auto mesh = readObj(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_EQ(mesh.error().message, path + ": no faces (the file has 3 vertices)");
}

TEST(ObjReader, FaceIndexOutOfRangeIsAnError) {
  const std::string path = writeFile("range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n");
  auto mesh = readObj(path);
  ASSERT_FALSE(mesh.ok());
  EXPECT_NE(mesh.error().message.find("refers to vertex 7, but the file has 3 vertices"), std::string::npos)
      << mesh.error().message;
}

// ---- Embree renderer ----

constexpr Material kFront{204, 51, 102, 255, 0};  // Kd 0.8 0.2 0.4
constexpr Material kSide{153, 153, 153, 255, 0};  // Kd 0.6 0.6 0.6

EmbreeRenderer boxRenderer(const std::string& name, const glm::dvec3& lo, const glm::dvec3& hi) {
  auto mesh = readObj(writeBox(name, lo, hi));
  EXPECT_TRUE(mesh.ok()) << mesh.error().message;
  auto renderer = EmbreeRenderer::create(*mesh);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  return std::move(renderer).value();
}

TEST(EmbreeRenderer, BoxGivesAnalyticDistancesAndColours) {
  // Near the origin and 10^6 m away (city coordinates): the same answers.
  for (const glm::dvec3 offset : {glm::dvec3(0.0), glm::dvec3(1.0e6, 20.0, -3.0e6)}) {
    SCOPED_TRACE(offset.x);
    const glm::dvec3 lo = offset + glm::dvec3(-1.0, -0.5, -2.0), hi = offset + glm::dvec3(1.0, 0.5, 0.0);
    const EmbreeRenderer renderer = boxRenderer("box", lo, hi);
    EXPECT_EQ(renderer.bounds().min, lo);
    EXPECT_EQ(renderer.bounds().max, hi);

    // Straight at the front face (z = hi.z) from 5 m.
    const glm::dvec3 eye = offset + glm::dvec3(0.0, 0.0, 5.0);
    const glm::dvec3 forward(0.0, 0.0, -1.0);
    MeshHit h = renderer.trace(eye, forward);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.distanceM, 5.0, 1e-4);
    EXPECT_EQ(h.normal, glm::dvec3(0, 0, 1));
    EXPECT_EQ(h.colour, shade(rgb(kFront), {0, 0, 1}, forward));

    // Obliquely onto the top face (y = hi.y) at a chosen point.
    const glm::dvec3 eye2 = offset + glm::dvec3(3.0, 4.0, 2.0);
    const glm::dvec3 onTop = offset + glm::dvec3(0.25, 0.5, -1.5);
    const glm::dvec3 dir = glm::normalize(onTop - eye2);
    h = renderer.trace(eye2, dir);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.distanceM, glm::length(onTop - eye2), 1e-4);
    EXPECT_EQ(h.normal, glm::dvec3(0, 1, 0));
    EXPECT_EQ(h.colour, shade(rgb(kSide), {0, 1, 0}, dir));

    // Up into the sky: background, no distance.
    h = renderer.trace(eye, glm::dvec3(0.0, 1.0, 0.0));
    EXPECT_FALSE(h.hit);
    EXPECT_TRUE(std::isinf(h.distanceM));
    EXPECT_EQ(h.colour, kBackground);

    // The centre pixel of an odd-sized image looks exactly along the view axis.
    Camera camera;
    camera.eye = eye;
    camera.target = offset + glm::dvec3(0.0, 0.0, -1.0);
    camera.width = 33;
    camera.height = 21;
    const MeshRenderOutput frame = renderer.render(camera, 2);
    EXPECT_NEAR(frame.distanceM[10 * 33 + 16], 5.0, 1e-4);
    const std::uint8_t* centre = frame.colour.at(16, 10);
    const auto expected = shade(rgb(kFront), {0, 0, 1}, forward);
    EXPECT_EQ((std::array<std::uint8_t, 4>{centre[0], centre[1], centre[2], centre[3]}),
              (std::array<std::uint8_t, 4>{expected[0], expected[1], expected[2], 255}));
    // The corner pixel misses: the box spans about ±11 degrees across, the image ±30.
    EXPECT_TRUE(std::isinf(frame.distanceM[0]));
    EXPECT_EQ(frame.colour.at(0, 0)[0], kBackground[0]);
  }
}

TEST(EmbreeRenderer, TranslucentFacesCompositeOnceEach) {
  // A glass quad (two triangles) at z = 1 in front of an opaque wall at z = 0.
  writeFile("glass.mtl", "newmtl glass\nKd 0.2 0.4 1.0\nd 0.5\nnewmtl wall\nKd 0.8 0.8 0.8\n");
  const std::string path = writeFile("glass.obj",
                                     "mtllib glass.mtl\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
                                     "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\n"
                                     "usemtl glass\nf 1 2 3\nf 1 3 4\nusemtl wall\nf 5 6 7 8\n");
  auto mesh = readObj(path);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  auto renderer = EmbreeRenderer::create(*mesh);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  const glm::dvec3 down(0.0, 0.0, -1.0);
  const double alpha = 128 / 255.0;  // round(255 * 0.5)
  const auto glass = shade({51, 102, 255}, {0, 0, 1}, down), wall = shade({204, 204, 204}, {0, 0, 1}, down);
  std::array<std::uint8_t, 3> expected{};
  for (std::size_t c = 0; c < 3; ++c)
    expected[c] = static_cast<std::uint8_t>(std::lround(alpha * glass[c] + (1.0 - alpha) * wall[c]));
  // Off the diagonal, and exactly through the edge the two glass triangles share.
  for (const glm::dvec3 eye : {glm::dvec3(0.3, -0.2, 5.0), glm::dvec3(0.0, 0.0, 5.0)}) {
    const MeshHit h = renderer->trace(eye, down);
    ASSERT_TRUE(h.hit);
    EXPECT_NEAR(h.distanceM, 5.0, 1e-4);  // the opaque wall
    EXPECT_EQ(h.colour, expected);
  }
  // Away from both: background.
  const MeshHit sky = renderer->trace(glm::dvec3(0.0, 0.0, 5.0), glm::dvec3(0.0, 0.0, 1.0));
  EXPECT_FALSE(sky.hit);
  EXPECT_EQ(sky.colour, kBackground);
}

TEST(EmbreeRenderer, DoubleSidedGlassIsOneLayer) {
  // Exporters often write a pane twice with opposite windings. The copies' float hit distances
  // differ in the last bits, so without care half the rays would tint twice.
  writeFile("pane.mtl", "newmtl glass\nKd 0.2 0.4 1.0\nd 0.5\nnewmtl wall\nKd 0.8 0.8 0.8\n");
  const std::string vertices = "mtllib pane.mtl\nv -1.1 -0.93 1.17\nv 1.03 -1.07 0.71\nv 0.97 1.13 1.33\nv -1.07 0.91 1.77\n"
                               "v -2 -2 0\nv 2 -2 0\nv 2 2 0\nv -2 2 0\nusemtl wall\nf 5 6 7 8\nusemtl glass\n";
  auto single = readObj(writeFile("pane1.obj", vertices + "f 1 2 3\nf 1 3 4\n"));
  auto twice = readObj(writeFile("pane2.obj", vertices + "f 1 2 3\nf 1 3 4\nf 3 2 1\nf 4 3 1\n"));
  ASSERT_TRUE(single.ok() && twice.ok());
  auto r1 = EmbreeRenderer::create(*single);
  auto r2 = EmbreeRenderer::create(*twice);
  ASSERT_TRUE(r1.ok() && r2.ok());
  Camera camera;
  camera.eye = {0.3, 0.2, 6.0};
  camera.width = camera.height = 200;
  camera.fovYDeg = 30;
  EXPECT_EQ(r1->render(camera).colour, r2->render(camera).colour);
}

TEST(EmbreeRenderer, OutputDoesNotDependOnThreadCount) {
  auto mesh = readObj(std::string(NUT_SOURCE_DIR) + "/tests/data/two_material_cube.obj");
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  auto renderer = EmbreeRenderer::create(*mesh);
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  const Camera camera = fitCamera(renderer->bounds(), 97, 61);
  MeshRenderStats stats1, stats2;
  const MeshRenderOutput one = renderer->render(camera, 1, &stats1);
  const MeshRenderOutput two = renderer->render(camera, 2, &stats2);
  EXPECT_EQ(one.colour, two.colour);
  EXPECT_EQ(0, std::memcmp(one.distanceM.data(), two.distanceM.data(), one.distanceM.size() * sizeof(float)));
  EXPECT_EQ(stats1.threads, 1);
  EXPECT_EQ(stats2.threads, 2);
  EXPECT_GT(stats1.raysPerSecond, 0);
  // The fitted camera sees the whole cube: the border is background, the centre is the cube.
  EXPECT_EQ(one.colour.at(0, 0)[0], kBackground[0]);
  EXPECT_FALSE(std::isinf(one.distanceM[30 * 97 + 48]));
  // Straight down onto the roof.
  const MeshHit h = renderer->trace({0.5, 5.0, 0.5}, {0.0, -1.0, 0.0});
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.distanceM, 4.0, 1e-9);
  EXPECT_EQ(h.colour, shade({255, 204, 102}, {0, 1, 0}, {0, -1, 0}));
}

// ---- Image comparison ----

Image filled(int w, int h, std::uint8_t value) {
  Image image(w, h);
  for (std::size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = (i % 4 == 3) ? 255 : value;
  return image;
}

TEST(CompareImages, IdenticalImages) {
  const Image a = filled(7, 5, 100);
  auto d = compareImages(a, a, 8);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->rms, 0.0);
  EXPECT_TRUE(std::isinf(d->psnr));
  EXPECT_EQ(d->pixels, 35);
  EXPECT_EQ(d->differing, 0);
  EXPECT_EQ(d->differingPct, 0.0);
  EXPECT_EQ(d->maxDifference, 0);
  // Equal pixels show A in faded grey: 96 + 100 / 2.
  EXPECT_EQ(d->diff.texel(3, 2), (Rgba8{146, 146, 146, 255}));
}

TEST(CompareImages, KnownDifferences) {
  const Image a = filled(10, 10, 100);
  Image b = a;
  b.at(0, 0)[0] = 120;  // +20 in R: differs
  b.at(1, 0)[1] = 108;  // +8 in G: equal to the threshold, does not differ
  b.at(2, 0)[2] = 91;   // -9 in B: differs
  b.at(3, 0)[3] = 0;    // alpha is ignored
  auto d = compareImages(a, b, 8);
  ASSERT_TRUE(d.ok()) << d.error().message;
  EXPECT_EQ(d->pixels, 100);
  EXPECT_EQ(d->differing, 2);
  EXPECT_DOUBLE_EQ(d->differingPct, 2.0);
  EXPECT_EQ(d->maxDifference, 20);
  EXPECT_DOUBLE_EQ(d->rms, std::sqrt((400.0 + 64.0 + 81.0) / 300.0));
  EXPECT_DOUBLE_EQ(d->psnr, 20.0 * std::log10(255.0 / d->rms));
  EXPECT_EQ(d->diff.texel(0, 0), (Rgba8{168, 0, 0, 255}));  // red: 128 + 127 * 20 / 64
  EXPECT_EQ(d->diff.texel(1, 0), (Rgba8{0, 0, 255, 255}));  // blue, full at the threshold
  EXPECT_EQ(d->diff.texel(2, 0), (Rgba8{146, 0, 0, 255}));  // red: 128 + 127 * 9 / 64
  EXPECT_EQ(d->diff.texel(3, 0), (Rgba8{146, 146, 146, 255}));

  // Threshold 0: every changed pixel differs.
  auto strict = compareImages(a, b, 0);
  ASSERT_TRUE(strict.ok());
  EXPECT_EQ(strict->differing, 3);
}

TEST(CompareImages, SizeMismatchAndBadThresholdAreErrors) {
  auto d = compareImages(filled(10, 10, 0), filled(10, 9, 0), 8);
  ASSERT_FALSE(d.ok());
  EXPECT_EQ(d.error().message, "images differ in size: 10x10 vs 10x9");
  auto t = compareImages(filled(2, 2, 0), filled(2, 2, 0), 256);
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.error().message, "threshold 256: expected 0..255");
}

}  // namespace
}  // namespace nut::meshref
