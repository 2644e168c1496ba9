// bench/lod2_district.hpp — the generated LoD2 district the plane-cell benchmarks draw
// (tests/data/lod2_district_seed1.obj: 30 buildings, walls and roofs at any angle), converted
// building by building as `nut convert -o FOLDER` converts it, without and with plane cells.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include <nut/camera.hpp>
#include <nut/image.hpp>
#include <nut/triangle_mesh.hpp>

namespace nut::bench {

// The buildings of one conversion: each HNI at its origin and its complementary mesh.
struct ConvertedDistrict {
  std::vector<Image> images;
  std::vector<glm::dvec3> originsM;
  std::vector<TriangleMesh> complements;  // empty meshes where the HNI shows every face
  std::size_t complementTriangles = 0, planeCells = 0;
};

struct Lod2District {
  TriangleMesh source;             // every building, one mesh
  ConvertedDistrict converted[2];  // [0] default options, [1] with plane cells
  Camera camera;                   // the one `nut render` fits to the source
};

// Converted once, on first use; exits naming the error when the file cannot be converted.
const Lod2District& lod2District(int width, int height);

}  // namespace nut::bench
