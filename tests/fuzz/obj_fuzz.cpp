// Fuzz target obj_fuzz: arbitrary bytes as an OBJ file, and optionally its MTL file, must never
// crash the OBJ reader, and what it returns must be consistent: an error names the file; an
// accepted file gives meshes whose every triangle has three vertex indices within the mesh's
// positions and a material within its materials, whose positions are finite, and (one mesh per
// object) whose vertex lists hold only vertices that a triangle uses.
// Input framing: OBJ text, then optionally kMtlSeparator and the text of every MTL file that a
// `mtllib` line names (without the separator, every MTL file is missing).
#include <cmath>
#include <string>
#include <string_view>

#include <scene/obj.hpp>

#include "obj_input.hpp"
#include "require.hpp"
#include "targets.hpp"

namespace nut::fuzz {

namespace {

void checkMesh(const TriangleMesh& mesh, bool everyVertexUsed) {
  NUT_FUZZ_REQUIRE(!mesh.triangles.empty());
  NUT_FUZZ_REQUIRE(mesh.triangleMaterial.size() == mesh.triangles.size());
  NUT_FUZZ_REQUIRE(mesh.materialNames.size() == mesh.materials.size());
  NUT_FUZZ_REQUIRE(mesh.materials.size() <= kMaxMeshMaterials);
  for (const glm::dvec3& p : mesh.positions)
    NUT_FUZZ_REQUIRE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
  std::vector<bool> used(mesh.positions.size(), false);
  for (const auto& triangle : mesh.triangles)
    for (std::uint32_t v : triangle) {
      NUT_FUZZ_REQUIRE(v < mesh.positions.size());
      used[v] = true;
    }
  for (std::uint16_t m : mesh.triangleMaterial) NUT_FUZZ_REQUIRE(m < mesh.materials.size());
  if (everyVertexUsed)
    for (bool u : used) NUT_FUZZ_REQUIRE(u);
}

void readAndCheck(const ObjInput& input, const scene::ObjReadOptions& options) {
  const std::string path = "fuzz/input.obj";
  const scene::MtlReader readMtl = [&](const std::string& mtlPath) -> Result<std::string> {
    if (!input.hasMtl) return Error{mtlPath + ": no such file"};
    return std::string(input.mtl);
  };
  auto contents = scene::readObjText(std::string(input.obj), path, readMtl, options);
  if (!contents) {
    NUT_FUZZ_REQUIRE(contents.error().message.rfind(path, 0) == 0);
    return;
  }
  NUT_FUZZ_REQUIRE(!contents->objects.empty());
  NUT_FUZZ_REQUIRE(!options.oneMesh || contents->objects.size() == 1);
  for (const TriangleMesh& mesh : contents->objects) checkMesh(mesh, !options.oneMesh);
}

}  // namespace

int objInput(const std::uint8_t* data, std::size_t size) {
  const ObjInput input = splitObjInput(data, size);
  readAndCheck(input, {});
  readAndCheck(input, {.zUp = true, .oneMesh = true});
  return 0;
}

}  // namespace nut::fuzz
