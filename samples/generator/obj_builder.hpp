// samples/generator/obj_builder.hpp — collects triangles with materials and objects and writes
// them as OBJ + MTL, the way building exporters do: vertices shared by exact position, one
// `usemtl` run per material, `o` per object, coordinates in metres to 0.1 mm.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <glm/vec3.hpp>

namespace nut::samples {

class ObjBuilder {
 public:
  // A material by name with its sRGB colour; the same name returns the same index.
  int material(const std::string& name, std::array<int, 3> rgb);
  // Faces added from now on belong to this object (`o name`).
  void object(const std::string& name);
  // Counter-clockwise seen from outside (the right-hand normal points out).
  void triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, int material);
  void quad(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d, int material);

  std::size_t triangleCount() const;
  // Writes path (OBJ) and the MTL beside it; false with a message on stderr when it cannot.
  bool write(const std::string& path, const std::string& header) const;

 private:
  struct Object {
    std::string name;
    std::vector<std::array<std::uint32_t, 3>> triangles;
    std::vector<int> materials;
  };
  std::uint32_t vertex(const glm::dvec3& p);

  std::vector<glm::dvec3> positions_;
  std::map<std::tuple<std::int64_t, std::int64_t, std::int64_t>, std::uint32_t> ids_;
  std::vector<std::pair<std::string, std::array<int, 3>>> materials_;
  std::vector<Object> objects_;
};

}  // namespace nut::samples
