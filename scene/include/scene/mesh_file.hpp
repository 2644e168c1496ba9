// scene/mesh_file.hpp — a mesh file in either format the toolkit reads, by its extension: .glb
// (binary glTF, scene/glb.hpp), anything else OBJ + MTL (scene/obj.hpp). What reads a
// complementary mesh or a mesh to render calls this.
#pragma once

#include <string>
#include <vector>

#include <nut/error.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::scene {

// Every triangle of the file as one mesh; the readers' warnings are appended to `warnings`.
Result<TriangleMesh> readMeshFile(const std::string& path, std::vector<std::string>& warnings);

// Whether `path` names a binary glTF file (extension .glb, any case).
bool isGlbPath(const std::string& path);

}  // namespace nut::scene
