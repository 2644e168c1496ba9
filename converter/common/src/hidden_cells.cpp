// Cells no ray can reach, and one material for them (converter/hidden_cells.hpp).
#include <converter/hidden_cells.hpp>

#include <algorithm>
#include <array>

namespace nut::converter {

namespace {

// Index steps to a cell's six face neighbours (x fastest, then y, then z).
std::array<std::ptrdiff_t, 6> neighbourSteps(const Block& b) {
  const std::ptrdiff_t nx = b.cellCount(0), nxy = nx * b.cellCount(1);
  return {-1, 1, -nx, nx, -nxy, nxy};
}

}  // namespace

std::vector<std::uint8_t> hiddenCells(const Block& block, const std::vector<Material>& materials) {
  std::vector<char> opaqueBox(block.cells.size());
  std::transform(block.cells.begin(), block.cells.end(), opaqueBox.begin(), [&](const Cell& c) {
    return c.kind == CellKind::Solid && c.solid.index == 0 && materials[c.material].opacity == 255;
  });
  std::vector<std::uint8_t> hidden(block.cells.size(), 0);
  const std::array<std::ptrdiff_t, 6> steps = neighbourSteps(block);
  // Only cells off the block's faces have six neighbours.
  for (int z = 1; z + 1 < block.cellCount(2); ++z)
    for (int y = 1; y + 1 < block.cellCount(1); ++y)
      for (int x = 1; x + 1 < block.cellCount(0); ++x) {
        const auto id = static_cast<std::ptrdiff_t>(block.cellIndex(x, y, z));
        const Cell& c = block.cells[static_cast<std::size_t>(id)];
        if (c.kind != CellKind::Solid || c.solid.index != 0) continue;
        hidden[static_cast<std::size_t>(id)] = std::all_of(steps.begin(), steps.end(), [&](std::ptrdiff_t s) {
          return opaqueBox[static_cast<std::size_t>(id + s)] != 0;
        });
      }
  return hidden;
}

std::size_t fillHiddenCells(Block& block, const std::vector<Material>& materials) {
  const std::vector<std::uint8_t> hidden = hiddenCells(block, materials);
  const std::array<std::ptrdiff_t, 6> steps = neighbourSteps(block);
  // Each face between a hidden cell and a cell that is not is a vote for that cell's material (a
  // hidden cell has all six neighbours, so no index leaves the block).
  std::vector<std::size_t> votes(materials.size(), 0);
  std::size_t count = 0;
  for (std::size_t id = 0; id < hidden.size(); ++id) {
    if (!hidden[id]) continue;
    ++count;
    for (const std::ptrdiff_t s : steps)
      if (const auto nb = static_cast<std::size_t>(static_cast<std::ptrdiff_t>(id) + s); !hidden[nb]) ++votes[block.cells[nb].material];
  }
  const auto material = static_cast<std::uint16_t>(std::max_element(votes.begin(), votes.end()) - votes.begin());
  for (std::size_t id = 0; id < hidden.size(); ++id)
    if (hidden[id]) block.cells[id].material = material;
  return count;
}

}  // namespace nut::converter
