// converter/assemble.hpp — from grids to a Hierarchy the core can compile: only the materials
// cells use, and blocks split where the format's per-axis limits would refuse them.
//
// The format indexes an axis with at most 256 metadata pixels, each boundary in a pixel of its own
// (docs/FORMAT.md, "Metadata item"), so an axis with more than 256 cells, or with a cell much
// narrower than the block (about D / 256), cannot be indexed; and a data component is at most
// 4096 pixels wide (n_x * n_z). compile() refuses such a block naming it; splitBlocks() replaces it
// by a parent of the same size whose cells redirect to pieces that fit, so every redirection that
// pointed at the block still sees the same content.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nut/error.hpp>
#include <nut/hierarchy.hpp>

namespace nut::converter {

// Whether compile() can index and lay out block b as it is (each axis: buildAxisIndex succeeds;
// n_x * n_z <= 4096). On failure, `why` says which axis and why.
bool blockFits(const Block& b, std::string* why = nullptr);

// Splits every block that does not fit (see above), recursively; returns how many blocks it added.
// Fails only when an axis cannot be split into indexable pieces at all (two boundaries closer than
// the format can tell apart at any block size).
Result<int> splitBlocks(Hierarchy& h);

// Drops materials no cell or plane surface uses and renumbers the rest.
void compactMaterials(Hierarchy& h);

// Renumbers every material index of the block, cells' and plane surfaces' alike: m becomes to[m].
// For blocks moved into another hierarchy's material list (a district, a turned wing).
void renumberMaterials(Block& b, const std::vector<std::uint16_t>& to);

}  // namespace nut::converter
