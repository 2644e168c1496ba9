// The CPU render of a scene of HNIs and meshes (scene/scene_render.hpp), against Embree on one
// mesh made independently of the scene's code: each HNI exported (export-mesh, read back by
// render-mesh's reader), placed as the scene places it, merged with the scene's meshes. Tolerance:
// 99.5 % of pixels within 8/255, the bar of an HNI against its exported mesh (sample_render_test);
// the renders and the diff image are written to the test output folder when a test fails.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>

#include <meshref/embree_renderer.hpp>
#include <nut/hierarchy.hpp>
#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/obj.hpp>
#include <scene/scene_render.hpp>

namespace nut::scene {
namespace {

using meshref::EmbreeRenderer;
using meshref::MeshRenderOutput;

namespace fs = std::filesystem;

constexpr int kWidth = 640, kHeight = 360;
constexpr double kMinWithinPct = 99.5;
constexpr std::array<std::uint8_t, 3> kBeamAlbedo{200, 30, 30};

fs::path outputDir() {
  const fs::path dir = fs::path(NUT_TEST_OUTPUT_DIR) / "scene_render";
  fs::create_directories(dir);
  return dir;
}

// A sample HNI and its exported mesh as render-mesh reads it.
struct Sample {
  PngFile png;
  TriangleMesh mesh;
  WorldBox content;
};

Sample loadSample(const std::string& name) {
  Sample s;
  auto png = readPng(std::string(NUT_SOURCE_DIR) + "/samples/hni/" + name + ".png");
  EXPECT_TRUE(png.ok()) << png.error().message;
  s.png = std::move(*png);
  auto h = decode(s.png.image);
  EXPECT_TRUE(h.ok());
  auto exported = exportMesh(*h, s.png.text.originM);
  EXPECT_TRUE(exported.ok());
  const fs::path obj = outputDir() / (name + ".obj");
  EXPECT_TRUE(writeObj(obj.string(), *exported).ok());
  std::vector<std::string> warnings;
  auto mesh = readObjMesh(obj.string(), warnings);
  EXPECT_TRUE(mesh.ok());
  s.mesh = std::move(*mesh);
  s.content = s.mesh.bounds();
  return s;
}

// An axis-aligned box as 12 triangles in one material.
TriangleMesh boxMesh(const WorldBox& b, const std::array<std::uint8_t, 3>& albedo) {
  TriangleMesh m;
  for (int c = 0; c < 8; ++c) m.positions.push_back({c & 1 ? b.max.x : b.min.x, c & 2 ? b.max.y : b.min.y, c & 4 ? b.max.z : b.min.z});
  const std::array<std::array<std::uint32_t, 4>, 6> quads{{{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  m.triangleMaterial.assign(m.triangles.size(), 0);
  m.materials.push_back(Material{albedo[0], albedo[1], albedo[2], 255, 0});
  m.materialNames.push_back("beam");
  return m;
}

// The scene renderer with the meshes traced by Embree.
SceneRenderer sceneOf(const std::vector<PlacedHni>& hnis, const std::vector<const TriangleMesh*>& meshes) {
  auto tracer = meshref::traceMeshes(meshes);
  EXPECT_TRUE(tracer.ok()) << tracer.error().message;
  return SceneRenderer(hnis, tracer ? std::move(*tracer) : nullptr);
}

double withinPct(const Image& scene, const Image& reference, const std::string& name) {
  auto diff = compareImages(scene, reference, 8);
  EXPECT_TRUE(diff.ok());
  const double within = 100.0 - diff->differingPct;
  std::printf("%s: %.4f %% of pixels within 8/255\n", name.c_str(), within);
  if (within < kMinWithinPct) {
    (void)writePng((outputDir() / (name + ".scene.png")).string(), scene);
    (void)writePng((outputDir() / (name + ".embree.png")).string(), reference);
    (void)writePng((outputDir() / (name + ".diff.png")).string(), diff->diff);
  }
  return within;
}

int pixelsOfColour(const Image& image, const std::array<std::uint8_t, 3>& colour) {
  int n = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) n += image.at(x, y)[0] == colour[0] && image.at(x, y)[1] == colour[1] && image.at(x, y)[2] == colour[2];
  return n;
}

// A beam through the building's front: its front half stands out of the facade, its back half is
// inside the building, hidden.
WorldBox beamThrough(const WorldBox& building) {
  const glm::dvec3 size = building.size();
  const double y = building.min.y + 0.4 * size.y;
  return {{building.min.x - 2.0, y, building.max.z - 2.0}, {building.max.x + 2.0, y + 1.5, building.max.z + 3.0}};
}

TEST(SceneRender, AnHniAndAMeshShowTheNearerSurfaceAsEmbreeOnTheirUnion) {
  const Sample building = loadSample("building");
  const TriangleMesh beam = boxMesh(beamThrough(building.content), kBeamAlbedo);
  const SceneRenderer scene = sceneOf({{&building.png.image, building.png.text.originM}}, {&beam});
  auto union_ = EmbreeRenderer::create(mergeMeshes(std::vector<const TriangleMesh*>{&building.mesh, &beam}).value());
  ASSERT_TRUE(union_.ok());
  WorldBox all = building.content;
  all.min = glm::min(all.min, beam.bounds().min), all.max = glm::max(all.max, beam.bounds().max);
  const Camera camera = fitCamera(all, kWidth, kHeight);
  RayCastOptions options;
  options.lookup = Lookup::Exact;
  const RenderOutput frame = scene.render(camera, options);
  const Image reference = union_->render(camera).colour;
  EXPECT_GE(withinPct(frame.colour, reference, "beam"), kMinWithinPct);
  // The beam is in the picture, in front of the facade (the lit face seen from the default camera).
  const auto lit = shade(kBeamAlbedo, {0, 0, 1}, glm::normalize(camera.target - camera.eye));
  EXPECT_GT(pixelsOfColour(reference, lit), 2000);
  EXPECT_GT(pixelsOfColour(frame.colour, lit), 2000);
}

TEST(SceneRender, ATurnedHniMatchesItsExportedMeshTurnedTheSameWay) {
  const Sample building = loadSample("building");
  const glm::dvec3 origin = building.png.text.originM;
  const glm::dmat3 turn = yawRotation(30.0);
  TriangleMesh turned = building.mesh;
  for (glm::dvec3& p : turned.positions) p = origin + turn * (p - origin);

  const HniRayCaster caster(building.png.image, origin, turn);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(caster.bounds().min[a], turned.bounds().min[a] + 1e-9) << "axis " << a;
    EXPECT_GE(caster.bounds().max[a], turned.bounds().max[a] - 1e-9) << "axis " << a;
  }
  const SceneRenderer scene = sceneOf({{&building.png.image, origin, turn}}, {});
  auto reference = EmbreeRenderer::create(turned);
  ASSERT_TRUE(reference.ok());
  const Camera camera = fitCamera(turned.bounds(), kWidth, kHeight);
  RayCastOptions options;
  options.lookup = Lookup::Exact;
  EXPECT_GE(withinPct(scene.render(camera, options).colour, reference->render(camera).colour, "turned"), kMinWithinPct);
}

// A block of 4 x 4 copies of one HNI, some turned: instances of one image and turn share a caster
// (each moved to its place), the ground grid decides which a ray is cast into, and copies hide
// each other. Against Embree on the exported mesh placed 16 times, from above the block and from a
// street inside it.
TEST(SceneRender, CopiesOfOneHniPlacedAndTurnedMatchEmbreeOnTheirPlacedMeshes) {
  const Sample building = loadSample("building");
  const glm::dvec3 origin = building.png.text.originM;
  std::vector<PlacedHni> placed;
  std::vector<TriangleMesh> copies;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const glm::dvec3 at = origin + glm::dvec3(32.0 * i, 0.0, 32.0 * j);
      const glm::dmat3 turn = yawRotation((i + j) % 3 == 0 ? 0.0 : (i + j) % 3 == 1 ? 90.0 : 30.0);
      placed.push_back({&building.png.image, at, turn});
      TriangleMesh copy = building.mesh;
      for (glm::dvec3& p : copy.positions) p = at + turn * (p - origin);
      copies.push_back(std::move(copy));
    }
  std::vector<const TriangleMesh*> pointers;
  for (const TriangleMesh& m : copies) pointers.push_back(&m);
  const TriangleMesh all = mergeMeshes(pointers).value();
  const SceneRenderer scene = sceneOf(placed, {});
  auto reference = EmbreeRenderer::create(all);
  ASSERT_TRUE(reference.ok());
  Camera above = fitCamera(all.bounds(), kWidth, kHeight);
  Camera street = above;
  street.eye = origin + glm::dvec3(58.0, 6.0, 110.0);
  street.target = origin + glm::dvec3(40.0, 4.0, 20.0);
  RayCastOptions options;
  options.lookup = Lookup::Exact;
  EXPECT_GE(withinPct(scene.render(above, options).colour, reference->render(above).colour, "copies-above"), kMinWithinPct);
  EXPECT_GE(withinPct(scene.render(street, options).colour, reference->render(street).colour, "copies-street"), kMinWithinPct);
}

TEST(SceneRender, ACappedRayShowsUnlessSomethingIsInFrontOfItsHni) {
  const Sample building = loadSample("building");
  const TriangleMesh beam = boxMesh(beamThrough(building.content), kBeamAlbedo);
  const SceneRenderer scene = sceneOf({{&building.png.image, building.png.text.originM}}, {&beam});
  auto beamAlone = EmbreeRenderer::create(beam);
  ASSERT_TRUE(beamAlone.ok());
  const HniRayCaster caster(building.png.image, building.png.text.originM);
  const WorldBox box = caster.bounds();
  const Camera camera = fitCamera(box, kWidth, kHeight);
  RayCastOptions options;
  options.maxIterations = 1;  // most rays that reach the building are capped
  const RenderOutput frame = scene.render(camera, options);
  const MeshRenderOutput beamFrame = beamAlone->render(camera);
  const RayGenerator rays(camera);
  int capped = 0, beamInFrontOfBox = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t* p = frame.colour.at(x, y);
      const bool magenta = p[0] == kCappedColour[0] && p[1] == kCappedColour[1] && p[2] == kCappedColour[2];
      capped += magenta;
      // Where the beam lies in front of the HNI's box, it is what the pixel shows.
      const glm::dvec3 dir = rays.direction(x, y);
      double entry = 0;
      for (int a = 0; a < 3; ++a) {
        const double t0 = (box.min[a] - camera.eye[a]) / dir[a], t1 = (box.max[a] - camera.eye[a]) / dir[a];
        entry = std::max(entry, std::min(t0, t1));
      }
      const float beamDistance = beamFrame.distanceM[static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x)];
      if (beamDistance < entry) {
        ++beamInFrontOfBox;
        EXPECT_FALSE(magenta) << "pixel " << x << "," << y;
      }
    }
  EXPECT_GT(capped, 10000);
  EXPECT_GT(beamInFrontOfBox, 1000);
}

TEST(SceneRender, YawIsTheFormatsYaw) {
  // A quarter turn takes x to -z (docs/FORMAT.md), and any yaw is the format's yaw of that angle.
  const glm::dvec3 x = yawRotation(90.0) * glm::dvec3(1, 0, 0);
  EXPECT_NEAR(x.x, 0.0, 1e-12);
  EXPECT_NEAR(x.z, -1.0, 1e-12);
  for (const std::uint16_t yaw : {std::uint16_t{1000}, std::uint16_t{20000}, std::uint16_t{50000}}) {
    const glm::dmat3 a = yawRotation(yaw * 360.0 / 65536.0), b = rotationMatrix(Rotation{0, yaw});
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) EXPECT_NEAR(a[c][r], b[c][r], 1e-12) << "yaw " << yaw;
  }
}

TEST(SceneRender, MergedMeshesKeepEachTrianglesCornersAndMaterial) {
  const TriangleMesh a = boxMesh({{0, 0, 0}, {1, 1, 1}}, {10, 20, 30});
  TriangleMesh b = boxMesh({{5, 0, 0}, {6, 2, 1}}, {40, 50, 60});
  b.materials.insert(b.materials.begin(), Material{});
  b.materialNames.insert(b.materialNames.begin(), "unused");
  for (auto& m : b.triangleMaterial) m = 1;
  const TriangleMesh merged = mergeMeshes(std::vector<const TriangleMesh*>{&a, &b}).value();
  ASSERT_EQ(merged.triangles.size(), a.triangles.size() + b.triangles.size());
  ASSERT_EQ(merged.materials.size(), 3u);
  for (std::size_t t = 0; t < b.triangles.size(); ++t) {
    const std::size_t m = a.triangles.size() + t;
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(merged.positions[merged.triangles[m][k]], b.positions[b.triangles[t][k]]);
    EXPECT_EQ(merged.materials[merged.triangleMaterial[m]].r, 40);
  }
  EXPECT_EQ(merged.bounds().min, glm::dvec3(0, 0, 0));
  EXPECT_EQ(merged.bounds().max, glm::dvec3(6, 2, 1));
}

}  // namespace
}  // namespace nut::scene
