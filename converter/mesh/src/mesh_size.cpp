// Meshoptimizer-compressed GLB of a mesh, and gzip (converter/mesh_size.hpp).
#include <converter/mesh_size.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
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

// One material's triangles, quantized to 16 bits per axis on the mesh's box (one step for all
// axes, as gltfpack does), their vertices deduplicated, ordered for the vertex cache and fetch,
// and encoded by meshoptimizer.
struct EncodedPrimitive {
  std::vector<unsigned char> vertices, indices;
  std::size_t vertexCount = 0, indexCount = 0;
  glm::dvec3 lo{65535}, hi{0};  // quantized bounds, for the accessor
};

std::optional<EncodedPrimitive> encodePrimitive(const TriangleMesh& mesh, std::size_t material, const glm::dvec3& origin,
                                                double scale) {
  std::vector<unsigned int> indices;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    if (mesh.triangleMaterial[t] == material)
      for (std::uint32_t v : mesh.triangles[t]) indices.push_back(v);
  if (indices.empty()) return std::nullopt;
  std::vector<Quantized> vertices;
  vertices.reserve(indices.size());
  for (unsigned int& i : indices) {
    const glm::dvec3 q = (mesh.positions[i] - origin) / scale;
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
  meshopt_optimizeVertexFetch(compact.data(), indices.data(), indices.size(), compact.data(), unique,
                              sizeof(Quantized));

  EncodedPrimitive out;
  out.vertexCount = unique;
  out.indexCount = indices.size();
  out.vertices.resize(meshopt_encodeVertexBufferBound(unique, sizeof(Quantized)));
  out.vertices.resize(
      meshopt_encodeVertexBuffer(out.vertices.data(), out.vertices.size(), compact.data(), unique, sizeof(Quantized)));
  out.indices.resize(meshopt_encodeIndexBufferBound(indices.size(), unique));
  out.indices.resize(meshopt_encodeIndexBuffer(out.indices.data(), out.indices.size(), indices.data(), indices.size()));
  for (const Quantized& q : compact) {
    out.lo = glm::min(out.lo, glm::dvec3(q.x, q.y, q.z));
    out.hi = glm::max(out.hi, glm::dvec3(q.x, q.y, q.z));
  }
  return out;
}

// The binary chunk and the glTF objects that describe it.
struct GltfParts {
  std::vector<std::uint8_t> bin;
  std::size_t fallbackBytes = 0;  // the decoded views' size
  nlohmann::json bufferViews = nlohmann::json::array(), accessors = nlohmann::json::array(),
                 primitives = nlohmann::json::array(), materials = nlohmann::json::array();

  // Appends meshoptimizer-encoded data as a buffer view; returns its index. As the extension
  // asks, the view itself describes the decoded data (count x stride bytes, a vertex view's
  // stride stated) in buffer 1, the fallback, which holds no bytes; the extension points at the
  // encoded bytes in buffer 0, the BIN chunk.
  std::size_t addMeshoptView(const std::vector<unsigned char>& data, std::size_t stride, std::size_t count,
                             const char* mode) {
    const std::size_t offset = bin.size();
    append(bin, data.data(), data.size());
    padTo4(bin, 0);
    nlohmann::json view = {{"buffer", 1},
                           {"byteOffset", fallbackBytes},
                           {"byteLength", count * stride},
                           {"extensions",
                            {{"EXT_meshopt_compression",
                              {{"buffer", 0},
                               {"byteOffset", offset},
                               {"byteLength", data.size()},
                               {"byteStride", stride},
                               {"count", count},
                               {"mode", mode}}}}}};
    if (std::string(mode) == "ATTRIBUTES") view["byteStride"] = stride;
    fallbackBytes += (count * stride + 3) / 4 * 4;
    bufferViews.push_back(std::move(view));
    return bufferViews.size() - 1;
  }

  void addPrimitive(const EncodedPrimitive& p, const Material& mat) {
    const std::size_t positionView = addMeshoptView(p.vertices, sizeof(Quantized), p.vertexCount, "ATTRIBUTES");
    const std::size_t indexView = addMeshoptView(p.indices, 4, p.indexCount, "TRIANGLES");
    accessors.push_back({{"bufferView", positionView},
                         {"componentType", 5123},
                         {"count", p.vertexCount},
                         {"type", "VEC3"},
                         {"min", {p.lo.x, p.lo.y, p.lo.z}},
                         {"max", {p.hi.x, p.hi.y, p.hi.z}}});
    accessors.push_back(
        {{"bufferView", indexView}, {"componentType", 5125}, {"count", p.indexCount}, {"type", "SCALAR"}});
    materials.push_back({{"pbrMetallicRoughness",
                          {{"baseColorFactor", {mat.r / 255.0, mat.g / 255.0, mat.b / 255.0, mat.opacity / 255.0}},
                           {"metallicFactor", 0}}}});
    if (mat.opacity != 255) materials.back()["alphaMode"] = "BLEND";  // glTF ignores alpha otherwise
    primitives.push_back({{"attributes", {{"POSITION", accessors.size() - 2}}},
                          {"indices", accessors.size() - 1},
                          {"material", materials.size() - 1}});
  }
};

// The GLB container: header, JSON chunk (padded with spaces), binary chunk.
std::vector<std::uint8_t> glbOf(const nlohmann::json& gltf, const std::vector<std::uint8_t>& bin) {
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

}  // namespace

std::vector<std::uint8_t> meshoptGlb(const TriangleMesh& mesh) {
  const WorldBox box = mesh.bounds();
  const glm::dvec3 extent = glm::max(box.max - box.min, glm::dvec3(1e-9));
  const double scale = std::max({extent.x, extent.y, extent.z}) / 65535.0;  // one step, all axes (gltfpack)
  GltfParts parts;
  for (std::size_t m = 0; m < mesh.materials.size(); ++m)
    if (auto primitive = encodePrimitive(mesh, m, box.min, scale)) parts.addPrimitive(*primitive, mesh.materials[m]);
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "nut mesh_size"}}},
      {"extensionsUsed", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"extensionsRequired", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"buffers",
       {{{"byteLength", parts.bin.size()}},
        {{"byteLength", parts.fallbackBytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
      {"bufferViews", parts.bufferViews},
      {"accessors", parts.accessors},
      {"materials", parts.materials},
      {"meshes", {{{"primitives", parts.primitives}}}},
      {"nodes", {{{"mesh", 0}, {"translation", {box.min.x, box.min.y, box.min.z}}, {"scale", {scale, scale, scale}}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  return glbOf(gltf, parts.bin);
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

MeshSizes measureMesh(const TriangleMesh& mesh) {
  MeshSizes s;
  s.decodedBytes = 12ull * mesh.positions.size() + 12ull * mesh.triangles.size();
  const std::vector<std::uint8_t> glb = meshoptGlb(mesh);
  s.glbBytes = glb.size();
  s.glbGzipBytes = gzip(glb).size();
  return s;
}

}  // namespace nut::converter
