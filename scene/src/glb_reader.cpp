// The GLB reader (scene/glb.hpp): container, JSON, buffer views (meshopt-decoded once each),
// accessors, then the default scene's node tree, each triangle primitive placed by its node.
#include <scene/glb.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>

#include <meshoptimizer.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <nlohmann/json.hpp>

#include <nut/png_io.hpp>

namespace nut::scene {

namespace {

using Json = nlohmann::json;

constexpr std::uint32_t kGlbMagic = 0x46546C67;  // "glTF"
constexpr std::uint32_t kChunkJson = 0x4E4F534A;
constexpr std::uint32_t kChunkBin = 0x004E4942;
// A meshopt stream decodes to at most 64 times its size (two header bits per byte of a 16-vertex
// block); the bound is checked before the output is allocated.
constexpr std::uint64_t kMaxMeshoptExpansion = 64;
constexpr int kMaxNodeDepth = 64;

std::uint32_t u32At(std::span<const std::uint8_t> bytes, std::size_t offset) {
  std::uint32_t v;
  std::memcpy(&v, bytes.data() + offset, 4);
  return v;
}

const Json* member(const Json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// An optional unsigned member: nullopt when absent; an error text when present but not one.
struct Unsigned {
  std::optional<std::uint64_t> value;
  bool bad = false;
};
Unsigned unsignedMember(const Json& object, const char* key) {
  const Json* m = member(object, key);
  if (!m) return {};
  if (!m->is_number_unsigned()) return {std::nullopt, true};
  return {m->get<std::uint64_t>(), false};
}

// A fixed-length array of finite numbers, or nullopt.
template <std::size_t N>
std::optional<std::array<double, N>> numbers(const Json* j) {
  if (!j || !j->is_array() || j->size() != N) return std::nullopt;
  std::array<double, N> out{};
  for (std::size_t i = 0; i < N; ++i) {
    if (!(*j)[i].is_number()) return std::nullopt;
    out[i] = (*j)[i].get<double>();
    if (!std::isfinite(out[i])) return std::nullopt;
  }
  return out;
}

std::size_t componentBytes(std::uint64_t componentType) {
  switch (componentType) {
    case 5120:
    case 5121: return 1;  // byte, unsigned byte
    case 5122:
    case 5123: return 2;  // short, unsigned short
    case 5125:
    case 5126: return 4;  // unsigned int, float
    default: return 0;
  }
}

class Reader {
 public:
  Reader(std::string name, std::vector<std::string>& warnings) : name_(std::move(name)), warnings_(warnings) {
    mesh_.name = std::filesystem::path(name_).stem().string();
  }

  Result<TriangleMesh> read(std::span<const std::uint8_t> bytes) {
    if (Status s = container(bytes); !s) return s.error();
    if (Status s = checkVersion(); !s) return s.error();
    if (Status s = scene(); !s) return s.error();
    if (degenerate_ > 0)
      warnings_.push_back(name_ + ": " + std::to_string(degenerate_) +
                          " degenerate triangles (a repeated vertex) left out");
    if (mesh_.triangles.empty()) return fail("no triangles");
    return std::move(mesh_);
  }

 private:
  Error fail(const std::string& what) const { return Error{name_ + ": " + what}; }

  Status container(std::span<const std::uint8_t> bytes) {
    if (bytes.size() < 20)
      return fail("not a GLB file: " + std::to_string(bytes.size()) + " bytes, shorter than its header");
    if (u32At(bytes, 0) != kGlbMagic) return fail("not a GLB file (no glTF magic)");
    if (u32At(bytes, 4) != 2) return fail("GLB version " + std::to_string(u32At(bytes, 4)) + ", not 2");
    const std::uint64_t length = u32At(bytes, 8);
    if (length > bytes.size())
      return fail("truncated: the header declares " + std::to_string(length) + " bytes, the file has " +
                  std::to_string(bytes.size()));
    const std::uint64_t jsonLength = u32At(bytes, 12);
    if (u32At(bytes, 16) != kChunkJson) return fail("the first chunk is not JSON");
    if (20 + jsonLength > length) return fail("the JSON chunk runs past the end of the file");
    const auto* text = reinterpret_cast<const char*>(bytes.data() + 20);
    gltf_ = Json::parse(text, text + jsonLength, nullptr, false);
    if (gltf_.is_discarded() || !gltf_.is_object()) return fail("the JSON chunk is not a glTF JSON object");
    std::uint64_t next = 20 + ((jsonLength + 3) & ~std::uint64_t{3});
    if (next + 8 <= length && u32At(bytes, next + 4) == kChunkBin) {
      const std::uint64_t binLength = u32At(bytes, next);
      if (next + 8 + binLength > length) return fail("the BIN chunk runs past the end of the file");
      bin_ = bytes.subspan(next + 8, binLength);
    }
    return Ok{};
  }

  Status checkVersion() const {
    const Json* asset = member(gltf_, "asset");
    const Json* version = asset ? member(*asset, "version") : nullptr;
    if (!version || !version->is_string() || version->get<std::string>().rfind("2.", 0) != 0)
      return fail("not glTF 2.0 (asset.version)");
    if (const Json* required = member(gltf_, "extensionsRequired"); required && required->is_array())
      for (const Json& e : *required) {
        const std::string ext = e.is_string() ? e.get<std::string>() : "?";
        if (ext != "EXT_meshopt_compression" && ext != "KHR_mesh_quantization" && ext != "KHR_materials_unlit")
          return fail("requires the extension " + ext + ", which is not read");
      }
    return Ok{};
  }

  // The i-th element of a top-level array ("accessors", ...), or null.
  const Json* element(const char* array, std::uint64_t i) const {
    const Json* a = member(gltf_, array);
    return a && a->is_array() && i < a->size() ? &(*a)[i] : nullptr;
  }

  Result<std::span<const std::uint8_t>> buffer(std::uint64_t index) const {
    const Json* b = element("buffers", index);
    if (!b) return fail("buffer " + std::to_string(index) + " does not exist");
    if (member(*b, "uri")) return fail("buffer " + std::to_string(index) + " is external (uri), which is not read");
    if (index != 0) return fail("buffer " + std::to_string(index) + " has no data (only buffer 0 is the BIN chunk)");
    const Unsigned length = unsignedMember(*b, "byteLength");
    if (!length.value || *length.value > bin_.size())
      return fail("buffer 0 declares more bytes than the BIN chunk has");
    return bin_.first(*length.value);
  }

  // The bytes of buffer view `index`, decoded once if meshopt-compressed.
  Result<std::span<const std::uint8_t>> view(std::uint64_t index) {
    if (const auto it = decoded_.find(index); it != decoded_.end()) return std::span<const std::uint8_t>(it->second);
    const std::string where = "bufferView " + std::to_string(index);
    const Json* v = element("bufferViews", index);
    if (!v) return fail(where + " does not exist");
    const Json* extensions = member(*v, "extensions");
    const Json* meshopt = extensions ? member(*extensions, "EXT_meshopt_compression") : nullptr;
    const Json& source = meshopt ? *meshopt : *v;
    const Unsigned bufferIndex = unsignedMember(source, "buffer"), offset = unsignedMember(source, "byteOffset"),
                   length = unsignedMember(source, "byteLength");
    if (!bufferIndex.value || !length.value || offset.bad) return fail(where + ": no buffer or byteLength");
    auto data = buffer(*bufferIndex.value);
    if (!data) return data.error();
    const std::uint64_t start = offset.value.value_or(0);
    if (start > data->size() || *length.value > data->size() - start) return fail(where + " lies outside its buffer");
    const auto bytes = data->subspan(start, *length.value);
    if (!meshopt) return bytes;
    return decodeMeshopt(index, *meshopt, bytes);
  }

  Result<std::span<const std::uint8_t>> decodeMeshopt(std::uint64_t index, const Json& ext,
                                                      std::span<const std::uint8_t> bytes) {
    const std::string where = "bufferView " + std::to_string(index);
    const Unsigned stride = unsignedMember(ext, "byteStride"), count = unsignedMember(ext, "count");
    const Json* mode = member(ext, "mode");
    if (!stride.value || !count.value || !mode || !mode->is_string())
      return fail(where + ": EXT_meshopt_compression without byteStride, count or mode");
    if (const Json* filter = member(ext, "filter"); filter && !(filter->is_string() && *filter == "NONE"))
      return fail(where + ": the meshopt filter " + filter->dump() + " is not read");
    const std::uint64_t size = *count.value * *stride.value;
    if (*stride.value == 0 || *stride.value > 256 || size / *stride.value != *count.value ||
        size > kMaxMeshoptExpansion * bytes.size() + 4096)
      return fail(where + ": " + std::to_string(*count.value) + " elements of " + std::to_string(*stride.value) +
                  " bytes cannot come from " + std::to_string(bytes.size()) + " compressed bytes");
    std::vector<std::uint8_t> out(size);
    const std::string kind = mode->get<std::string>();
    int status = -1;
    if (kind == "ATTRIBUTES" && *stride.value % 4 == 0) {
      status = meshopt_decodeVertexBuffer(out.data(), *count.value, *stride.value, bytes.data(), bytes.size());
    } else if (kind == "TRIANGLES" && (*stride.value == 2 || *stride.value == 4) && *count.value % 3 == 0) {
      status = meshopt_decodeIndexBuffer(out.data(), *count.value, *stride.value, bytes.data(), bytes.size());
    } else if (kind == "INDICES" && (*stride.value == 2 || *stride.value == 4)) {
      status = meshopt_decodeIndexSequence(out.data(), *count.value, *stride.value, bytes.data(), bytes.size());
    } else {
      return fail(where + ": meshopt mode " + kind + " with a stride of " + std::to_string(*stride.value) +
                  " is not valid");
    }
    if (status != 0)
      return fail(where + ": the meshopt data is corrupt (decoder status " + std::to_string(status) + ")");
    return std::span<const std::uint8_t>(decoded_[index] = std::move(out));
  }

  // An accessor's elements as doubles, `components` per element, with its layout checked.
  Result<std::vector<double>> accessor(std::uint64_t index, const char* type, std::size_t components, bool indices) {
    const std::string where = "accessor " + std::to_string(index);
    const Json* a = element("accessors", index);
    if (!a) return fail(where + " does not exist");
    if (member(*a, "sparse")) return fail(where + " is sparse, which is not read");
    const Json* t = member(*a, "type");
    if (!t || *t != type) return fail(where + " is not a " + std::string(type));
    const Unsigned viewIndex = unsignedMember(*a, "bufferView"), offset = unsignedMember(*a, "byteOffset"),
                   countField = unsignedMember(*a, "count"), componentType = unsignedMember(*a, "componentType");
    if (!viewIndex.value || !countField.value || !componentType.value || offset.bad)
      return fail(where + ": no bufferView, count or componentType");
    const std::size_t bytesEach = componentBytes(*componentType.value);
    const bool integerIndex =
        *componentType.value == 5121 || *componentType.value == 5123 || *componentType.value == 5125;
    if (bytesEach == 0 || (indices && !integerIndex) || (!indices && *componentType.value == 5125))
      return fail(where + ": component type " + std::to_string(*componentType.value) + " is not valid here");
    const Json* normalizedMember = member(*a, "normalized");
    const bool normalized = normalizedMember && normalizedMember->is_boolean() && normalizedMember->get<bool>();
    if (*countField.value > 3 * kMaxGlbTriangles)
      return fail(where + ": " + std::to_string(*countField.value) + " elements, too many");
    auto data = view(*viewIndex.value);
    if (!data) return data.error();
    const Json* viewJson = element("bufferViews", *viewIndex.value);
    const std::size_t elementBytes = bytesEach * components;
    const Unsigned declaredStride = unsignedMember(*viewJson, "byteStride");
    const std::size_t stride = declaredStride.value ? *declaredStride.value : elementBytes;
    const std::uint64_t start = offset.value.value_or(0), count = *countField.value;
    if (count > 0) {
      // The last element ends at start + (count - 1) * stride + elementBytes, inside the view.
      const std::uint64_t room = start <= data->size() ? data->size() - start : 0;
      if (stride < elementBytes || room < elementBytes || (count - 1) > (room - elementBytes) / stride)
        return fail(where + " lies outside bufferView " + std::to_string(*viewIndex.value));
    }
    std::vector<double> out(count * components);
    for (std::uint64_t e = 0; e < count; ++e)
      for (std::size_t c = 0; c < components; ++c)
        out[e * components + c] =
            component(data->data() + start + e * stride + c * bytesEach, *componentType.value, normalized);
    return out;
  }

  static double component(const std::uint8_t* p, std::uint64_t type, bool normalized) {
    switch (type) {
      case 5120: {
        std::int8_t v;
        std::memcpy(&v, p, 1);
        return normalized ? std::max(v / 127.0, -1.0) : v;
      }
      case 5121: {
        std::uint8_t v = *p;
        return normalized ? v / 255.0 : v;
      }
      case 5122: {
        std::int16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? std::max(v / 32767.0, -1.0) : v;
      }
      case 5123: {
        std::uint16_t v;
        std::memcpy(&v, p, 2);
        return normalized ? v / 65535.0 : v;
      }
      case 5125: {
        std::uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
      }
      default: {
        float v;
        std::memcpy(&v, p, 4);
        return v;
      }
    }
  }

  // The mesh material of glTF material `index` (nullopt: the glTF default, white).
  Result<std::uint16_t> material(std::optional<std::uint64_t> index) {
    const std::int64_t key = index ? static_cast<std::int64_t>(*index) : -1;
    if (const auto it = materials_.find(key); it != materials_.end()) return it->second;
    Material m{255, 255, 255, 255, 0};
    std::string name = "default";
    if (index) {
      const Json* g = element("materials", *index);
      if (!g) return fail("material " + std::to_string(*index) + " does not exist");
      name = "material " + std::to_string(*index);
      if (const Json* n = member(*g, "name"); n && n->is_string()) name = n->get<std::string>();
      const Json* pbr = member(*g, "pbrMetallicRoughness");
      std::array<double, 4> factor{1, 1, 1, 1};
      if (const Json* f = pbr ? member(*pbr, "baseColorFactor") : nullptr) {
        const auto read = numbers<4>(f);
        if (!read) return fail("material " + std::to_string(*index) + ": baseColorFactor is not four numbers");
        factor = *read;
      }
      if (pbr && member(*pbr, "baseColorTexture"))
        warnings_.push_back(name_ + ": material " + std::to_string(*index) +
                            ": its base colour texture is not read; its colour factor is used");
      const auto byte = [](double x) {
        return static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(x, 0.0, 1.0)));
      };
      m = {byte(factor[0]), byte(factor[1]), byte(factor[2]), 255, 0};
      const Json* alphaMode = member(*g, "alphaMode");
      if (alphaMode && *alphaMode == "BLEND") m.opacity = byte(factor[3]);
      if (alphaMode && *alphaMode == "MASK") {
        const Json* cutoff = member(*g, "alphaCutoff");
        m.opacity = factor[3] >= (cutoff && cutoff->is_number() ? cutoff->get<double>() : 0.5) ? 255 : 0;
      }
    }
    if (mesh_.materials.size() >= kMaxMeshMaterials)
      return fail("more than " + std::to_string(kMaxMeshMaterials) + " materials");
    mesh_.materials.push_back(m);
    mesh_.materialNames.push_back(name);
    const auto added = static_cast<std::uint16_t>(mesh_.materials.size() - 1);
    materials_.emplace(key, added);
    return added;
  }

  Status primitive(const Json& p, const glm::dmat4& transform, const std::string& where) {
    const Json* modeMember = member(p, "mode");
    const std::uint64_t mode = modeMember && modeMember->is_number_unsigned() ? modeMember->get<std::uint64_t>() : 4;
    if (mode != 4) {
      warnings_.push_back(name_ + ": " + where + " draws points or lines (mode " + std::to_string(mode) +
                          "), left out");
      return Ok{};
    }
    const Json* attributes = member(p, "attributes");
    const Unsigned positionIndex = attributes ? unsignedMember(*attributes, "POSITION") : Unsigned{};
    if (!positionIndex.value) return fail(where + " has no POSITION");
    auto positions = accessor(*positionIndex.value, "VEC3", 3, false);
    if (!positions) return positions.error();
    const std::size_t vertexCount = positions->size() / 3;
    std::vector<double> indices;
    if (const Unsigned indexAccessor = unsignedMember(p, "indices"); indexAccessor.value) {
      auto read = accessor(*indexAccessor.value, "SCALAR", 1, true);
      if (!read) return read.error();
      indices = std::move(*read);
    } else {
      indices.resize(vertexCount);
      for (std::size_t i = 0; i < vertexCount; ++i) indices[i] = static_cast<double>(i);
    }
    if (indices.size() % 3 != 0)
      return fail(where + ": " + std::to_string(indices.size()) + " indices, not whole triangles");
    if (mesh_.triangles.size() + indices.size() / 3 > kMaxGlbTriangles)
      return fail("more than " + std::to_string(kMaxGlbTriangles) + " triangles");
    const Unsigned materialIndex = unsignedMember(p, "material");
    if (materialIndex.bad) return fail(where + ": its material is not an index");
    auto materialSlot = material(materialIndex.value);
    if (!materialSlot) return materialSlot.error();

    const std::size_t base = mesh_.positions.size();
    for (std::size_t v = 0; v < vertexCount; ++v) {
      const glm::dvec4 world =
          transform * glm::dvec4((*positions)[3 * v], (*positions)[3 * v + 1], (*positions)[3 * v + 2], 1.0);
      if (!std::isfinite(world.x) || !std::isfinite(world.y) || !std::isfinite(world.z))
        return fail(where + ": vertex " + std::to_string(v) + " is not a finite position");
      mesh_.positions.emplace_back(world);
    }
    for (std::size_t i = 0; i < indices.size(); i += 3) {
      std::array<std::uint32_t, 3> t{};
      for (std::size_t k = 0; k < 3; ++k) {
        if (indices[i + k] >= static_cast<double>(vertexCount))
          return fail(where + ": index " + std::to_string(static_cast<std::uint64_t>(indices[i + k])) + " past its " +
                      std::to_string(vertexCount) + " vertices");
        t[k] = static_cast<std::uint32_t>(base + static_cast<std::size_t>(indices[i + k]));
      }
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
        ++degenerate_;
        continue;
      }
      mesh_.triangles.push_back(t);
      mesh_.triangleMaterial.push_back(*materialSlot);
    }
    return Ok{};
  }

  static std::optional<glm::dmat4> localTransform(const Json& node) {
    if (const Json* matrix = member(node, "matrix")) {
      const auto m = numbers<16>(matrix);
      if (!m) return std::nullopt;
      glm::dmat4 out;
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) out[c][r] = (*m)[static_cast<std::size_t>(4 * c + r)];
      return out;
    }
    std::array<double, 3> translation{0, 0, 0}, scale{1, 1, 1};
    std::array<double, 4> rotation{0, 0, 0, 1};
    if (const Json* t = member(node, "translation")) {
      const auto read = numbers<3>(t);
      if (!read) return std::nullopt;
      translation = *read;
    }
    if (const Json* r = member(node, "rotation")) {
      const auto read = numbers<4>(r);
      if (!read) return std::nullopt;
      rotation = *read;
    }
    if (const Json* s = member(node, "scale")) {
      const auto read = numbers<3>(s);
      if (!read) return std::nullopt;
      scale = *read;
    }
    const glm::dquat q(rotation[3], rotation[0], rotation[1], rotation[2]);  // glTF stores x, y, z, w
    const double length = std::sqrt(glm::dot(q, q));
    const glm::dmat3 turn = length > 0 ? glm::mat3_cast(q / length) : glm::dmat3(1.0);
    glm::dmat4 out(1.0);
    for (int c = 0; c < 3; ++c)
      for (int r = 0; r < 3; ++r) out[c][r] = turn[c][r] * scale[static_cast<std::size_t>(c)];
    out[3] = glm::dvec4(translation[0], translation[1], translation[2], 1.0);
    return out;
  }

  Status node(std::uint64_t index, const glm::dmat4& parent, int depth) {
    const std::string where = "node " + std::to_string(index);
    if (depth > kMaxNodeDepth)
      return fail(where + ": the node tree is deeper than " + std::to_string(kMaxNodeDepth) + " (a cycle?)");
    const Json* n = element("nodes", index);
    if (!n) return fail(where + " does not exist");
    const auto local = localTransform(*n);
    if (!local) return fail(where + ": its matrix, translation, rotation or scale is not numbers");
    const glm::dmat4 transform = parent * *local;
    if (const Unsigned meshIndex = unsignedMember(*n, "mesh"); meshIndex.value) {
      const Json* m = element("meshes", *meshIndex.value);
      const Json* primitives = m ? member(*m, "primitives") : nullptr;
      if (!primitives || !primitives->is_array())
        return fail("mesh " + std::to_string(*meshIndex.value) + " does not exist or has no primitives");
      for (std::size_t p = 0; p < primitives->size(); ++p)
        if (Status s = primitive((*primitives)[p], transform,
                                 "mesh " + std::to_string(*meshIndex.value) + " primitive " + std::to_string(p));
            !s)
          return s;
    }
    if (const Json* children = member(*n, "children"); children && children->is_array())
      for (const Json& c : *children) {
        if (!c.is_number_unsigned()) return fail(where + ": a child is not a node index");
        if (Status s = node(c.get<std::uint64_t>(), transform, depth + 1); !s) return s;
      }
    return Ok{};
  }

  // The default scene's root nodes; without scenes, every node no other node holds.
  Status scene() {
    std::vector<std::uint64_t> roots;
    const Json* scenes = member(gltf_, "scenes");
    const Unsigned chosen = unsignedMember(gltf_, "scene");
    if (scenes && scenes->is_array() && !scenes->empty()) {
      const std::uint64_t s = chosen.value.value_or(0);
      const Json* nodes = s < scenes->size() ? member((*scenes)[s], "nodes") : nullptr;
      if (s >= scenes->size()) return fail("scene " + std::to_string(s) + " does not exist");
      if (nodes && nodes->is_array())
        for (const Json& n : *nodes)
          if (n.is_number_unsigned()) roots.push_back(n.get<std::uint64_t>());
    } else if (const Json* nodes = member(gltf_, "nodes"); nodes && nodes->is_array()) {
      std::vector<bool> isChild(nodes->size(), false);
      for (const Json& n : *nodes)
        if (const Json* children = member(n, "children"); children && children->is_array())
          for (const Json& c : *children)
            if (c.is_number_unsigned() && c.get<std::uint64_t>() < isChild.size())
              isChild[c.get<std::uint64_t>()] = true;
      for (std::uint64_t i = 0; i < nodes->size(); ++i)
        if (!isChild[i]) roots.push_back(i);
    }
    for (std::uint64_t r : roots)
      if (Status s = node(r, glm::dmat4(1.0), 0); !s) return s;
    return Ok{};
  }

  std::string name_;
  std::vector<std::string>& warnings_;
  Json gltf_;
  std::span<const std::uint8_t> bin_;
  std::map<std::uint64_t, std::vector<std::uint8_t>> decoded_;  // meshopt views by index
  std::map<std::int64_t, std::uint16_t> materials_;             // glTF material (-1: default) -> mesh
  TriangleMesh mesh_;
  std::size_t degenerate_ = 0;
};

}  // namespace

Result<TriangleMesh> readGlbBytes(std::span<const std::uint8_t> bytes, const std::string& name,
                                  std::vector<std::string>& warnings) {
  return Reader(name, warnings).read(bytes);
}

Result<TriangleMesh> readGlbMesh(const std::string& path, std::vector<std::string>& warnings) {
  auto text = readTextFile(path);
  if (!text) return text.error();
  return readGlbBytes(std::span(reinterpret_cast<const std::uint8_t*>(text->data()), text->size()), path, warnings);
}

}  // namespace nut::scene
