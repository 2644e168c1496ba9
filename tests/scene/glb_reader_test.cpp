// The GLB reader: files built here byte by byte (the glTF spec's layout, tests/glb_bytes.hpp,
// and meshoptimizer's own encoders for compressed views), read back against positions worked out by hand, and malformed
// files each refused with one error naming the glTF object.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <meshoptimizer.h>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <scene/glb.hpp>
#include <scene/mesh_file.hpp>
#include <scene/obj.hpp>

#include "glb_bytes.hpp"
#include "test_files.hpp"

namespace nut::scene {
namespace {

using Json = nlohmann::json;

using testing::appendGlbBytes;
using testing::glbContainer;

// One triangle (0,0,0), (1,0,0), (0,1,0) as floats with 16-bit indices, drawn by two nodes: the
// first moved by (10, 0, 0) and turned 90 degrees about +y, the second scaled by 2 under a parent
// moved by (0, 5, 0). Material 0 is half-transparent red (BLEND).
struct Sample {
  Json gltf;
  std::vector<std::uint8_t> bin;
};
Sample triangleSample() {
  Sample s;
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[3] = {0, 1, 2};
  appendGlbBytes(s.bin, positions, sizeof positions);
  appendGlbBytes(s.bin, indices, sizeof indices);
  const double half = std::sqrt(0.5);
  s.gltf = {{"asset", {{"version", "2.0"}}},
            {"buffers", {{{"byteLength", s.bin.size()}}}},
            {"bufferViews",
             {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
              {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 6}}}},
            {"accessors",
             {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
              {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
            {"materials",
             {{{"name", "glass"},
               {"alphaMode", "BLEND"},
               {"pbrMetallicRoughness", {{"baseColorFactor", {1.0, 0.0, 0.0, 0.5}}}}}}},
            {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
            {"nodes",
             {{{"mesh", 0}, {"translation", {10, 0, 0}}, {"rotation", {0, half, 0, half}}},
              {{"translation", {0, 5, 0}}, {"children", {2}}},
              {{"mesh", 0}, {"scale", {2, 2, 2}}}}},
            {"scenes", {{{"nodes", {0, 1}}}}},
            {"scene", 0}};
  return s;
}

Result<TriangleMesh> read(const Sample& s, std::vector<std::string>& warnings) {
  const std::vector<std::uint8_t> bytes = glbContainer(s.gltf, s.bin);
  return readGlbBytes(bytes, "test.glb", warnings);
}

void expectNear(const glm::dvec3& a, const glm::dvec3& b, double tolerance = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tolerance);
  EXPECT_NEAR(a.y, b.y, tolerance);
  EXPECT_NEAR(a.z, b.z, tolerance);
}

TEST(GlbReader, NodesPlaceEachInstanceOfAMesh) {
  std::vector<std::string> warnings;
  auto mesh = read(triangleSample(), warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(mesh->triangles.size(), 2u);
  ASSERT_EQ(mesh->positions.size(), 6u);
  // A quarter turn about +y takes +x to -z: (1,0,0) -> (0,0,-1); +y stays.
  expectNear(mesh->positions[0], {10, 0, 0});
  expectNear(mesh->positions[1], {10, 0, -1});
  expectNear(mesh->positions[2], {10, 1, 0});
  // Scaled by 2 under a parent moved up by 5.
  expectNear(mesh->positions[3], {0, 5, 0});
  expectNear(mesh->positions[4], {2, 5, 0});
  expectNear(mesh->positions[5], {0, 7, 0});
  EXPECT_EQ(mesh->triangles[1], (std::array<std::uint32_t, 3>{3, 4, 5}));
  ASSERT_EQ(mesh->materials.size(), 1u);  // both instances share the glTF material
  EXPECT_EQ(mesh->materials[0], (Material{255, 0, 0, 128, 0}));
  EXPECT_EQ(mesh->materialNames[0], "glass");
  EXPECT_EQ(mesh->name, "test");
}

TEST(GlbReader, AlphaCountsOnlyUnderBlendAndAPrimitiveWithoutMaterialIsWhite) {
  Sample s = triangleSample();
  s.gltf["materials"][0].erase("alphaMode");  // OPAQUE, the default: alpha is ignored
  s.gltf["meshes"][0]["primitives"].push_back({{"attributes", {{"POSITION", 0}}}});  // no indices, no material
  std::vector<std::string> warnings;
  auto mesh = read(s, warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_EQ(mesh->materials.size(), 2u);
  EXPECT_EQ(mesh->materials[0], (Material{255, 0, 0, 255, 0}));
  EXPECT_EQ(mesh->materials[1], (Material{255, 255, 255, 255, 0}));
  EXPECT_EQ(mesh->triangles.size(), 4u);
}

// The triangle quantized to 16 bits (KHR_mesh_quantization) and both views compressed with
// meshoptimizer, as gltfpack writes them; the node's scale and translation undo the quantization.
TEST(GlbReader, ReadsMeshoptCompressedQuantizedViews) {
  struct Q {
    std::uint16_t x, y, z, pad;
  };
  const std::vector<Q> vertices = {{0, 0, 0, 0}, {65535, 0, 0, 0}, {0, 65535, 0, 0}, {65535, 65535, 0, 0}};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 2, 1, 3};
  std::vector<unsigned char> v(meshopt_encodeVertexBufferBound(vertices.size(), sizeof(Q)));
  v.resize(meshopt_encodeVertexBuffer(v.data(), v.size(), vertices.data(), vertices.size(), sizeof(Q)));
  std::vector<unsigned char> i(meshopt_encodeIndexBufferBound(indices.size(), vertices.size()));
  i.resize(meshopt_encodeIndexBuffer(i.data(), i.size(), indices.data(), indices.size()));
  std::vector<std::uint8_t> bin(v.begin(), v.end());
  while (bin.size() % 4) bin.push_back(0);
  const std::size_t indexOffset = bin.size();
  bin.insert(bin.end(), i.begin(), i.end());
  const auto meshopt = [](std::size_t offset, std::size_t length, int stride, int count, const char* mode) {
    return Json{{"EXT_meshopt_compression",
                 {{"buffer", 0},
                  {"byteOffset", offset},
                  {"byteLength", length},
                  {"byteStride", stride},
                  {"count", count},
                  {"mode", mode}}}};
  };
  const double step = 100.0 / 65535;  // a 100 m square at 1,000,000 m east
  const Json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"extensionsRequired", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"buffers", {{{"byteLength", bin.size() + (4 - bin.size() % 4) % 4}}}},
      {"bufferViews",
       {{{"buffer", 0},
         {"byteLength", 32},
         {"byteStride", 8},
         {"extensions", meshopt(0, v.size(), 8, 4, "ATTRIBUTES")}},
        {{"buffer", 0}, {"byteLength", 24}, {"extensions", meshopt(indexOffset, i.size(), 4, 6, "TRIANGLES")}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5123}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 1}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"nodes", {{{"mesh", 0}, {"translation", {1e6, 0, 0}}, {"scale", {step, step, step}}}}}};
  std::vector<std::string> warnings;
  const std::vector<std::uint8_t> bytes = glbContainer(gltf, bin);
  auto mesh = readGlbBytes(bytes, "quantized.glb", warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  ASSERT_EQ(mesh->triangles.size(), 2u);
  expectNear(mesh->positions[3], {1e6 + 100, 100, 0}, 1e-9);  // a double's step at 10^6 m is 1.2e-10
  // meshoptimizer keeps the order of triangles and their winding, but may start each elsewhere.
  const std::array<std::uint32_t, 3> t = mesh->triangles[1];
  EXPECT_TRUE(t == (std::array<std::uint32_t, 3>{2, 1, 3}) || t == (std::array<std::uint32_t, 3>{1, 3, 2}) ||
              t == (std::array<std::uint32_t, 3>{3, 2, 1}))
      << t[0] << " " << t[1] << " " << t[2];
}

// Each malformed file: the change made to the good sample, and the words its one error must hold.
struct Broken {
  const char* what;
  void (*change)(Sample&);
  const char* message;
};

const Broken kBroken[] = {
    {"no JSON object", [](Sample& s) { s.gltf = Json::array(); }, "not a glTF JSON object"},
    {"glTF 1", [](Sample& s) { s.gltf["asset"]["version"] = "1.0"; }, "not glTF 2.0"},
    {"Draco", [](Sample& s) { s.gltf["extensionsRequired"] = {"KHR_draco_mesh_compression"}; },
     "requires the extension KHR_draco_mesh_compression"},
    {"external buffer", [](Sample& s) { s.gltf["buffers"][0]["uri"] = "data.bin"; }, "buffer 0 is external (uri)"},
    {"view outside the buffer", [](Sample& s) { s.gltf["bufferViews"][1]["byteLength"] = 600; },
     "bufferView 1 lies outside its buffer"},
    {"accessor outside the view", [](Sample& s) { s.gltf["accessors"][0]["count"] = 4; },
     "accessor 0 lies outside bufferView 0"},
    {"index past the vertices", [](Sample& s) { s.bin[40] = 7; }, "index 7 past its 3 vertices"},
    {"NaN position",
     [](Sample& s) {
       const float nan = std::nanf("");
       std::memcpy(s.bin.data() + 4, &nan, 4);
     },
     "vertex 0 is not a finite position"},
    {"sparse accessor", [](Sample& s) { s.gltf["accessors"][0]["sparse"] = Json::object(); }, "accessor 0 is sparse"},
    {"float indices", [](Sample& s) { s.gltf["accessors"][1]["componentType"] = 5126; },
     "accessor 1: component type 5126 is not valid here"},
    {"a node its own child", [](Sample& s) { s.gltf["nodes"][1]["children"] = {1}; }, "deeper than 64 (a cycle?)"},
    {"a missing node", [](Sample& s) { s.gltf["scenes"][0]["nodes"] = {9}; }, "node 9 does not exist"},
    {"a rotation of text", [](Sample& s) { s.gltf["nodes"][0]["rotation"] = "up"; },
     "node 0: its matrix, translation, rotation or scale is not numbers"},
    {"corrupt meshopt data",
     [](Sample& s) {
       s.gltf["bufferViews"][0]["extensions"] = {
           {"EXT_meshopt_compression",
            {{"buffer", 0}, {"byteLength", 36}, {"byteStride", 12}, {"count", 3}, {"mode", "ATTRIBUTES"}}}};
     },
     "bufferView 0: the meshopt data is corrupt"},
    {"a meshopt count its bytes cannot hold",
     [](Sample& s) {
       s.gltf["bufferViews"][0]["extensions"] = {
           {"EXT_meshopt_compression",
            {{"buffer", 0}, {"byteLength", 36}, {"byteStride", 12}, {"count", 4000000000u}, {"mode", "ATTRIBUTES"}}}};
     },
     "cannot come from 36 compressed bytes"},
    {"a meshopt filter",
     [](Sample& s) {
       s.gltf["bufferViews"][0]["extensions"] = {{"EXT_meshopt_compression",
                                                  {{"buffer", 0},
                                                   {"byteLength", 36},
                                                   {"byteStride", 12},
                                                   {"count", 3},
                                                   {"mode", "ATTRIBUTES"},
                                                   {"filter", "OCTAHEDRAL"}}}};
     },
     "the meshopt filter \"OCTAHEDRAL\" is not read"},
    {"lines only", [](Sample& s) { s.gltf["meshes"][0]["primitives"][0]["mode"] = 1; }, "test.glb: no triangles"},
};

TEST(GlbReader, RefusesMalformedFilesNamingTheObject) {
  for (const Broken& b : kBroken) {
    Sample s = triangleSample();
    b.change(s);
    std::vector<std::string> warnings;
    auto mesh = read(s, warnings);
    ASSERT_FALSE(mesh.ok()) << b.what;
    EXPECT_NE(mesh.error().message.find(b.message), std::string::npos) << b.what << ": " << mesh.error().message;
    EXPECT_EQ(mesh.error().message.rfind("test.glb: ", 0), 0u) << b.what << ": " << mesh.error().message;
  }
}

TEST(GlbReader, RefusesABrokenContainer) {
  const std::vector<std::uint8_t> good = glbContainer(triangleSample().gltf, triangleSample().bin);
  std::vector<std::string> warnings;
  const auto error = [&](std::vector<std::uint8_t> bytes) {
    auto mesh = readGlbBytes(bytes, "c.glb", warnings);
    return mesh.ok() ? std::string("read") : mesh.error().message;
  };
  EXPECT_EQ(error({'h', 'e', 'l', 'l', 'o'}), "c.glb: not a GLB file: 5 bytes, shorter than its header");
  std::vector<std::uint8_t> bytes = good;
  bytes[0] = 'x';
  EXPECT_EQ(error(bytes), "c.glb: not a GLB file (no glTF magic)");
  bytes = good;
  bytes[4] = 1;
  EXPECT_EQ(error(bytes), "c.glb: GLB version 1, not 2");
  bytes = good;
  bytes.resize(good.size() - 8);
  EXPECT_NE(error(bytes).find("truncated: the header declares"), std::string::npos);
  bytes = good;
  bytes[12] = 0xFF, bytes[13] = 0xFF;  // the JSON chunk's length past the end
  EXPECT_EQ(error(bytes), "c.glb: the JSON chunk runs past the end of the file");
  // Every prefix of a good file is refused with an error, never read past its end.
  for (std::size_t n = 0; n < good.size(); ++n) {
    bytes = good;
    bytes.resize(n);
    EXPECT_NE(error(bytes), "read") << n << " bytes";
  }
}

// Triangles per material colour, and their area.
std::map<std::array<std::uint8_t, 4>, std::pair<std::size_t, double>> byColour(const TriangleMesh& mesh) {
  std::map<std::array<std::uint8_t, 4>, std::pair<std::size_t, double>> out;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Material& m = mesh.materials[mesh.triangleMaterial[t]];
    const auto& [a, b, c] = mesh.triangles[t];
    auto& slot = out[{m.r, m.g, m.b, m.opacity}];
    ++slot.first;
    slot.second +=
        0.5 * glm::length(glm::cross(mesh.positions[b] - mesh.positions[a], mesh.positions[c] - mesh.positions[a]));
  }
  return out;
}

TEST(GlbReader, ReadsWhatGltfpackWrites) {
  // tests/data/two_material_cube.cc.glb is `gltfpack -i two_material_cube.obj -o ... -cc` (gltfpack
  // 1.3.0, npm): quantized positions, 16-bit indices at offsets into shared views, meshopt views.
  const std::string data = std::string(NUT_SOURCE_DIR) + "/tests/data/";
  std::vector<std::string> warnings;
  auto glbMesh = readMeshFile(data + "two_material_cube.cc.glb", warnings);
  ASSERT_TRUE(glbMesh.ok()) << glbMesh.error().message;
  auto objMesh = readObjMesh(data + "two_material_cube.obj", warnings);
  ASSERT_TRUE(objMesh.ok()) << objMesh.error().message;
  const auto fromGlb = byColour(*glbMesh), fromObj = byColour(*objMesh);
  ASSERT_EQ(fromGlb.size(), fromObj.size());
  for (const auto& [colour, countAndArea] : fromObj) {
    ASSERT_TRUE(fromGlb.count(colour)) << int(colour[0]) << " " << int(colour[1]) << " " << int(colour[2]);
    EXPECT_EQ(fromGlb.at(colour).first, countAndArea.first);
    EXPECT_NEAR(fromGlb.at(colour).second, countAndArea.second, 1e-3);
  }
  const WorldBox a = glbMesh->bounds(), b = objMesh->bounds();
  expectNear(a.min, b.min, 1e-4);  // gltfpack's step here: 1 / 16383 m
  expectNear(a.max, b.max, 1e-4);
}

TEST(GlbReader, MeshFilesAreReadByTheirExtension) {
  const Sample s = triangleSample();
  const std::vector<std::uint8_t> bytes = glbContainer(s.gltf, s.bin);
  const std::string path = testing::writeTestFile("glb", "triangle.GLB", std::string(bytes.begin(), bytes.end()));
  EXPECT_TRUE(isGlbPath(path));
  EXPECT_FALSE(isGlbPath("house.obj"));
  std::vector<std::string> warnings;
  auto mesh = readMeshFile(path, warnings);
  ASSERT_TRUE(mesh.ok()) << mesh.error().message;
  EXPECT_EQ(mesh->triangles.size(), 2u);
  // The same bytes named .obj go to the OBJ reader, which finds no faces in them.
  const std::string asObj = testing::writeTestFile("glb", "triangle.obj", std::string(bytes.begin(), bytes.end()));
  EXPECT_FALSE(readMeshFile(asObj, warnings).ok());
}

}  // namespace
}  // namespace nut::scene
