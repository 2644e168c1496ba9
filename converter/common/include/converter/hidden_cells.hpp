// converter/hidden_cells.hpp — cells no ray can reach, and a material for them that compresses.
//
// A solid building's grid is mostly inside: on the high-rise 85 % of the cells are boxes whose
// six neighbours are opaque boxes too. No ray reaches such a cell, so its material is never seen,
// but it is stored, and the solid conversion gives it the material of the nearest face along its
// line of cells (solid_occupancy.cpp), which extrudes the facades' patterns through the inside.
// Giving them all the one material most of the cells around them have lets the layers and blocks
// of the inside merge instead; which of the two compresses better depends on the building
// (convert.cpp tries both where 40 % of the cells are hidden). A material per enclosed region
// (the cells connected through faces) gives the same HNIs on every sample and external mesh, in
// three times the time (90 ms on the high-rise). Only a camera inside the building sees the
// difference: one colour inside instead of the facades carried through.
#pragma once

#include <cstdint>
#include <vector>

#include <nut/hierarchy.hpp>

namespace nut::converter {

// Per cell of `block` (Block::cellIndex), 1 when it is hidden: a box, and each of its six
// neighbours an opaque box of `block` (a cell on the block's faces is never hidden: the block is
// the whole building, and what lies beyond it is air).
std::vector<std::uint8_t> hiddenCells(const Block& block, const std::vector<Material>& materials);

// Gives every hidden cell of `block` the material that most faces between a hidden cell and one
// that is not have on the other side (ties: the lower material index). Returns the number of
// hidden cells.
std::size_t fillHiddenCells(Block& block, const std::vector<Material>& materials);

}  // namespace nut::converter
