// scene/glb.hpp — the toolkit's binary glTF (GLB) reader: the triangles of a .glb file as one
// nut::TriangleMesh, as a complementary mesh or a mesh to render is read (scene/mesh_file.hpp
// picks this reader or the OBJ one by the file's extension).
//
// What it reads: glTF 2.0 in a GLB container with its buffer in the BIN chunk; the default scene's
// nodes (or every root node when there is none), each mesh placed by its node's matrix or
// translation, rotation and scale, composed in double precision; triangle primitives (mode 4),
// positions as floats or as integers, normalized or not (KHR_mesh_quantization), indices as 8, 16
// or 32-bit integers or none; buffer views compressed with EXT_meshopt_compression (no filter),
// as gltfpack and the converter write them. A triangle's material is its primitive's base colour
// factor: sRGB bytes round(255 * factor), opacity round(255 * alpha) under alphaMode BLEND and
// 255 otherwise. Normals, texture coordinates and textures are not read (renderers shade flat).
//
// A file may require EXT_meshopt_compression, KHR_mesh_quantization and KHR_materials_unlit (an
// unlit material is read by its colour factor like any other).
//
// What it refuses, with one error naming the file and the glTF object: a truncated or malformed
// container or JSON, another required extension, an external or data: URI buffer, an accessor or
// view outside its data, sparse accessors, meshopt filters, an index past its positions, a
// position that is not finite, more than kMaxGlbTriangles triangles, and a file with no
// triangles. Points and lines are left out with a warning.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nut/error.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::scene {

// More triangles than this are refused before they are decoded: 2^26, 3 GiB as a TriangleMesh.
inline constexpr std::size_t kMaxGlbTriangles = std::size_t{1} << 26;

// Reads a GLB file. Warnings ("<file>: <what>") are appended to `warnings`.
Result<TriangleMesh> readGlbMesh(const std::string& path, std::vector<std::string>& warnings);

// The same on bytes in memory; `name` names them in messages and is the mesh's name.
Result<TriangleMesh> readGlbBytes(std::span<const std::uint8_t> bytes, const std::string& name,
                                  std::vector<std::string>& warnings);

}  // namespace nut::scene
