// converter/mesh.hpp — the triangle mesh the converter works on, and the OBJ + MTL reader that
// makes it.
//
// Coordinates are world metres in double precision with y up (docs/RENDERING.md); a city
// coordinate near 10^6 m keeps its millimetres. One material per triangle (MTL Kd and d / Tr).
//
// The reader is our own rather than OpenMesh's (OpenMesh::IO): that one parses coordinates into
// floats (6 cm steps at 10^6 m), ignores `o` / `g` groups, and skips a vertex it cannot parse, which
// silently shifts every later face index. This one keeps doubles, splits objects, and refuses a
// file with a bad coordinate or index, naming the line.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/error.hpp>
#include <nut/hierarchy.hpp>

namespace nut::converter {

// The material of faces that name none, or name one the MTL files do not define.
inline constexpr Material kDefaultMaterial{200, 200, 200, 255, 0};

struct Mesh {
  std::string name;                                     // object name (`o` / `g`), or the file stem
  std::vector<glm::dvec3> positions;                    // world metres, y up
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into positions
  std::vector<std::uint16_t> triangleMaterial;          // per triangle, index into materials
  std::vector<Material> materials;
  std::vector<std::string> materialNames;               // parallel to materials

  // Bounds of the vertices that triangles use; min > max for a mesh without triangles.
  WorldBox bounds() const;
  // Sum of triangle areas, m^2.
  double area() const;
};

struct ObjReadOptions {
  // The file is z-up (CAD, GIS): (x, y, z) becomes (x, z, -y), a right-handed turn to y-up.
  bool zUp = false;
};

struct ObjContents {
  // One mesh per object: split at `o` lines, or at `g` lines when the file has no `o` (groups of
  // the same name merge). Faces before the first of them form an object named after the file.
  // Objects without faces are left out. Each mesh has its own compact vertex list; every mesh
  // carries the file's whole material list, so indices agree between objects.
  std::vector<Mesh> objects;
  std::vector<std::string> warnings;  // "<file>:<line>: <what>", one each
  std::uintmax_t fileBytes = 0;
};

// Reads an OBJ file and the MTL files it names (paths relative to the OBJ's folder). Polygons are
// cut into triangles by ear clipping (nut/polygon.hpp: non-convex faces, and faces with a hole
// joined by a bridge, keep their shape); faces with fewer than three distinct vertices are
// dropped with a warning.
// Errors, naming file and line: unreadable file, a coordinate that is not a finite number, a face
// index out of range or zero, no faces at all.
Result<ObjContents> readObj(const std::string& path, const ObjReadOptions& options = {});

// All objects as one mesh (the whole file as one building).
Mesh mergeObjects(const std::vector<Mesh>& objects, const std::string& name);

}  // namespace nut::converter
