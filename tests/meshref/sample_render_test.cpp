// The "compare ray-cast output against mesh renders" test on the CPU: every sample HNI is
// ray-cast (nut::HniRayCaster) and, independently, exported to OBJ (export-mesh), read back
// (render-mesh's reader) and ray-traced with Embree, from the same default camera. Tolerance: at
// least 99.5 % of pixels within 8/255, and the pixels that differ lie on silhouettes and edges.
// The renders and the diff image are written to the test output folder.
#include <gtest/gtest.h>

#include <filesystem>

#include <glm/common.hpp>

#include <meshref/embree_renderer.hpp>
#include <nut/hni.hpp>
#include <nut/image_compare.hpp>
#include <nut/mesh_export.hpp>
#include <nut/png_io.hpp>
#include <nut/raycast.hpp>
#include <scene/obj.hpp>

namespace nut {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 640, kHeight = 360;
constexpr int kThreshold = 8;

fs::path outputDir() {
  const fs::path dir = fs::path(NUT_TEST_OUTPUT_DIR) / "sample_render";
  fs::create_directories(dir);
  return dir;
}

// Whether pixel (x, y) of `image` is within one pixel of an edge: a neighbour whose colour differs
// by more than the threshold, or whose distance differs by more than 2 % (a silhouette).
bool nearEdge(const Image& image, const std::vector<float>& distance, int x, int y) {
  const std::size_t i = static_cast<std::size_t>(y) * kWidth + static_cast<std::size_t>(x);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      const int nx = x + dx, ny = y + dy;
      if (nx < 0 || ny < 0 || nx >= kWidth || ny >= kHeight) continue;
      const std::size_t j = static_cast<std::size_t>(ny) * kWidth + static_cast<std::size_t>(nx);
      for (int c = 0; c < 3; ++c)
        if (std::abs(image.at(x, y)[c] - image.at(nx, ny)[c]) > kThreshold) return true;
      const float a = distance[i], b = distance[j];
      if (std::isinf(a) != std::isinf(b) || std::abs(a - b) > 0.02f * std::min(a, b)) return true;
    }
  return false;
}

class SampleRender : public ::testing::TestWithParam<std::string> {};

// A sample HNI and its hierarchy.
struct Sample {
  PngFile png;
  Hierarchy hierarchy;
};

Result<Sample> loadSample(const std::string& name) {
  auto png = readPng(std::string(NUT_SOURCE_DIR) + "/samples/hni/" + name + ".png");
  if (!png) return png.error();
  auto h = decode(png->image);
  if (!h) return h.error();
  return Sample{std::move(*png), std::move(*h)};
}

TEST_P(SampleRender, RayCastMatchesEmbreeOnTheExportedMesh) {
  const std::string name = GetParam();
  auto sample = loadSample(name);
  ASSERT_TRUE(sample.ok()) << sample.error().message;
  const PngFile& png = sample->png;
  const Hierarchy& h = sample->hierarchy;

  // export-mesh, then render-mesh's reader.
  auto exported = exportMesh(h, png.text.originM);
  ASSERT_TRUE(exported.ok()) << exported.error().message;
  const fs::path obj = outputDir() / (name + ".obj");
  ASSERT_TRUE(writeObj(obj.string(), *exported).ok());
  std::vector<std::string> warnings;
  auto mesh = scene::readObjMesh(obj.string(), warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  auto embree = meshref::EmbreeRenderer::create(*mesh);
  ASSERT_TRUE(embree.ok()) << embree.error().message;

  // The default cameras of `nut render` and `nut render-mesh` are fitted to these two boxes.
  auto content = contentBounds(h, png.text.originM);
  ASSERT_TRUE(content.ok());
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(content->min[a], embree->bounds().min[a], 1e-6) << name << " axis " << a;
    EXPECT_NEAR(content->max[a], embree->bounds().max[a], 1e-6) << name << " axis " << a;
  }
  const Camera camera = fitCamera(*content, kWidth, kHeight);

  const HniRayCaster caster(png.image, png.text.originM);
  for (const Lookup lookup : {Lookup::Heuristic, Lookup::Exact}) {
    const char* mode = lookup == Lookup::Exact ? "exact" : "heuristic";
    RayCastOptions options;
    options.lookup = lookup;
    const RenderOutput nut = renderHni(caster, camera, options);
    const meshref::MeshRenderOutput reference = embree->render(camera);
    auto diff = nut::compareImages(nut.colour, reference.colour, kThreshold);
    ASSERT_TRUE(diff.ok());

    long long offEdge = 0;
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const std::uint8_t* p = nut.colour.at(x, y);
        const std::uint8_t* q = reference.colour.at(x, y);
        const bool differs = std::max({std::abs(p[0] - q[0]), std::abs(p[1] - q[1]), std::abs(p[2] - q[2])}) > kThreshold;
        if (differs && !nearEdge(reference.colour, reference.distanceM, x, y) && !nearEdge(nut.colour, nut.distanceM, x, y))
          ++offEdge;
      }
    const std::string stem = (outputDir() / (name + "." + mode)).string();
    const bool pass = diff->differingPct <= 0.5 && offEdge == 0;
    if (!pass) {
      (void)writePng(stem + ".actual.png", nut.colour);
      (void)writePng(stem + ".mesh.png", reference.colour);
      (void)writePng(stem + ".diff.png", diff->diff);
    }
    std::printf("%s %s: %.3f %% of %lld pixels differ by more than %d/255 (%lld off edges), rms %.2f\n", name.c_str(),
                mode, diff->differingPct, static_cast<long long>(diff->pixels), kThreshold, offEdge, diff->rms);
    EXPECT_LE(diff->differingPct, 0.5) << name << " " << mode << ": see " << stem << ".diff.png";
    EXPECT_EQ(offEdge, 0) << name << " " << mode << ": differing pixels away from any edge; see " << stem << ".diff.png";
  }
}

TEST_P(SampleRender, ContentBoundsAreTheCoarseMeshVertexBoundsToTheBit) {
  // The bounds walk skips every cell, row, layer and tile that the bounds found so far already
  // hold (most of a sample's instances: the building's storeys and bays); the box must still be
  // the one the export's vertices give, bit for bit, quadrics at one segment per quarter.
  const std::string name = GetParam();
  auto sample = loadSample(name);
  ASSERT_TRUE(sample.ok()) << sample.error().message;
  const PngFile& png = sample->png;
  const Hierarchy& h = sample->hierarchy;
  MeshExportOptions coarse;
  coarse.minSegmentsPerQuarter = coarse.maxSegmentsPerQuarter = 1;
  auto mesh = exportMesh(h, png.text.originM, coarse);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_FALSE(mesh->positions.empty());
  glm::dvec3 lo = mesh->positions.front(), hi = lo;
  for (const glm::dvec3& p : mesh->positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  auto content = contentBounds(h, png.text.originM);
  ASSERT_TRUE(content.ok()) << content.error().message;
  for (int a = 0; a < 3; ++a) {
    EXPECT_EQ(content->min[a], lo[a]) << name << " axis " << a;
    EXPECT_EQ(content->max[a], hi[a]) << name << " axis " << a;
  }
}

TEST_P(SampleRender, EmbreePacketsAndStreamsGiveTheOneRayImage) {
  // The peer of the speed comparison is the fastest of Embree's ray modes, so each must draw the
  // same picture as one ray at a time: at a size that is no multiple of the packet or the tile,
  // from the default camera and from a close-up, at one and two threads.
  const std::string name = GetParam();
  auto sample = loadSample(name);
  ASSERT_TRUE(sample.ok()) << sample.error().message;
  auto mesh = exportMesh(sample->hierarchy, sample->png.text.originM);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  auto embree = meshref::EmbreeRenderer::create(*mesh);
  ASSERT_TRUE(embree.ok()) << embree.error().message;
  Camera close = fitCamera(embree->bounds(), 203, 117);
  close.eye = close.target + 0.3 * (close.eye - close.target);
  for (const Camera& camera : {fitCamera(embree->bounds(), 203, 117), close}) {
    const meshref::MeshRenderOutput single = embree->render(camera, 1);
    for (const auto rays : {meshref::EmbreeRays::Packet8, meshref::EmbreeRays::Packet16, meshref::EmbreeRays::Stream})
      for (const int threads : {1, 2}) {
        const meshref::MeshRenderOutput other = embree->render(camera, threads, nullptr, rays);
        const bool same = other.colour == single.colour && other.distanceM == single.distanceM;
        const std::string stem = (outputDir() / (name + ".rays" + std::to_string(static_cast<int>(rays)))).string();
        if (!same) {
          (void)writePng(stem + ".single.png", single.colour);
          (void)writePng(stem + ".other.png", other.colour);
        }
        EXPECT_TRUE(same) << name << ", ray mode " << static_cast<int>(rays) << ", " << threads << " threads: see "
                          << stem << ".*.png";
      }
  }
}

INSTANTIATE_TEST_SUITE_P(Samples, SampleRender, ::testing::Values("facade", "building", "solids", "rotations"));

}  // namespace
}  // namespace nut
