// nut/triangle_mesh.hpp — the one triangle-mesh type of the toolkit: world metres in double
// precision (y up, docs/RENDERING.md; a city coordinate near 10^6 m keeps its millimetres) and one
// material per triangle.
//
// Every mesh is one of these: what the OBJ reader gives (scene/obj.hpp), what the converter works
// on and leaves as the complementary mesh, what exportMesh makes of an HNI, and what the Embree
// reference and the GL rasteriser draw. It lives in the core because exportMesh makes it.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>

namespace nut {

// The material of faces that name none, or name one the MTL files do not define.
inline constexpr Material kDefaultMaterial{200, 200, 200, 255, 0};

struct TriangleMesh {
  std::string name;                                     // object name, file stem, or empty
  std::vector<glm::dvec3> positions;                    // world metres, y up
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions
  std::vector<std::uint16_t> triangleMaterial;          // per triangle, index into materials
  std::vector<Material> materials;
  std::vector<std::string> materialNames;               // parallel to materials, or empty

  // Bounds of the vertices that triangles use; min > max for a mesh without triangles.
  WorldBox bounds() const;
  // Sum of triangle areas, m^2.
  double area() const;
};

// Materials a mesh can have: triangleMaterial is 16-bit, as the HNI material index is.
inline constexpr std::size_t kMaxMeshMaterials = 65536;

// The meshes as one, named `name`: positions and triangles appended in order. Materials are
// merged by value and name, first seen first: the objects of one OBJ file, which share its
// material list, keep that list as it is. Materials without names (an exported HNI's) merge by
// value alone. Error: more than kMaxMeshMaterials distinct materials.
Result<TriangleMesh> mergeMeshes(const std::vector<const TriangleMesh*>& meshes, const std::string& name = {});
// The same for meshes held by value (the objects of an OBJ file).
Result<TriangleMesh> mergeMeshes(const std::vector<TriangleMesh>& meshes, const std::string& name = {});

}  // namespace nut
