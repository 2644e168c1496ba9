// Hashing positions by their exact bits, for welding equal positions (mesh_check.cpp, Mesh).
#pragma once

#include <cstdint>
#include <cstring>

#include <glm/vec3.hpp>

namespace nut::converter {

struct PositionHash {
  std::size_t operator()(const glm::dvec3& p) const {
    std::uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < 3; ++i) {
      std::uint64_t bits;
      const double v = p[i] == 0.0 ? 0.0 : p[i];  // -0 and +0 are one position
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

}  // namespace nut::converter
