// Internal to the block stage (blocks.cpp): the paper's user-selected blocks (`--block`), which
// buildHierarchy extracts before the automatic search, and the cell test both use.
#pragma once

#include <glm/vec3.hpp>

#include <converter/blocks.hpp>
#include <nut/camera.hpp>
#include <nut/hierarchy.hpp>

namespace nut::converter {

// A box or an empty cell looks the same however it is stretched or cut; other solids do not.
inline bool stretchable(const Cell& c) {
  return c.kind == CellKind::Empty || (c.kind == CellKind::Solid && c.solid.index == 0);
}

// Whether a cell at one place of a block shows what an equal cell shows at another: not for plane
// cells, whose planes are the block's and so cut each place differently. Blocks are not repeated
// across plane cells.
inline bool sameAtAnotherPlace(const Cell& x, const Cell& y) { return x == y && x.kind != CellKind::Plane; }

// The paper's user-selected block: the cells the box covers, simplified, become block S (added to
// h), and every place of g0 that matches S (one-to-many width matching within the tolerance)
// redirects to it. Nothing happens when the box misses g0.
void extractManual(Hierarchy& h, Block& g0, const WorldBox& box, const glm::dvec3& originM, double tolerance, BlockStats& stats);

}  // namespace nut::converter
