// meshref/obj.hpp — OBJ + MTL files as a plain triangle mesh for the mesh reference renderer.
//
// The mesh is what `nut render-mesh` draws and what NUT output is compared against, so it keeps
// the file's coordinates as they are (world metres, docs/RENDERING.md) in double precision and one
// material per triangle (the MTL diffuse colour Kd and opacity d / Tr).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>

namespace nut::meshref {

// The material of a face that names none, or whose MTL file is missing.
inline constexpr Material kDefaultMeshMaterial{200, 200, 200, 255, 0};

struct MeshMaterial {
  std::string name;  // as in the MTL file; "default" for kDefaultMeshMaterial
  Material material;
};

struct TriangleMesh {
  std::vector<glm::dvec3> positions;                    // world metres
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions
  std::vector<std::uint32_t> triangleMaterial;          // per triangle, index into materials
  std::vector<MeshMaterial> materials;
  WorldBox bounds;                                      // of the vertices that faces use
  std::vector<std::string> warnings;                    // one line each, naming the file
};

// Reads an OBJ file and the MTL files it names (looked up beside it). Polygons are split into
// triangle fans; faces with fewer than three vertices are dropped. Kd in 0..1 becomes the sRGB
// bytes round(255 * Kd) (clamped), the MTL opacity d (or 1 - Tr) becomes round(255 * d). A missing
// MTL file or unknown material name is a warning and gives kDefaultMeshMaterial.
//
// Errors name the file (and the line where it is known): a file that cannot be opened, a vertex
// coordinate that is not a finite number, a face index out of range, no faces at all.
Result<TriangleMesh> readObj(const std::string& path);

}  // namespace nut::meshref
