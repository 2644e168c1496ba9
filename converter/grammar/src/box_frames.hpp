// Boxes and sides under the cube rotations that turn a derivation's frames (hierarchy.hpp), for
// the derivation and its mesh.
#pragma once

#include <glm/common.hpp>
#include <glm/mat3x3.hpp>

#include <nut/camera.hpp>

namespace nut::grammar {

using IMat3 = glm::mat<3, 3, int>;

// A rotation's inverse; glm's transpose takes floats only.
inline IMat3 transposed(const IMat3& m) {
  IMat3 t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t[i][j] = m[j][i];
  return t;
}

// The box turned by r and moved by offset: still axis-aligned.
inline WorldBox turned(const WorldBox& b, const IMat3& r, const glm::dvec3& offset) {
  const glm::dmat3 m(r);
  const glm::dvec3 a = m * b.min, c = m * b.max;
  return {offset + glm::min(a, c), offset + glm::max(a, c)};
}

// The side 2 * axis + (0 for +, 1 for -) of a frame, turned by r; -1 (no side) stays -1.
inline int turnedSide(int side, const IMat3& r) {
  if (side < 0) return side;
  const glm::ivec3 normal = r[side / 2] * (side % 2 == 0 ? 1 : -1);
  for (int a = 0; a < 3; ++a)
    if (normal[a] != 0) return 2 * a + (normal[a] > 0 ? 0 : 1);
  return side;
}

}  // namespace nut::grammar
