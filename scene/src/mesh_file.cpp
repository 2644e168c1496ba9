// A mesh file by its extension (scene/mesh_file.hpp).
#include <scene/mesh_file.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <scene/glb.hpp>
#include <scene/obj.hpp>

namespace nut::scene {

bool isGlbPath(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension == ".glb";
}

Result<TriangleMesh> readMeshFile(const std::string& path, std::vector<std::string>& warnings) {
  return isGlbPath(path) ? readGlbMesh(path, warnings) : readObjMesh(path, warnings);
}

}  // namespace nut::scene
