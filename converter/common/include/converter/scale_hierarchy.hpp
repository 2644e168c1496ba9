// converter/scale_hierarchy.hpp — a hierarchy stretched along its root's axes: every length
// multiplied by a factor per axis, every cell's content the same. `nut city` makes distinct
// buildings of one converted sample this way (docs/CITY.md, "Buildings").
#pragma once

#include <glm/vec3.hpp>

#include <nut/error.hpp>
#include <nut/hierarchy.hpp>

namespace nut::converter {

// The hierarchy whose root-frame point diag(factors) * p shows what h's point p shows. Each block
// is stretched in its own frame by the factors its redirections turn into it (a cube rotation
// permutes them); a block reached under two different stretches is stored once for each.
// Solids fill their cells in cell-relative coordinates, so they stretch with the cells; summaries
// (covered fractions of a side) do not change; level-of-detail footprints shrink or grow with the
// smallest factor. Errors: a factor that is not positive and finite, a yaw redirection in a block
// stretched differently along its x and z (the turn would shear it), or texture infos (their
// offsets are shared by blocks that would stretch differently).
Result<Hierarchy> scaleHierarchy(const Hierarchy& h, const glm::dvec3& factors);

}  // namespace nut::converter
