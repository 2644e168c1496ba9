// Test helpers: following a redirection as docs/FORMAT.md defines it, for tests that look points up
// through a hierarchy by hand (an independent check of what the renderers do).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include <nut/hierarchy.hpp>
#include <nut/solids.hpp>

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

// What point p (block-local metres) of block `id` holds, followed through its redirections: the
// material of the solid or plane cell it is inside, or -1.
inline int contentAt(const Hierarchy& h, BlockId id, const glm::dvec3& p) {
  const Block& b = h.blocks[id];
  std::array<int, 3> c{};
  glm::dvec3 unit;
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
    if (p[a] < 0 || p[a] >= bounds.back()) return -1;
    c[static_cast<std::size_t>(a)] = static_cast<int>(std::upper_bound(bounds.begin(), bounds.end(), p[a]) - bounds.begin()) - 1;
    const double lo = bounds[static_cast<std::size_t>(c[static_cast<std::size_t>(a)])];
    unit[a] = (p[a] - lo) / (bounds[static_cast<std::size_t>(c[static_cast<std::size_t>(a)] + 1)] - lo);
  }
  const Cell& cell = b.cell(c[0], c[1], c[2]);
  if (cell.kind == CellKind::Solid) return solidContains(cell.solid, unit) ? cell.material : -1;
  // A plane cut's planes are in the block's frame: p itself, not the cell's unit cube.
  if (cell.kind == CellKind::Plane) return cutContains(b.cuts[cell.cut], p) ? cell.material : -1;
  if (cell.kind == CellKind::Empty) return -1;
  const Redirection& r = b.redirections[cell.redirection];
  return contentAt(h, r.target, redirectedPoint(h, b, c, r, p));
}

}  // namespace nut::testing
