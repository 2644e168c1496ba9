// The triangle mesh's measures and merging (nut/triangle_mesh.hpp).
#include <nut/triangle_mesh.hpp>

#include <limits>
#include <map>
#include <string>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

namespace nut {

WorldBox TriangleMesh::bounds() const {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  WorldBox box{glm::dvec3(kInfinity), glm::dvec3(-kInfinity)};
  for (const auto& t : triangles)
    for (std::uint32_t v : t) {
      box.min = glm::min(box.min, positions[v]);
      box.max = glm::max(box.max, positions[v]);
    }
  return box;
}

double TriangleMesh::area() const {
  double sum = 0;
  for (const auto& t : triangles)
    sum += 0.5 * glm::length(glm::cross(positions[t[1]] - positions[t[0]], positions[t[2]] - positions[t[0]]));
  return sum;
}

namespace {

// A material and its name, ordered so that a map can find an equal one.
struct MaterialKey {
  std::array<std::uint8_t, 5> value;
  std::string name;
  auto operator<=>(const MaterialKey&) const = default;
};

}  // namespace

Result<TriangleMesh> mergeMeshes(const std::vector<const TriangleMesh*>& meshes, const std::string& name) {
  TriangleMesh out;
  out.name = name;
  bool named = true;
  for (const TriangleMesh* mesh : meshes) named = named && mesh->materialNames.size() == mesh->materials.size();
  std::map<MaterialKey, std::uint16_t> indexOf;
  std::vector<std::uint16_t> renumber;
  for (const TriangleMesh* mesh : meshes) {
    renumber.clear();
    for (std::size_t m = 0; m < mesh->materials.size(); ++m) {
      const Material& mat = mesh->materials[m];
      MaterialKey key{{mat.r, mat.g, mat.b, mat.opacity, mat.reflectance}, named ? mesh->materialNames[m] : std::string()};
      auto [it, added] = indexOf.try_emplace(std::move(key), static_cast<std::uint16_t>(out.materials.size()));
      if (added) {
        if (out.materials.size() == kMaxMeshMaterials)
          return Error{"merging meshes: more than " + std::to_string(kMaxMeshMaterials) + " distinct materials"};
        out.materials.push_back(mat);
        if (named) out.materialNames.push_back(mesh->materialNames[m]);
      }
      renumber.push_back(it->second);
    }
    const auto firstVertex = static_cast<std::uint32_t>(out.positions.size());
    out.positions.insert(out.positions.end(), mesh->positions.begin(), mesh->positions.end());
    for (const auto& t : mesh->triangles) out.triangles.push_back({t[0] + firstVertex, t[1] + firstVertex, t[2] + firstVertex});
    for (std::uint16_t m : mesh->triangleMaterial) out.triangleMaterial.push_back(renumber[m]);
  }
  return out;
}

Result<TriangleMesh> mergeMeshes(const std::vector<TriangleMesh>& meshes, const std::string& name) {
  std::vector<const TriangleMesh*> pointers;
  for (const TriangleMesh& m : meshes) pointers.push_back(&m);
  return mergeMeshes(pointers, name);
}

}  // namespace nut
