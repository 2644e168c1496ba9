// tests/glb_bytes.hpp — GLB files for tests, written here from the glTF 2.0 spec's layout and
// independent of the code under test: the container around any JSON and binary chunk, and a
// TriangleMesh as plain float positions (relative to a node translation, so city coordinates keep
// their precision) with 32-bit indices, one primitive per material.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <nut/triangle_mesh.hpp>

namespace nut::testing {

inline void appendGlbBytes(std::vector<std::uint8_t>& out, const void* data, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  out.insert(out.end(), p, p + size);
}

inline void appendGlbU32(std::vector<std::uint8_t>& out, std::uint32_t v) { appendGlbBytes(out, &v, 4); }

// A GLB container: 12-byte header, the JSON chunk padded with spaces, the BIN chunk (when not
// empty) padded with zeros.
inline std::vector<std::uint8_t> glbContainer(const nlohmann::json& gltf, std::vector<std::uint8_t> bin) {
  std::string json = gltf.dump();
  while (json.size() % 4) json += ' ';
  while (bin.size() % 4) bin.push_back(0);
  std::vector<std::uint8_t> out;
  appendGlbU32(out, 0x46546C67);  // "glTF"
  appendGlbU32(out, 2);
  appendGlbU32(out, static_cast<std::uint32_t>(12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size())));
  appendGlbU32(out, static_cast<std::uint32_t>(json.size()));
  appendGlbU32(out, 0x4E4F534A);  // "JSON"
  appendGlbBytes(out, json.data(), json.size());
  if (!bin.empty()) {
    appendGlbU32(out, static_cast<std::uint32_t>(bin.size()));
    appendGlbU32(out, 0x004E4942);  // "BIN\0"
    appendGlbBytes(out, bin.data(), bin.size());
  }
  return out;
}

// The mesh as a GLB: each material's triangles one primitive, over the whole vertex list.
inline std::vector<std::uint8_t> meshAsGlb(const TriangleMesh& mesh) {
  const glm::dvec3 origin = mesh.bounds().min;
  std::vector<std::uint8_t> bin;
  for (const glm::dvec3& p : mesh.positions) {
    const float xyz[3] = {static_cast<float>(p.x - origin.x), static_cast<float>(p.y - origin.y),
                          static_cast<float>(p.z - origin.z)};
    appendGlbBytes(bin, xyz, sizeof xyz);
  }
  nlohmann::json views = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", bin.size()}}};
  nlohmann::json accessors = {
      {{"bufferView", 0}, {"componentType", 5126}, {"count", mesh.positions.size()}, {"type", "VEC3"}}};
  nlohmann::json primitives = nlohmann::json::array(), materials = nlohmann::json::array();
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
    const std::size_t offset = bin.size();
    std::size_t count = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      if (mesh.triangleMaterial[t] == m)
        for (std::uint32_t v : mesh.triangles[t]) appendGlbU32(bin, v), ++count;
    if (count == 0) continue;
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", 4 * count}});
    accessors.push_back(
        {{"bufferView", views.size() - 1}, {"componentType", 5125}, {"count", count}, {"type", "SCALAR"}});
    const Material& mat = mesh.materials[m];
    nlohmann::json material = {
        {"pbrMetallicRoughness",
         {{"baseColorFactor", {mat.r / 255.0, mat.g / 255.0, mat.b / 255.0, mat.opacity / 255.0}}}}};
    if (mat.opacity != 255) material["alphaMode"] = "BLEND";
    materials.push_back(material);
    primitives.push_back(
        {{"attributes", {{"POSITION", 0}}}, {"indices", accessors.size() - 1}, {"material", materials.size() - 1}});
  }
  const nlohmann::json gltf = {{"asset", {{"version", "2.0"}}},
                               {"buffers", {{{"byteLength", bin.size()}}}},
                               {"bufferViews", views},
                               {"accessors", accessors},
                               {"materials", materials},
                               {"meshes", {{{"primitives", primitives}}}},
                               {"nodes", {{{"mesh", 0}, {"translation", {origin.x, origin.y, origin.z}}}}},
                               {"scenes", {{{"nodes", {0}}}}}};
  return glbContainer(gltf, std::move(bin));
}

}  // namespace nut::testing
