// converter/axis_order.hpp — the axis order in which a grid's cells compress best.
//
// An HNI stores a block's cells as its z slices side by side, one image row per y layer, and the
// PNG's deflate finds repeats along rows and between neighbouring rows. Which axis of a building
// runs along the rows decides how much of its repetition deflate can see, and which blocks the
// extraction finds: the residential sample's smallest HNI is 12 % smaller in another axis order
// (6,279 B against 7,119 B). So the converter may build the hierarchy from the grid turned into
// another axis order and let a root of one cell redirect to it with the cube rotation that turns
// it back (the format's 24 rotations; solids are turned with it).
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include <nut/hierarchy.hpp>

namespace nut::converter {

// A grid re-expressed in another axis order: placed with redirection rotation `cube` at
// `offsetM` in a cell the size of the original, it shows exactly the original.
struct TurnedBlock {
  Block block;
  int cube = 0;
  glm::dvec3 offsetM{0.0};
};

// `b` in the frame of cube rotation `cube`: solids turned, redirections (cube rotations only, no
// yaw) re-expressed in their turned cells.
TurnedBlock turnBlock(const Block& b, int cube);

// One rotation per order of the axes (the one with fewest mirrored axes: a mirrored axis only
// reverses rows or slices), the identity first. Which order compresses best depends on the
// blocks extracted afterwards, so the converter tries them (convert.cpp).
std::vector<int> axisOrderRotations();

// Puts a new root over h: one cell of size sizeM redirecting to the old root as `turned` says.
void wrapRoot(Hierarchy& h, const glm::dvec3& sizeM, int cube, const glm::dvec3& offsetM);

}  // namespace nut::converter
