// Axis orders of a grid (converter/axis_order.hpp): turning a block by a cube rotation, choosing
// the order whose data component compresses best, and the root that turns it back.
#include <converter/axis_order.hpp>

#include <array>
#include <cstdlib>
#include <map>
#include <tuple>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <nut/format.hpp>
#include <nut/units.hpp>

namespace nut::converter {

namespace {

int rotationIndex(const glm::mat<3, 3, int>& m) {
  for (int r = 0; r < format::kCubeRotationCount; ++r)
    if (cubeRotationMatrix(r) == m) return r;
  std::abort();  // products of cube rotations are cube rotations
}

int inverseRotation(const glm::mat<3, 3, int>& m) {
  for (int r = 0; r < format::kCubeRotationCount; ++r)
    if (cubeRotationMatrix(r) * m == glm::mat<3, 3, int>(1)) return r;
  std::abort();  // the rotations of the cube are a group
}

}  // namespace

TurnedBlock turnBlock(const Block& b, int cube) {
  // Column i of M is the old axis that new axis i runs along, with its sign:
  // p_old = M p_new + offset, where offset puts a mirrored axis back on [0, D).
  const glm::mat<3, 3, int> m = cubeRotationMatrix(cube);
  std::array<int, 3> from{}, sign{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (m[i][j] != 0) from[static_cast<std::size_t>(i)] = j, sign[static_cast<std::size_t>(i)] = m[i][j];
  TurnedBlock out;
  out.cube = cube;
  for (int i = 0; i < 3; ++i) {
    const auto& bounds = b.boundsM[static_cast<std::size_t>(from[static_cast<std::size_t>(i)])];
    auto& turned = out.block.boundsM[static_cast<std::size_t>(i)];
    if (sign[static_cast<std::size_t>(i)] > 0) {
      turned = bounds;
    } else {
      for (auto it = bounds.rbegin(); it != bounds.rend(); ++it) turned.push_back(snapToUnits(bounds.back() - *it));
      out.offsetM[from[static_cast<std::size_t>(i)]] = bounds.back();
    }
  }
  // Plane cuts live in the block's frame: n . p_old <= d with p_old = M p_new + offset is
  // (M^T n) . p_new <= d - n . offset.
  const glm::dmat3 forward(m);
  for (PlaneCut cut : b.cuts) {
    for (CutPlane& plane : cut.planes) {
      plane.offsetM -= glm::dot(plane.normal, out.offsetM);
      plane.normal = glm::transpose(forward) * plane.normal;
    }
    out.block.cuts.push_back(cut);
  }
  // A cell's unit cube turns with the block about its centre, so its solid turns by M^-1.
  const int inverse = inverseRotation(m);
  const glm::dmat3 inverseMatrix(cubeRotationMatrix(inverse));
  // A redirection is re-expressed in the turned cell's frame: p_old_cell = M p_new_cell + t_cell,
  // where t_cell puts a mirrored axis back on the cell, so the target placed by (R, O) in the old
  // cell is placed by (M^-1 R, M^-1 (O - t_cell)) in the new one. t_cell depends on the cell's
  // size, so equal records are shared only between cells of equal size along mirrored axes.
  std::map<std::tuple<BlockId, std::int64_t, std::int64_t, std::int64_t, int, std::array<bool, 3>>, std::uint32_t> records;
  const auto turnedRedirection = [&](const Redirection& r, const std::array<int, 3>& old) {
    glm::dvec3 shift(0.0);
    for (std::size_t i = 0; i < 3; ++i) {
      if (sign[i] > 0) continue;
      const auto& bounds = b.boundsM[static_cast<std::size_t>(from[i])];
      const auto k = static_cast<std::size_t>(old[static_cast<std::size_t>(from[i])]);
      shift[from[i]] = bounds[k + 1] - bounds[k];
    }
    const int rotation = rotationIndex(cubeRotationMatrix(inverse) * cubeRotationMatrix(r.rotation.cube));
    glm::dvec3 offset = inverseMatrix * (r.offsetM - shift);
    for (int a = 0; a < 3; ++a) offset[a] = snapToUnits(offset[a]);
    const auto key = std::make_tuple(r.target, toUnits(offset.x), toUnits(offset.y), toUnits(offset.z), rotation, r.wrap);
    auto [it, inserted] = records.try_emplace(key, static_cast<std::uint32_t>(out.block.redirections.size()));
    if (inserted)
      out.block.redirections.push_back(Redirection{r.target, offset, Rotation{static_cast<std::uint8_t>(rotation), 0}, r.wrap});
    return it->second;
  };
  const std::array<int, 3> n{out.block.cellCount(0), out.block.cellCount(1), out.block.cellCount(2)};
  out.block.cells.resize(b.cells.size());
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x) {
        const std::array<int, 3> c{x, y, z};
        std::array<int, 3> old{};
        for (std::size_t i = 0; i < 3; ++i)
          old[static_cast<std::size_t>(from[i])] = sign[i] > 0 ? c[i] : n[i] - 1 - c[i];
        Cell cell = b.cell(old[0], old[1], old[2]);
        if (cell.kind == CellKind::Solid) cell.solid = rotateSolid(cell.solid, inverse);
        if (cell.kind == CellKind::Redirection) cell.redirection = turnedRedirection(b.redirections[cell.redirection], old);
        out.block.cell(x, y, z) = cell;
      }
  return out;
}

std::vector<int> axisOrderRotations() {
  std::map<std::array<int, 3>, std::pair<int, int>> fewestMirrored;  // order -> (mirrored, rotation)
  for (int r = 0; r < format::kCubeRotationCount; ++r) {
    const glm::mat<3, 3, int> m = cubeRotationMatrix(r);
    std::array<int, 3> order{};
    int mirrored = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (m[i][j] != 0) order[static_cast<std::size_t>(i)] = j, mirrored += m[i][j] < 0;
    auto [it, inserted] = fewestMirrored.try_emplace(order, mirrored, r);
    if (!inserted && mirrored < it->second.first) it->second = {mirrored, r};
  }
  std::vector<int> out;
  for (const auto& entry : fewestMirrored) out.push_back(entry.second.second);  // (0, 1, 2) first
  return out;
}

void wrapRoot(Hierarchy& h, const glm::dvec3& sizeM, int cube, const glm::dvec3& offsetM) {
  Block root = Block::fromSizes({{{sizeM.x}, {sizeM.y}, {sizeM.z}}});
  root.redirections.push_back(Redirection{h.root, offsetM, Rotation{static_cast<std::uint8_t>(cube), 0}, {false, false, false}});
  root.cells[0] = Cell::redirect(0);
  h.root = h.addBlock(std::move(root));
}

}  // namespace nut::converter
