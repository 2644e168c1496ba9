// Test helper: following a redirection as docs/FORMAT.md defines it, for tests that look points up
// through a hierarchy by hand (an independent check of what the renderers do).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include <nut/hierarchy.hpp>

namespace nut::testing {

// The target-local point that block-local point p of block b, inside cell c, shows through
// redirection r: relative to the cell's minimum corner, minus the offset, rotated back, taken
// modulo the target's size along its tiled axes.
inline glm::dvec3 redirectedPoint(const Hierarchy& h, const Block& b, const std::array<int, 3>& c, const Redirection& r,
                                  const glm::dvec3& p) {
  glm::dvec3 local;
  for (int a = 0; a < 3; ++a) local[a] = p[a] - b.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(c[static_cast<std::size_t>(a)])];
  glm::dvec3 q = glm::transpose(rotationMatrix(r.rotation)) * (local - r.offsetM);
  const glm::dvec3 size = h.blocks[r.target].sizeM();
  for (int a = 0; a < 3; ++a)
    if (r.wrap[static_cast<std::size_t>(a)]) q[a] -= std::floor(q[a] / size[a]) * size[a];
  return q;
}

}  // namespace nut::testing
