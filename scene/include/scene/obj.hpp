// scene/obj.hpp — the toolkit's one OBJ + MTL reader: every mesh that comes in (a building to
// convert, a source mesh to render for comparison, a complementary mesh beside its HNI) is read
// here into nut::TriangleMesh.
//
// Coordinates are kept as written, in double precision (a city coordinate near 10^6 m keeps its
// millimetres). One material per triangle: the MTL diffuse colour Kd becomes the sRGB bytes
// round(255 * Kd) (clamped to 0..1), the opacity d (or 1 - Tr) round(255 * d).
//
// The reader is our own, not OpenMesh's or tinyobjloader's: those parse coordinates into floats or
// read an unparsable coordinate as 0, and a vertex they skip silently shifts every later face
// index. This one keeps doubles, splits objects, and refuses a file with a bad coordinate or index,
// naming the line.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nut/error.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::scene {

struct ObjReadOptions {
  // The file is z-up (CAD, GIS): (x, y, z) becomes (x, z, -y), a right-handed turn to y-up.
  bool zUp = false;
  // Every face in one mesh named after the file, in the file's order, with the file's vertex list
  // as it is (vertex indices as in the file), instead of one mesh per object: what a reference
  // render of the whole file draws.
  bool oneMesh = false;
};

struct ObjContents {
  // One mesh per object: split at `o` lines, or at `g` lines when the file has no `o` (groups of
  // the same name merge). Faces before the first of them form an object named after the file.
  // Objects without faces are left out. Each mesh has its own compact vertex list; every mesh
  // carries the file's whole material list (with names), so indices agree between objects.
  std::vector<TriangleMesh> objects;
  std::vector<std::string> warnings;  // "<file>:<line>: <what>", one each
  std::uintmax_t fileBytes = 0;
};

// Reads an OBJ file and the MTL files it names (paths relative to the OBJ's folder). Polygons are
// cut into triangles by ear clipping (nut/polygon.hpp: non-convex faces, and faces with a hole
// joined by a bridge, keep their shape); faces with fewer than three distinct vertices are
// dropped with a warning. A missing MTL file or an undefined material name is a warning, and its
// faces take nut::kDefaultMaterial.
// Errors, naming file and line: unreadable file, a coordinate that is not a finite number, a face
// index out of range or zero, more than nut::kMaxMeshMaterials materials, no faces at all.
Result<ObjContents> readObj(const std::string& path, const ObjReadOptions& options = {});

// Gives the text of an MTL file, named by its path (a `mtllib` name joined to the OBJ's folder),
// or an error, which the reader keeps as a warning.
using MtlReader = std::function<Result<std::string>(const std::string& path)>;

// readObj on an OBJ already in memory: `path` names it in messages and gives the folder of its MTL
// files, whose text `readMtl` supplies (readObj: the file's text, and readTextFile).
Result<ObjContents> readObjText(const std::string& text, const std::string& path, const MtlReader& readMtl,
                                const ObjReadOptions& options = {});

// The whole file as one mesh (readObj with oneMesh), its warnings appended to `warnings`.
Result<TriangleMesh> readObjMesh(const std::string& path, std::vector<std::string>& warnings);

}  // namespace nut::scene
