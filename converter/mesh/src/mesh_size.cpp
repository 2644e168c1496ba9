// Meshoptimizer-compressed GLB of a mesh, and gzip (converter/mesh_size.hpp).
#include <converter/mesh_size.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include <glm/common.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <zlib.h>

namespace nut::converter {

namespace {

struct Quantized {
  std::uint16_t x, y, z, pad;
};

void append(std::vector<std::uint8_t>& out, const void* data, std::size_t size) {
  const auto* p = static_cast<const std::uint8_t*>(data);
  out.insert(out.end(), p, p + size);
}
void appendU32(std::vector<std::uint8_t>& out, std::uint32_t v) { append(out, &v, 4); }
void padTo4(std::vector<std::uint8_t>& out, std::uint8_t with) {
  while (out.size() % 4) out.push_back(with);
}

}  // namespace

std::vector<std::uint8_t> meshoptGlb(const Mesh& mesh) {
  const WorldBox box = mesh.bounds();
  const glm::dvec3 extent = glm::max(box.max - box.min, glm::dvec3(1e-9));
  const double scale = std::max({extent.x, extent.y, extent.z}) / 65535.0;  // one step, all axes (gltfpack)

  std::vector<std::uint8_t> bin;
  nlohmann::json bufferViews = nlohmann::json::array(), accessors = nlohmann::json::array(), primitives = nlohmann::json::array(),
                 materials = nlohmann::json::array();
  for (std::size_t m = 0; m < mesh.materials.size(); ++m) {
    // Triangles of this material, with their own compact vertex list.
    std::vector<unsigned int> indices;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      if (mesh.triangleMaterial[t] == m)
        for (std::uint32_t v : mesh.triangles[t]) indices.push_back(v);
    if (indices.empty()) continue;
    std::vector<Quantized> vertices;
    vertices.reserve(indices.size());
    for (unsigned int& i : indices) {
      const glm::dvec3 q = (mesh.positions[i] - box.min) / scale;
      vertices.push_back({static_cast<std::uint16_t>(std::lround(q.x)), static_cast<std::uint16_t>(std::lround(q.y)),
                          static_cast<std::uint16_t>(std::lround(q.z)), 0});
      i = static_cast<unsigned int>(vertices.size() - 1);
    }
    std::vector<unsigned int> remap(indices.size());
    const std::size_t unique = meshopt_generateVertexRemap(remap.data(), indices.data(), indices.size(), vertices.data(),
                                                           vertices.size(), sizeof(Quantized));
    std::vector<Quantized> compact(unique);
    meshopt_remapIndexBuffer(indices.data(), indices.data(), indices.size(), remap.data());
    meshopt_remapVertexBuffer(compact.data(), vertices.data(), vertices.size(), sizeof(Quantized), remap.data());
    meshopt_optimizeVertexCache(indices.data(), indices.data(), indices.size(), unique);
    meshopt_optimizeVertexFetch(compact.data(), indices.data(), indices.size(), compact.data(), unique, sizeof(Quantized));

    std::vector<unsigned char> encodedVertices(meshopt_encodeVertexBufferBound(unique, sizeof(Quantized)));
    encodedVertices.resize(meshopt_encodeVertexBuffer(encodedVertices.data(), encodedVertices.size(), compact.data(), unique,
                                                      sizeof(Quantized)));
    std::vector<unsigned char> encodedIndices(meshopt_encodeIndexBufferBound(indices.size(), unique));
    encodedIndices.resize(meshopt_encodeIndexBuffer(encodedIndices.data(), encodedIndices.size(), indices.data(), indices.size()));

    const auto view = [&](const std::vector<unsigned char>& data, std::size_t stride, std::size_t count, const char* mode) {
      const std::size_t offset = bin.size();
      append(bin, data.data(), data.size());
      padTo4(bin, 0);
      bufferViews.push_back({{"buffer", 0},
                             {"byteOffset", offset},
                             {"byteLength", data.size()},
                             {"extensions",
                              {{"EXT_meshopt_compression",
                                {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", data.size()}, {"byteStride", stride},
                                 {"count", count}, {"mode", mode}}}}}});
      return bufferViews.size() - 1;
    };
    const std::size_t positionView = view(encodedVertices, sizeof(Quantized), unique, "ATTRIBUTES");
    const std::size_t indexView = view(encodedIndices, 4, indices.size(), "TRIANGLES");
    glm::dvec3 lo(65535), hi(0);
    for (const Quantized& q : compact) {
      lo = glm::min(lo, glm::dvec3(q.x, q.y, q.z));
      hi = glm::max(hi, glm::dvec3(q.x, q.y, q.z));
    }
    accessors.push_back({{"bufferView", positionView}, {"componentType", 5123}, {"count", unique}, {"type", "VEC3"},
                         {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}});
    accessors.push_back({{"bufferView", indexView}, {"componentType", 5125}, {"count", indices.size()}, {"type", "SCALAR"}});
    const Material& mat = mesh.materials[m];
    materials.push_back({{"pbrMetallicRoughness",
                          {{"baseColorFactor", {mat.r / 255.0, mat.g / 255.0, mat.b / 255.0, mat.opacity / 255.0}}, {"metallicFactor", 0}}}});
    primitives.push_back({{"attributes", {{"POSITION", accessors.size() - 2}}}, {"indices", accessors.size() - 1},
                          {"material", materials.size() - 1}});
  }
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "nut mesh_size"}}},
      {"extensionsUsed", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"extensionsRequired", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"buffers", {{{"byteLength", bin.size()}}}},
      {"bufferViews", bufferViews},
      {"accessors", accessors},
      {"materials", materials},
      {"meshes", {{{"primitives", primitives}}}},
      {"nodes", {{{"mesh", 0}, {"translation", {box.min.x, box.min.y, box.min.z}}, {"scale", {scale, scale, scale}}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  std::vector<std::uint8_t> json;
  const std::string text = gltf.dump();
  append(json, text.data(), text.size());
  padTo4(json, ' ');
  std::vector<std::uint8_t> glb;
  appendU32(glb, 0x46546C67);  // "glTF"
  appendU32(glb, 2);
  appendU32(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  appendU32(glb, static_cast<std::uint32_t>(json.size()));
  appendU32(glb, 0x4E4F534A);  // "JSON"
  append(glb, json.data(), json.size());
  appendU32(glb, static_cast<std::uint32_t>(bin.size()));
  appendU32(glb, 0x004E4942);  // "BIN"
  append(glb, bin.data(), bin.size());
  return glb;
}

std::vector<std::uint8_t> gzip(const std::vector<std::uint8_t>& bytes) {
  z_stream z{};
  // windowBits 15 + 16: the gzip wrapper; memLevel 9, the most memory for the best ratio.
  if (deflateInit2(&z, Z_BEST_COMPRESSION, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY) != Z_OK) return {};
  std::vector<std::uint8_t> out(deflateBound(&z, static_cast<uLong>(bytes.size())) + 32);
  z.next_in = const_cast<Bytef*>(bytes.data());
  z.avail_in = static_cast<uInt>(bytes.size());
  z.next_out = out.data();
  z.avail_out = static_cast<uInt>(out.size());
  deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  return out;
}

MeshSizes measureMesh(const Mesh& mesh) {
  MeshSizes s;
  s.decodedBytes = 12ull * mesh.positions.size() + 12ull * mesh.triangles.size();
  const std::vector<std::uint8_t> glb = meshoptGlb(mesh);
  s.glbBytes = glb.size();
  s.glbGzipBytes = gzip(glb).size();
  return s;
}

}  // namespace nut::converter
