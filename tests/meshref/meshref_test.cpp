// The mesh reference renderer: the Embree renderer on analytic scenes with known distances and
// colours, and determinism across thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include <glm/geometric.hpp>

#include <meshref/embree_renderer.hpp>
#include <scene/obj.hpp>

#include "test_files.hpp"

namespace nut::meshref {
namespace {

using scene::MeshHit;

namespace fs = std::filesystem;

std::string writeFile(const std::string& name, const std::string& text) {
  return testing::writeTestFile("meshref", name, text);
}

std::array<std::uint8_t, 3> rgb(const Material& m) { return {m.r, m.g, m.b}; }

// The whole OBJ file as one mesh, as render-mesh reads it.
Result<TriangleMesh> readMesh(const std::string& path) {
  std::vector<std::string> warnings;
  return scene::readObjMesh(path, warnings);
}

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

// ---- Embree renderer ----

constexpr Material kFront{204, 51, 102, 255, 0};  // Kd 0.8 0.2 0.4
constexpr Material kSide{153, 153, 153, 255, 0};  // Kd 0.6 0.6 0.6

EmbreeRenderer boxRenderer(const std::string& name, const glm::dvec3& lo, const glm::dvec3& hi) {
  auto mesh = readMesh(writeBox(name, lo, hi));
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
  auto mesh = readMesh(path);
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
  // Every ray mode composites the glass the same way: a packet's lane goes on one ray at a time.
  Camera camera;
  camera.eye = {0.3, 0.2, 6.0};
  camera.width = 37, camera.height = 29;
  camera.fovYDeg = 45;
  const MeshRenderOutput single = renderer->render(camera, 1);
  const std::uint8_t* centre = single.colour.at(18, 14);
  EXPECT_NE((std::array<std::uint8_t, 3>{centre[0], centre[1], centre[2]}), kBackground);
  for (const auto rays : {EmbreeRays::Packet8, EmbreeRays::Packet16, EmbreeRays::Stream}) {
    const MeshRenderOutput other = renderer->render(camera, 2, nullptr, rays);
    EXPECT_EQ(other.colour, single.colour) << static_cast<int>(rays);
    EXPECT_EQ(other.distanceM, single.distanceM) << static_cast<int>(rays);
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
  auto single = readMesh(writeFile("pane1.obj", vertices + "f 1 2 3\nf 1 3 4\n"));
  auto twice = readMesh(writeFile("pane2.obj", vertices + "f 1 2 3\nf 1 3 4\nf 3 2 1\nf 4 3 1\n"));
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
  auto mesh = readMesh(std::string(NUT_SOURCE_DIR) + "/tests/data/two_material_cube.obj");
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

}  // namespace
}  // namespace nut::meshref
