// Sizes of the converter's output against the source mesh: the HNI PNG (blocks chosen
// automatically, and without extraction where that fits an HNI) against the OBJ + MTL files, a
// binary glTF compressed with meshoptimizer and gzip (mesh_size.hpp), and the decoded mesh in
// memory. Prints one Markdown table row per sample (docs/CONVERTER.md, "Sizes") and checks the
// GLB it measures decodes back to the mesh.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>

#include <glm/geometric.hpp>

#include <converter/convert.hpp>
#include <converter/mesh_size.hpp>
#include <scene/city.hpp>
#include <scene/glb.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

namespace fs = std::filesystem;

TriangleMesh carparkMovedEast() {
  auto obj = scene::readObj(std::string(NUT_SOURCE_DIR) + "/samples/obj/carpark.obj");
  EXPECT_TRUE(obj.ok());
  TriangleMesh mesh = obj.ok() ? mergeMeshes(obj->objects, "carpark").value() : TriangleMesh{};
  for (glm::dvec3& p : mesh.positions) p += glm::dvec3(1e6, 0, 0);
  return mesh;
}

double quantizationStep(const TriangleMesh& mesh) {
  const WorldBox box = mesh.bounds();
  const glm::dvec3 extent = box.max - box.min;
  return std::max({extent.x, extent.y, extent.z}) / 65535.0;
}

// Reads `mesh` back from its GLB with the scene's reader: each triangle keeps its material and
// its centroid lies within `step` of a source triangle's of that material (the encoder reorders
// triangles and may start each at another corner).
void expectDecodesBack(const TriangleMesh& mesh, double step) {
  const std::vector<std::uint8_t> glb = meshoptGlb(mesh);
  std::vector<std::string> warnings;
  auto decoded = scene::readGlbBytes(glb, "carpark.glb", warnings);
  ASSERT_TRUE(decoded.ok()) << decoded.error().message;
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(decoded->triangles.size(), mesh.triangles.size());
  std::map<std::array<std::uint8_t, 4>, std::vector<glm::dvec3>> sourceCentroids;
  const auto centroid = [](const TriangleMesh& m, std::size_t t) {
    const auto& [a, b, c] = m.triangles[t];
    return (m.positions[a] + m.positions[b] + m.positions[c]) / 3.0;
  };
  const auto colourOf = [](const TriangleMesh& m, std::size_t t) {
    const Material& mat = m.materials[m.triangleMaterial[t]];
    return std::array<std::uint8_t, 4>{mat.r, mat.g, mat.b, mat.opacity};
  };
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    sourceCentroids[colourOf(mesh, t)].push_back(centroid(mesh, t));
  std::size_t unmatched = 0;
  for (std::size_t t = 0; t < decoded->triangles.size(); ++t) {
    const auto it = sourceCentroids.find(colourOf(*decoded, t));
    const glm::dvec3 c = centroid(*decoded, t);
    const bool matched = it != sourceCentroids.end() &&
                         std::any_of(it->second.begin(), it->second.end(),
                                     [&](const glm::dvec3& s) { return glm::length(s - c) <= step; });
    unmatched += matched ? 0 : 1;
  }
  EXPECT_EQ(unmatched, 0u);
}

TEST(MeshSize, TheGlbDecodesBackToTheTriangles) {
  // The carpark moved a million metres east: the GLB's node carries the offset in double, its
  // 16-bit positions the rest, within one quantization step.
  const TriangleMesh mesh = carparkMovedEast();
  expectDecodesBack(mesh, quantizationStep(mesh));
  const MeshSizes sizes = measureMesh(mesh);
  EXPECT_LT(sizes.glbGzipBytes, sizes.glbBytes);
  EXPECT_LT(sizes.glbBytes, sizes.decodedBytes);
}

TEST(MeshSize, AMeshKilometresAcrossKeepsTheStepOfEachPart) {
  // Two carparks 5 km apart, as a district of buildings far apart is: one 16-bit grid over both
  // would step 7.6 cm; each 256 m tile has its own node and grid, so the step stays the carpark's.
  const TriangleMesh one = carparkMovedEast();
  TriangleMesh moved = one;
  for (glm::dvec3& p : moved.positions) p += glm::dvec3(3000, 0, 4000);
  const TriangleMesh both = mergeMeshes(std::vector<const TriangleMesh*>{&one, &moved}, "carparks").value();
  ASSERT_GT(quantizationStep(both), 0.05);
  expectDecodesBack(both, quantizationStep(one));
}

class SampleSize : public ::testing::TestWithParam<std::string> {};

TEST_P(SampleSize, Table) {
  const std::string path = std::string(NUT_SOURCE_DIR) + "/samples/obj/" + GetParam() + ".obj";
  auto obj = scene::readObj(path);
  ASSERT_TRUE(obj.ok());
  const std::uintmax_t objBytes =
      fs::file_size(path) + fs::file_size(fs::path(path).replace_extension(".mtl"));
  const TriangleMesh mesh = mergeMeshes(obj->objects, GetParam()).value();
  const MeshSizes sizes = measureMesh(mesh);
  // As `nut convert IN.obj -o OUT.png` does it: one HNI of the whole file, the street's four
  // buildings included.
  auto c = convertMesh(mesh);
  ASSERT_TRUE(c.ok()) << c.error().message;
  ASSERT_TRUE(writeConversion(*c, testing::outputDir("converter_size") + "/" + scene::safeFileStem(mesh.name) + ".png", "").ok());
  const auto png = static_cast<long long>(c->report.pngBytes);
  std::printf("| %s | %zu | %ju | %ju | %ju | %lld | %.0fx | %.2f | %zu | %s |\n", GetParam().c_str(), mesh.triangles.size(),
              objBytes, static_cast<std::uintmax_t>(sizes.glbGzipBytes), static_cast<std::uintmax_t>(sizes.decodedBytes), png,
              static_cast<double>(sizes.decodedBytes) / static_cast<double>(png),
              static_cast<double>(png) / static_cast<double>(sizes.glbGzipBytes), c->complement.triangles.size(),
              c->report.blockMode.c_str());
  EXPECT_LT(png, static_cast<long long>(objBytes) / 10);
  // The size target (docs/CONVERTER.md, Sizes): at most half the bytes of the meshopt + gzip GLB (the HNI alone; what the
  // complementary mesh adds is in its own column).
  EXPECT_LE(2 * png, static_cast<long long>(sizes.glbGzipBytes)) << GetParam();
  if (obj->objects.size() < 2) return;
  // `-o FOLDER` writes one HNI per object instead (a city); the target holds for their sum too.
  long long perObjectPng = 0;
  for (const TriangleMesh& part : obj->objects) {
    auto p = convertMesh(part);
    ASSERT_TRUE(p.ok()) << p.error().message;
    ASSERT_TRUE(writeConversion(*p, testing::outputDir("converter_size") + "/" + scene::safeFileStem(part.name) + ".png", "").ok());
    perObjectPng += static_cast<long long>(p->report.pngBytes);
  }
  std::printf("%s, one HNI per object (%zu): %lld bytes PNG, %.0fx below the decoded mesh, %.2f of meshopt+gzip\n",
              GetParam().c_str(), obj->objects.size(), perObjectPng,
              static_cast<double>(sizes.decodedBytes) / static_cast<double>(perObjectPng),
              static_cast<double>(perObjectPng) / static_cast<double>(sizes.glbGzipBytes));
  EXPECT_LE(2 * perObjectPng, static_cast<long long>(sizes.glbGzipBytes)) << GetParam() << ", one HNI per object";
}

INSTANTIATE_TEST_SUITE_P(Samples, SampleSize, ::testing::Values("highrise", "street", "residential", "carpark", "house"));

}  // namespace
}  // namespace nut::converter
