// Meshoptimizer-compressed GLB of a mesh, and gzip (converter/mesh_size.hpp).
#include <converter/mesh_size.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
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

// One material's triangles of one tile, quantized to 16 bits per axis on the tile's box (one step
// for all axes, as gltfpack does), their vertices deduplicated and ordered for the vertex cache
// and fetch.
struct Primitive {
  std::vector<Quantized> vertices;
  std::vector<unsigned int> indices;  // into vertices
  glm::dvec3 lo{65535}, hi{0};        // quantized bounds, for the accessor
};

std::optional<Primitive> quantizePrimitive(const TriangleMesh& mesh, std::size_t material, const glm::dvec3& origin,
                                           double scale) {
  Primitive out;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    if (mesh.triangleMaterial[t] == material)
      for (std::uint32_t v : mesh.triangles[t]) out.indices.push_back(v);
  if (out.indices.empty()) return std::nullopt;
  std::vector<Quantized> vertices;
  vertices.reserve(out.indices.size());
  for (unsigned int& i : out.indices) {
    const glm::dvec3 q = (mesh.positions[i] - origin) / scale;
    vertices.push_back({static_cast<std::uint16_t>(std::lround(q.x)), static_cast<std::uint16_t>(std::lround(q.y)),
                        static_cast<std::uint16_t>(std::lround(q.z)), 0});
    i = static_cast<unsigned int>(vertices.size() - 1);
  }
  std::vector<unsigned int> remap(out.indices.size());
  const std::size_t unique = meshopt_generateVertexRemap(remap.data(), out.indices.data(), out.indices.size(),
                                                         vertices.data(), vertices.size(), sizeof(Quantized));
  out.vertices.resize(unique);
  meshopt_remapIndexBuffer(out.indices.data(), out.indices.data(), out.indices.size(), remap.data());
  meshopt_remapVertexBuffer(out.vertices.data(), vertices.data(), vertices.size(), sizeof(Quantized), remap.data());
  meshopt_optimizeVertexCache(out.indices.data(), out.indices.data(), out.indices.size(), unique);
  meshopt_optimizeVertexFetch(out.vertices.data(), out.indices.data(), out.indices.size(), out.vertices.data(), unique,
                              sizeof(Quantized));
  for (const Quantized& q : out.vertices) {
    out.lo = glm::min(out.lo, glm::dvec3(q.x, q.y, q.z));
    out.hi = glm::max(out.hi, glm::dvec3(q.x, q.y, q.z));
  }
  return out;
}

// Every primitive's vertices in one stream and indices in another, each encoded by meshoptimizer
// (EXT_meshopt_compression) as one buffer view, as gltfpack lays them out: the JSON then names two
// views, and each primitive's accessors reach into them by offset.
struct GltfParts {
  std::vector<Quantized> vertices;
  std::vector<unsigned int> indices;  // each primitive's from 0
  std::size_t largestPrimitive = 0;   // vertices
  nlohmann::json accessors = nlohmann::json::array();

  // The primitive's accessors, and its glTF object with material `material` (an index into the
  // file's materials).
  nlohmann::json add(const Primitive& p, std::size_t material) {
    accessors.push_back({{"bufferView", 0},
                         {"byteOffset", vertices.size() * sizeof(Quantized)},
                         {"componentType", 5123},
                         {"count", p.vertices.size()},
                         {"type", "VEC3"},
                         {"min", {p.lo.x, p.lo.y, p.lo.z}},
                         {"max", {p.hi.x, p.hi.y, p.hi.z}}});
    accessors.push_back({{"bufferView", 1},
                         {"byteOffset", indices.size() * sizeof(unsigned int)},
                         {"componentType", 5125},
                         {"count", p.indices.size()},
                         {"type", "SCALAR"}});
    vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
    indices.insert(indices.end(), p.indices.begin(), p.indices.end());
    largestPrimitive = std::max(largestPrimitive, p.vertices.size());
    return {{"attributes", {{"POSITION", accessors.size() - 2}}},
            {"indices", accessors.size() - 1},
            {"material", material}};
  }

  // The BIN chunk and the two views. As the extension asks, a view describes the decoded data
  // (count x stride bytes) in buffer 1, the fallback, which holds no bytes; the extension points
  // at the encoded bytes in buffer 0, the BIN chunk.
  nlohmann::json views(std::vector<std::uint8_t>& bin, std::size_t& fallbackBytes) const {
    fallbackBytes = 0;
    if (vertices.empty()) return nlohmann::json::array();
    std::vector<unsigned char> encodedVertices(meshopt_encodeVertexBufferBound(vertices.size(), sizeof(Quantized)));
    encodedVertices.resize(meshopt_encodeVertexBuffer(encodedVertices.data(), encodedVertices.size(), vertices.data(),
                                                      vertices.size(), sizeof(Quantized)));
    std::vector<unsigned char> encodedIndices(meshopt_encodeIndexBufferBound(indices.size(), largestPrimitive));
    encodedIndices.resize(
        meshopt_encodeIndexBuffer(encodedIndices.data(), encodedIndices.size(), indices.data(), indices.size()));
    nlohmann::json out = nlohmann::json::array();
    const auto view = [&](const std::vector<unsigned char>& data, std::size_t stride, std::size_t count,
                          const char* mode) {
      const std::size_t offset = bin.size();
      append(bin, data.data(), data.size());
      padTo4(bin, 0);
      nlohmann::json v = {{"buffer", 1},
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
      if (std::string(mode) == "ATTRIBUTES") v["byteStride"] = stride;
      fallbackBytes += (count * stride + 3) / 4 * 4;
      out.push_back(std::move(v));
    };
    view(encodedVertices, sizeof(Quantized), vertices.size(), "ATTRIBUTES");
    view(encodedIndices, sizeof(unsigned int), indices.size(), "TRIANGLES");
    return out;
  }
};

nlohmann::json materialJson(const Material& mat) {
  nlohmann::json m = {{"pbrMetallicRoughness",
                       {{"baseColorFactor", {mat.r / 255.0, mat.g / 255.0, mat.b / 255.0, mat.opacity / 255.0}},
                        {"metallicFactor", 0}}}};
  if (mat.opacity != 255) m["alphaMode"] = "BLEND";  // glTF ignores alpha otherwise
  return m;
}

// The mesh's triangles grouped by the kTileM cube, counted from the mesh's minimum corner, their
// centroid lies in, each group a mesh of its own (positions 16 bits over the group's bounds: 4 mm
// steps at most, whatever the mesh's extent), in order of first triangle. A mesh within one cube's
// extent is one group.
constexpr double kTileM = 256.0;
std::vector<TriangleMesh> tiles(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return {};
  const WorldBox box = mesh.bounds();
  const glm::dvec3 extent = box.max - box.min;
  if (std::max({extent.x, extent.y, extent.z}) <= kTileM) return {mesh};
  std::map<std::array<std::int64_t, 3>, std::size_t> tileOf;
  std::vector<TriangleMesh> out;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const glm::dvec3 centroid = (mesh.positions[tri[0]] + mesh.positions[tri[1]] + mesh.positions[tri[2]]) / 3.0;
    std::array<std::int64_t, 3> key{};
    for (int a = 0; a < 3; ++a)
      key[static_cast<std::size_t>(a)] = static_cast<std::int64_t>(std::floor((centroid[a] - box.min[a]) / kTileM));
    auto [it, fresh] = tileOf.try_emplace(key, out.size());
    if (fresh) {
      out.emplace_back();
      out.back().materials = mesh.materials;
    }
    TriangleMesh& tile = out[it->second];
    const auto first = static_cast<std::uint32_t>(tile.positions.size());
    for (std::uint32_t v : tri) tile.positions.push_back(mesh.positions[v]);
    tile.triangles.push_back({first, first + 1, first + 2});
    tile.triangleMaterial.push_back(mesh.triangleMaterial[t]);
  }
  return out;
}

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
  GltfParts parts;
  nlohmann::json materials = nlohmann::json::array(), meshes = nlohmann::json::array(), nodes = nlohmann::json::array(),
                 roots = nlohmann::json::array();
  std::vector<std::int64_t> materialIndex(mesh.materials.size(), -1);
  for (const TriangleMesh& tile : tiles(mesh)) {
    const WorldBox box = tile.bounds();
    const glm::dvec3 extent = glm::max(box.max - box.min, glm::dvec3(1e-9));
    const double scale = std::max({extent.x, extent.y, extent.z}) / 65535.0;  // one step, all axes (gltfpack)
    nlohmann::json primitives = nlohmann::json::array();
    for (std::size_t m = 0; m < tile.materials.size(); ++m) {
      const auto primitive = quantizePrimitive(tile, m, box.min, scale);
      if (!primitive) continue;
      if (materialIndex[m] < 0) {
        materialIndex[m] = static_cast<std::int64_t>(materials.size());
        materials.push_back(materialJson(mesh.materials[m]));
      }
      primitives.push_back(parts.add(*primitive, static_cast<std::size_t>(materialIndex[m])));
    }
    roots.push_back(nodes.size());
    nodes.push_back({{"mesh", meshes.size()},
                     {"translation", {box.min.x, box.min.y, box.min.z}},
                     {"scale", {scale, scale, scale}}});
    meshes.push_back({{"primitives", std::move(primitives)}});
  }
  std::vector<std::uint8_t> bin;
  std::size_t fallbackBytes = 0;
  const nlohmann::json views = parts.views(bin, fallbackBytes);
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}, {"generator", "nut mesh_size"}}},
      {"extensionsUsed", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"extensionsRequired", {"EXT_meshopt_compression", "KHR_mesh_quantization"}},
      {"buffers",
       {{{"byteLength", bin.size()}},
        {{"byteLength", fallbackBytes}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}}},
      {"bufferViews", views},
      {"accessors", parts.accessors},
      {"materials", materials},
      {"meshes", meshes},
      {"nodes", nodes},
      {"scenes", {{{"nodes", roots}}}},
      {"scene", 0}};
  return glbOf(gltf, bin);
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
