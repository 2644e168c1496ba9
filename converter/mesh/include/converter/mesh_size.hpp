// converter/mesh_size.hpp — what the same building costs as a mesh, for the size comparisons of
// docs/CONVERTER.md: a binary glTF (GLB) compressed the way gltfpack does it, with
// meshoptimizer, then gzip.
//
// The GLB has one primitive per material (glTF has no per-triangle material), positions only
// (flat shading needs no normals: the glTF default), quantized to 16 bits per axis over the
// mesh's bounds (KHR_mesh_quantization; 2 mm steps on a 140 m tower) and, per primitive,
// vertex-cache and vertex-fetch optimized, then encoded with meshopt_encodeVertexBuffer and
// meshopt_encodeIndexBuffer (EXT_meshopt_compression). The JSON chunk is written in full, so its
// bytes count too.
#pragma once

#include <cstdint>
#include <vector>

#include <scene/obj.hpp>

namespace nut::converter {

struct MeshSizes {
  std::uint64_t decodedBytes = 0;       // in memory: float3 per vertex, 3 x u32 per triangle
  std::uint64_t glbBytes = 0;           // GLB with meshopt-encoded buffers
  std::uint64_t glbGzipBytes = 0;       // ... after gzip -9
};

// The GLB as bytes (see above).
std::vector<std::uint8_t> meshoptGlb(const TriangleMesh& mesh);

MeshSizes measureMesh(const TriangleMesh& mesh);

// gzip -9 of the bytes (zlib, gzip wrapper).
std::vector<std::uint8_t> gzip(const std::vector<std::uint8_t>& bytes);

}  // namespace nut::converter
