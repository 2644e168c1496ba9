// converter/mesh/src/closed_surface.hpp — whether the edges a mesh leaves uncancelled cancel
// along their lines: the last step of deciding that a mesh is a closed surface (MeshCheck::
// closedSurface), on which the occupancy step may count a line's crossings instead of asking the
// winding number.
//
// A surface is closed where every edge is run as often one way as the other. Generated and
// exported buildings are full of T-junctions (a wall's long edge against three windows' short
// ones), so the edges that do not cancel between their own two vertices are gathered per
// supporting line, and the surface is open only where their runs along a line do not cancel
// either (a roof sheet overhanging its gable, a pane filling a wall's hole, walls standing on a
// base plate without a floor of their own).
#pragma once

#include <span>

#include <glm/vec3.hpp>

namespace nut::converter {

// An edge from a to b that the faces using it run `weight` more times a -> b than b -> a.
struct UncancelledEdge {
  glm::dvec3 a, b;
  int weight;
};

bool cancelAlongLines(std::span<const UncancelledEdge> edges);

}  // namespace nut::converter
