// Positions welded by exact equality (mesh_check.cpp's edges, the complementary mesh's corners,
// the solid builder's corner ids that join quadric and corner-slope pieces across seams).
#pragma once

#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include <glm/vec3.hpp>

namespace nut::converter {

// Hashes a position by its exact bits.
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

// The distinct positions, in the order they first appear, and the triangles as their ids.
struct Welded {
  std::vector<glm::dvec3> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

Welded weld(const std::vector<glm::dvec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles);

}  // namespace nut::converter
