// Sizes of the converter's output against the source mesh: the HNI PNG (blocks chosen
// automatically, and without extraction where that fits an HNI) against the OBJ + MTL files, a
// binary glTF compressed with meshoptimizer and gzip (mesh_size.hpp), and the decoded mesh in
// memory. Prints one Markdown table row per sample (docs/CONVERTER.md, "Sizes") and checks the
// GLB it measures decodes back to the mesh.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include <converter/convert.hpp>
#include <converter/mesh_size.hpp>
#include <scene/city.hpp>
#include <scene/obj.hpp>

#include "converter_support.hpp"

namespace nut::converter {
namespace {

namespace fs = std::filesystem;

TEST(MeshSize, TheGlbDecodesBackToTheTriangles) {
  auto obj = scene::readObj(std::string(NUT_SOURCE_DIR) + "/samples/obj/carpark.obj");
  ASSERT_TRUE(obj.ok());
  const TriangleMesh mesh = mergeMeshes(obj->objects, "carpark").value();
  const std::vector<std::uint8_t> glb = meshoptGlb(mesh);
  ASSERT_GT(glb.size(), 20u);
  std::uint32_t magic = 0, jsonLength = 0;
  std::memcpy(&magic, glb.data(), 4);
  std::memcpy(&jsonLength, glb.data() + 12, 4);
  EXPECT_EQ(magic, 0x46546C67u);
  EXPECT_EQ(jsonLength % 4, 0u);
  const MeshSizes sizes = measureMesh(mesh);
  EXPECT_LT(sizes.glbGzipBytes, sizes.glbBytes);
  EXPECT_LT(sizes.glbBytes, sizes.decodedBytes);
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
