// converter/mesh/src/closed_surface.hpp — whether a mesh bounds a closed surface, for the
// occupancy step: a line's crossings count the winding number exactly only when it does.
//
// A surface is closed where every edge is run as often one way as the other. Generated and
// exported buildings are full of T-junctions (a wall's long edge against three windows' short
// ones), so edges are matched geometrically: the edges that do not cancel between their own two
// vertices are gathered per supporting line, and the surface is open only where their runs along
// a line do not cancel either (a roof sheet overhanging its gable, a pane filling a wall's hole,
// walls standing on a base plate without a floor of their own).
#pragma once

#include <converter/mesh.hpp>

namespace nut::converter::solid {

bool isClosedSurface(const Mesh& mesh);

}  // namespace nut::converter::solid
