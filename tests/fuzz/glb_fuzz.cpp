// Fuzz target glb_fuzz: arbitrary bytes as a binary glTF file must never crash the GLB reader, nor
// make it allocate beyond its bounds, and what it returns must be consistent: an error names the
// file; an accepted file gives a mesh whose every triangle has three distinct vertex indices
// within its positions and a material within its materials, whose positions are finite, with at
// most scene::kMaxGlbTriangles triangles.
#include <cmath>
#include <span>
#include <string>
#include <vector>

#include <scene/glb.hpp>

#include "require.hpp"
#include "targets.hpp"

namespace nut::fuzz {

int glbInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> warnings;
  auto mesh = scene::readGlbBytes(std::span(data, size), "fuzz.glb", warnings);
  if (!mesh) {
    NUT_FUZZ_REQUIRE(mesh.error().message.rfind("fuzz.glb: ", 0) == 0);
    return 0;
  }
  NUT_FUZZ_REQUIRE(!mesh->triangles.empty() && mesh->triangles.size() <= scene::kMaxGlbTriangles);
  NUT_FUZZ_REQUIRE(mesh->triangleMaterial.size() == mesh->triangles.size());
  NUT_FUZZ_REQUIRE(mesh->materialNames.size() == mesh->materials.size());
  for (const glm::dvec3& p : mesh->positions)
    NUT_FUZZ_REQUIRE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  for (const auto& [a, b, c] : mesh->triangles) {
    NUT_FUZZ_REQUIRE(a < mesh->positions.size() && b < mesh->positions.size() && c < mesh->positions.size());
    NUT_FUZZ_REQUIRE(a != b && b != c && a != c);
  }
  for (std::uint16_t m : mesh->triangleMaterial) NUT_FUZZ_REQUIRE(m < mesh->materials.size());
  for (const std::string& w : warnings) NUT_FUZZ_REQUIRE(w.rfind("fuzz.glb: ", 0) == 0);
  return 0;
}

}  // namespace nut::fuzz
