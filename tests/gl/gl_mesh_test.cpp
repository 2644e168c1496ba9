// Meshes and HNIs in GL: (1) the "compare ray-cast output against mesh renders" test on the GPU
// path: every sample HNI ray-cast by the GLSL caster against the GL raster of its exported mesh
// (nut::exportMesh), same camera, at least 99.5 % of the pixels within 8/255; (2) an HNI and a
// complementary mesh in one depth-tested image, where a beam passes through a wall: compared with
// the CPU caster and Embree composited by distance, and checked for depth order on both sides of
// the wall; (3) two HNIs of one atlas in one instanced draw, against the CPU caster composited;
// (4) an instance turned by its per-instance rotation, against the CPU caster on a redirection
// with that rotation; (5) an invalid HNI is refused before upload.
// On failure <name>.actual.png, .expected.png and .diff.png go to tests/gl/output/mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include <meshref/embree_renderer.hpp>
#include <nut/hni.hpp>
#include <nut/mesh_export.hpp>
#include <nut/raycast.hpp>

#include "gl_scenes.hpp"
#include "gl_test_support.hpp"

namespace nut::gltest {
namespace {

class SampleRaster : public ::testing::TestWithParam<std::string> {};

TEST_P(SampleRaster, RayCastMatchesTheRasterOfTheExportedMesh) {
  const Scene s = sampleScene(GetParam(), 640, 360);
  ASSERT_GT(s.image.width, 0);
  auto exported = exportMesh(s.model, s.originM);
  ASSERT_TRUE(exported.ok()) << exported.error().message;

  auto rayCaster = openRenderer();
  ASSERT_TRUE(rayCaster);
  ASSERT_TRUE(rayCaster->addHni(s.image, s.originM).ok());
  auto cast = rayCaster->render(s.camera, {});
  ASSERT_TRUE(cast.ok()) << cast.error().message;
  rayCaster.reset();  // one context at a time

  auto rasteriser = openRenderer();
  ASSERT_TRUE(rasteriser);
  ASSERT_TRUE(rasteriser->addMesh(*exported).ok());
  auto raster = rasteriser->render(s.camera, {});
  ASSERT_TRUE(raster.ok()) << raster.error().message;

  // Colours only: rasterised depth is interpolated in float across large triangles, it does not
  // reach the ray casters' precision (the mixed-frame test below checks depth order).
  const std::vector<float> noDepth(raster->windowDepth.size(), 1.0f);
  const Agreement a = compareFrames(outputDir("mesh"), s.name + "-raster", raster->colour, noDepth, cast->colour,
                                    cast->windowDepth, 8, 99.5);
  EXPECT_GE(a.withinPct, 99.5) << s.name;
}

INSTANTIATE_TEST_SUITE_P(Samples, SampleRaster, ::testing::Values("facade", "building", "solids"));

// A closed box as a mesh with one material.
TriangleMesh boxMesh(const glm::dvec3& lo, const glm::dvec3& hi, const Material& material) {
  TriangleMesh m;
  for (int c = 0; c < 8; ++c) m.positions.push_back({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
  const std::uint32_t faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& f : faces) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  m.triangleMaterial.assign(m.triangles.size(), 0);
  m.materials.push_back(material);
  m.materialNames.push_back("beam");
  return m;
}

// Per pixel, the nearer of two CPU renders (ray caster, Embree): the reference for a mixed frame.
struct Composite {
  Image colour;
  std::vector<float> windowDepth;
  std::vector<char> fromSecond;  // the second render was nearer
};

Composite nearer(const Camera& camera, const Image& a, const std::vector<float>& distanceA, const Image& b,
                 const std::vector<float>& distanceB) {
  const RayGenerator rays(camera);
  Composite out{a, std::vector<float>(distanceA.size(), 1.0f), std::vector<char>(distanceA.size(), 0)};
  for (int y = 0; y < camera.height; ++y)
    for (int x = 0; x < camera.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(camera.width) + static_cast<std::size_t>(x);
      const bool second = distanceB[i] < distanceA[i];
      const float distance = second ? distanceB[i] : distanceA[i];
      if (second) std::copy_n(b.at(x, y), 4, out.colour.at(x, y));
      out.fromSecond[i] = second;
      if (std::isfinite(distance)) out.windowDepth[i] = static_cast<float>(rays.windowDepth(distance, rays.direction(x, y)));
    }
  return out;
}

TEST(MixedFrame, ComplementaryMeshThroughABlockKeepsDepthOrder) {
  // A 4 m x 3 m wall, 0.3 m thick, with a window opening; a beam pierces it at a slant from behind
  // to well in front, so that it is hidden behind the wall on one side and in front of it on the other.
  Hierarchy h;
  h.materials = {{210, 180, 140, 255, 0}};
  Block wall = Block::fromSizes({{{1.0, 0.8, 2.2}, {1.0, 1.2, 0.8}, {0.3}}});
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 3; ++y)
      if (x != 1 || y != 1) wall.cell(x, y, 0) = Cell::box(0);
  h.addBlock(std::move(wall));
  Scene s = compiledScene("mixed", h, glm::dvec3(0.0), 480, 270);
  ASSERT_GT(s.image.width, 0);
  const TriangleMesh beam = boxMesh({2.6, 1.1, -1.5}, {3.0, 1.5, 2.0}, {40, 90, 200, 255, 0});
  s.camera.eye = glm::dvec3(5.0, 2.6, 4.2);
  s.camera.target = glm::dvec3(2.0, 1.3, 0.0);
  s.camera.nearM = 1.0;
  s.camera.farM = 20.0;

  const HniRayCaster caster(s.image, s.originM);
  const RenderOutput cpu = renderHni(caster, s.camera, {});
  auto embree = meshref::EmbreeRenderer::create(beam);
  ASSERT_TRUE(embree.ok()) << embree.error().message;
  const meshref::MeshRenderOutput traced = embree->render(s.camera);
  const Composite reference = nearer(s.camera, cpu.colour, cpu.distanceM, traced.colour, traced.distanceM);

  auto renderer = openRenderer();
  ASSERT_TRUE(renderer);
  ASSERT_TRUE(renderer->addHni(s.image, s.originM).ok());
  ASSERT_TRUE(renderer->addMesh(beam).ok());
  auto gl = renderer->render(s.camera, {});
  ASSERT_TRUE(gl.ok()) << gl.error().message;
  const Agreement a = compareFrames(outputDir("mesh"), "mixed", reference.colour, reference.windowDepth, gl->colour,
                                    gl->windowDepth, 8, 99.5);
  EXPECT_GE(a.withinPct, 99.5);
  EXPECT_EQ(a.depthOutOfRange, 0);

  // Depth order where they interleave: pixels that see the beam in front of the wall, and pixels
  // whose ray meets the beam only behind the wall, which must show the wall.
  long long beamInFront = 0, beamInFrontShown = 0, beamHidden = 0, beamHiddenShown = 0;
  for (int y = 0; y < s.camera.height; ++y)
    for (int x = 0; x < s.camera.width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * static_cast<std::size_t>(s.camera.width) + static_cast<std::size_t>(x);
      if (!std::isfinite(cpu.distanceM[i]) || !std::isfinite(traced.distanceM[i])) continue;
      const bool sameColourAsBeam = std::equal(gl->colour.at(x, y), gl->colour.at(x, y) + 3, traced.colour.at(x, y));
      const bool sameColourAsWall = std::equal(gl->colour.at(x, y), gl->colour.at(x, y) + 3, cpu.colour.at(x, y));
      if (traced.distanceM[i] < cpu.distanceM[i] - 0.01) ++beamInFront, beamInFrontShown += sameColourAsBeam;
      if (traced.distanceM[i] > cpu.distanceM[i] + 0.01) ++beamHidden, beamHiddenShown += sameColourAsWall;
    }
  std::printf("beam in front of the wall: %lld of %lld pixels show it; beam behind the wall: %lld of %lld show the wall\n",
              beamInFrontShown, beamInFront, beamHiddenShown, beamHidden);
  EXPECT_GT(beamInFront, 500);
  EXPECT_GT(beamHidden, 500);
  EXPECT_GE(beamInFrontShown, beamInFront * 99 / 100);
  EXPECT_GE(beamHiddenShown, beamHidden * 99 / 100);
}

TEST(MixedFrame, TwoHnisShareOneAtlasAndOneDraw) {
  Scene facade = sampleScene("facade", 480, 270);
  Scene solids = sampleScene("solids", 480, 270);
  ASSERT_GT(facade.image.width, 0);
  ASSERT_GT(solids.image.width, 0);
  // The solids sample stands in front of the facade, to its right.
  const HniRayCaster facadeCaster(facade.image, facade.originM);
  const WorldBox box = facadeCaster.bounds();
  solids.originM = facade.originM + glm::dvec3(0.6 * box.size().x, 0.0, box.size().z + 4.0);
  const HniRayCaster solidsCaster(solids.image, solids.originM);
  Camera camera = facade.camera;
  camera.target = 0.5 * (box.centre() + solidsCaster.bounds().centre());
  camera.eye = camera.target + glm::dvec3(12.0, 10.0, 48.0);
  camera.farM *= 2.0;

  const RenderOutput a = renderHni(facadeCaster, camera, {});
  const RenderOutput b = renderHni(solidsCaster, camera, {});
  const Composite reference = nearer(camera, a.colour, a.distanceM, b.colour, b.distanceM);

  auto renderer = openRenderer();
  ASSERT_TRUE(renderer);
  ASSERT_TRUE(renderer->addHni(facade.image, facade.originM).ok());
  ASSERT_TRUE(renderer->addHni(solids.image, solids.originM).ok());
  auto gl = renderer->render(camera, {});
  ASSERT_TRUE(gl.ok()) << gl.error().message;
  const Agreement agreement = compareFrames(outputDir("mesh"), "two-hnis", reference.colour, reference.windowDepth,
                                            gl->colour, gl->windowDepth, 2, 99.9);
  EXPECT_GE(agreement.withinPct, 99.9);
  EXPECT_EQ(agreement.depthOutOfRange, 0);
  long long fromSolids = 0;
  for (char c : reference.fromSecond) fromSolids += c;
  EXPECT_GT(fromSolids, 1000) << "the second HNI should be in view";
}

TEST(MixedFrame, RotatedInstanceMatchesARotatedRedirection) {
  // The facade drawn as an instance turned a quarter about y, against the CPU caster on a wrapper
  // block whose one cell shows the facade through a redirection with the same rotation.
  const Scene facade = sampleScene("facade", 480, 270);
  ASSERT_GT(facade.image.width, 0);
  std::uint8_t quarterTurn = 0;
  for (int i = 0; i < 24; ++i)
    if (cubeRotationMatrix(i)[0] == glm::ivec3(0, 0, -1) && cubeRotationMatrix(i)[1] == glm::ivec3(0, 1, 0))
      quarterTurn = static_cast<std::uint8_t>(i);
  ASSERT_NE(quarterTurn, 0);
  const glm::dmat3 rotation = rotationMatrix({quarterTurn, 0});
  const glm::dvec3 size = facade.model.blocks[facade.model.root].sizeM();

  Hierarchy wrapper = facade.model;
  Block outer = Block::fromSizes({{{size.z}, {size.y}, {size.x}}});
  // The turned facade spans x in [0, Z] and z in [-X, 0] from its origin: shift it by X along z.
  outer.redirections.push_back({facade.model.root, glm::dvec3(0.0, 0.0, size.x), {quarterTurn, 0}, {false, false, false}});
  outer.cell(0, 0, 0) = Cell::redirect(0);
  wrapper.root = wrapper.addBlock(std::move(outer));
  const glm::dvec3 origin(3.0, -1.0, 2.0);
  Scene s = compiledScene("rotated-instance", wrapper, origin, 480, 270);
  ASSERT_GT(s.image.width, 0);

  const HniRayCaster caster(s.image, s.originM);
  const RenderOutput cpu = renderHni(caster, s.camera, {});
  auto renderer = openRenderer();
  ASSERT_TRUE(renderer);
  ASSERT_TRUE(renderer->addHni(facade.image, origin + glm::dvec3(0.0, 0.0, size.x), rotation).ok());
  auto gl = renderer->render(s.camera, {});
  ASSERT_TRUE(gl.ok()) << gl.error().message;
  const Agreement a = compareFrames(outputDir("mesh"), s.name, cpu.colour, cpu.windowDepth, gl->colour,
                                    gl->windowDepth, 2, 99.9);
  EXPECT_GE(a.withinPct, 99.9);
  EXPECT_EQ(a.depthOutOfRange, 0);
  EXPECT_GT(a.depthPixels, 10000);
}

TEST(MixedFrame, InvalidHniIsRejected) {
  // A hostile image never reaches the shader: the renderer validates it first.
  Image garbage(16, 4);
  auto renderer = openRenderer();
  ASSERT_TRUE(renderer);
  const Status s = renderer->addHni(garbage, glm::dvec3(0.0));
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("invalid HNI"), std::string::npos) << s.error().message;
}

}  // namespace
}  // namespace nut::gltest
