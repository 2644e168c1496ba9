// converter/mesh_size.hpp — what the same building costs as a mesh, for the size comparisons of
// docs/CONVERTER.md: a binary glTF (GLB) compressed the way gltfpack does it, with
// meshoptimizer, then gzip.
//
// The GLB has one mesh and node per 256 m cube the triangles' centroids fall in (one for a
// building), one primitive per material in each (glTF has no per-triangle material), positions
// only (flat shading needs no normals: the glTF default), quantized to 16 bits per axis over the
// cube's triangles' bounds (KHR_mesh_quantization; 2 mm steps on a 140 m tower, 4 mm at most
// however far apart a district's buildings lie), the node placing them. Each primitive is
// vertex-cache and vertex-fetch optimized; as gltfpack lays them out, all vertices are then one
// buffer view encoded with meshopt_encodeVertexBuffer and all indices one encoded with
// meshopt_encodeIndexBuffer (EXT_meshopt_compression), materials shared. The JSON chunk is written
// in full, so its bytes count too.
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
