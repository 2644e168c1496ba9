// converter/share_axes.hpp — block axes refined so that their metadata items are equal.
//
// compile() stores equal metadata items once. Blocks that a split cut from one facade (storeys of
// a house, slabs of a wall) often have axes of the same size whose boundaries differ by a few
// (a door in one storey): each stores its own item, up to 256 pixels of two rows (about a byte of
// PNG per pixel). Refining every such axis to the union of the boundaries makes the items equal
// at the cost of a few more cells (a few hundredths of a byte each in a PNG).
#pragma once

#include <nut/hierarchy.hpp>

namespace nut::converter {

// Refines axes of equal size to the union of their boundaries where the metadata pixels saved
// outweigh the cells added, the union still fits an axis (256 pixels at heuristicToleranceM,
// CompileOptions) and every cell a new boundary cuts looks the same cut (boxes, empty cells,
// redirections, solids extruded along the axis). What every block shows is unchanged. Returns the
// number of axes refined.
int shareAxes(Hierarchy& h, double heuristicToleranceM);

}  // namespace nut::converter
