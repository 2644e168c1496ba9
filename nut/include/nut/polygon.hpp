// nut/polygon.hpp — the triangles of a polygon in space: how both OBJ readers (the converter's and
// the mesh reference's) read a face of more than three corners, so that they agree.
//
// Ear clipping in the plane the polygon's Newell normal picks: right for the non-convex faces
// exporters write (an L-shaped floor or roof), which a fan around the first corner would cover
// partly outside the face, and for a face with a hole joined to its outline by a bridge. Each ear is cut at the first
// corner, going round from the second, that has one: a convex polygon therefore gives exactly the fan (0, k, k + 1).
// What is left of a polygon that is not simple (self-intersecting, no area) when no corner is an ear is fanned.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace nut {

// Sets `triangles` to indices into `corners`, each triangle in the polygon's own winding:
// corners.size() - 2 of them for a polygon of at least three corners, none for fewer. (An output
// argument: a reader reuses one vector for every face.)
void triangulatePolygon(std::span<const glm::dvec3> corners, std::vector<std::array<std::uint32_t, 3>>& triangles);

}  // namespace nut
