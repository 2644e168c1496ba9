// The NUT model: construction helpers, rotations, structural checks and the millimetre snapping
// that defines what an encoded hierarchy decodes to.
#include <nut/hierarchy.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>

#include <glm/geometric.hpp>

#include <nut/format.hpp>
#include <nut/units.hpp>

namespace nut {

namespace {

std::array<glm::mat<3, 3, int>, format::kCubeRotationCount> makeCubeRotations() {
  // Signed permutation matrices with determinant +1, in a fixed order: permutations of the axes
  // lexicographically, then sign patterns by increasing bit mask. The order is part of the format.
  std::array<glm::mat<3, 3, int>, format::kCubeRotationCount> out{};
  int perm[3] = {0, 1, 2};
  int n = 0;
  do {
    for (int signs = 0; signs < 8; ++signs) {
      glm::mat<3, 3, int> m(0);
      for (int column = 0; column < 3; ++column) m[column][perm[column]] = (signs >> column & 1) ? -1 : 1;
      const int det = m[0][0] * (m[1][1] * m[2][2] - m[2][1] * m[1][2]) -
                      m[1][0] * (m[0][1] * m[2][2] - m[2][1] * m[0][2]) +
                      m[2][0] * (m[0][1] * m[1][2] - m[1][1] * m[0][2]);
      if (det == 1) out[n++] = m;
    }
  } while (std::next_permutation(perm, perm + 3));
  return out;
}

std::string cellName(BlockId b, const Block& block, std::size_t index) {
  const auto nx = static_cast<std::size_t>(block.cellCount(0));
  const auto ny = static_cast<std::size_t>(block.cellCount(1));
  return "block " + std::to_string(b) + " cell (" + std::to_string(index % nx) + "," +
         std::to_string(index / nx % ny) + "," + std::to_string(index / (nx * ny)) + ")";
}

const char* axisName(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

}  // namespace

glm::mat<3, 3, int> cubeRotationMatrix(int index) {
  static const auto rotations = makeCubeRotations();
  return rotations.at(static_cast<std::size_t>(index));
}

Solid rotateSolid(Solid s, int cube) {
  // Found once per (solid, rotation) by comparing inside tests at sample points: the rotated
  // solid is the one of the same group that holds exactly the rotated points of s. The grid
  // avoids the regions' boundaries (planes through 1/2, 1/3 and the unit sphere about corners).
  static const auto table = [] {
    std::array<std::array<Solid, kSolidCount>, format::kCubeRotationCount> t{};
    constexpr int kSamples = 5;
    for (int r = 0; r < format::kCubeRotationCount; ++r) {
      const glm::dmat3 m(cubeRotationMatrix(r));
      for (int i = 0; i < kSolidCount; ++i) {
        const Solid from{static_cast<std::uint8_t>(i)};
        const SolidGroup group = solidGroup(from);
        for (int o = 0; o < groupOrientationCount(group); ++o) {
          const Solid to = makeSolid(group, o);
          bool same = true;
          for (int x = 0; x < kSamples && same; ++x)
            for (int y = 0; y < kSamples && same; ++y)
              for (int z = 0; z < kSamples && same; ++z) {
                const glm::dvec3 p = (glm::dvec3(x, y, z) + 0.41) / double{kSamples};
                same = solidContains(from, p) == solidContains(to, m * (p - 0.5) + 0.5);
              }
          if (same) t[static_cast<std::size_t>(r)][static_cast<std::size_t>(i)] = to;
        }
      }
    }
    return t;
  }();
  return table.at(static_cast<std::size_t>(cube))[s.index];
}

glm::dmat3 rotationMatrix(const Rotation& r) {
  if (r.yaw == 0) return glm::dmat3(cubeRotationMatrix(r.cube));
  // Quarter turns are exact, so that a sub-block turned by one fits its cell without a seam.
  static constexpr double kQuarterCos[4] = {1, 0, -1, 0}, kQuarterSin[4] = {0, 1, 0, -1};
  const double angle = 2.0 * std::numbers::pi * r.yaw / format::kYawSteps;
  const bool quarter = r.yaw % (format::kYawSteps / 4) == 0;
  const double c = quarter ? kQuarterCos[r.yaw / (format::kYawSteps / 4)] : std::cos(angle);
  const double s = quarter ? kQuarterSin[r.yaw / (format::kYawSteps / 4)] : std::sin(angle);
  // Right-handed rotation about +y: counter-clockwise seen from above. Columns are images of axes.
  const glm::dmat3 yaw(glm::dvec3(c, 0, -s), glm::dvec3(0, 1, 0), glm::dvec3(s, 0, c));
  return yaw * glm::dmat3(cubeRotationMatrix(r.cube));
}

Block Block::fromSizes(const std::array<std::vector<double>, 3>& sizesM) {
  Block b;
  std::size_t count = 1;
  for (int a = 0; a < 3; ++a) {
    b.boundsM[a].push_back(0.0);
    for (double s : sizesM[a]) b.boundsM[a].push_back(b.boundsM[a].back() + s);
    count *= sizesM[a].size();
  }
  b.cells.assign(count, Cell::empty());
  return b;
}

std::uint16_t Hierarchy::addMaterial(const Material& m) {
  const auto it = std::find(materials.begin(), materials.end(), m);
  if (it != materials.end()) return static_cast<std::uint16_t>(it - materials.begin());
  materials.push_back(m);
  return static_cast<std::uint16_t>(materials.size() - 1);
}

Status checkHierarchy(const Hierarchy& h) {
  if (h.blocks.empty()) return Error{"hierarchy has no blocks"};
  if (h.root >= h.blocks.size())
    return Error{"root block " + std::to_string(h.root) + " out of range (" +
                 std::to_string(h.blocks.size()) + " blocks)"};
  for (BlockId b = 0; b < h.blocks.size(); ++b) {
    const Block& block = h.blocks[b];
    const std::string where = "block " + std::to_string(b);
    std::size_t count = 1;
    for (int a = 0; a < 3; ++a) {
      const auto& bounds = block.boundsM[a];
      if (bounds.size() < 2) return Error{where + " axis " + axisName(a) + ": no cells"};
      if (bounds.front() != 0.0)
        return Error{where + " axis " + axisName(a) + ": first boundary must be 0"};
      for (std::size_t i = 1; i < bounds.size(); ++i)
        if (!std::isfinite(bounds[i]) || !(bounds[i] > bounds[i - 1]))
          return Error{where + " axis " + axisName(a) + ": boundary " + std::to_string(i) +
                       " is not finite and greater than the previous one"};
      count *= bounds.size() - 1;
    }
    if (block.cells.size() != count)
      return Error{where + ": " + std::to_string(block.cells.size()) + " cells, expected " +
                   std::to_string(count)};
    if (!std::isfinite(block.lodFootprintM) || block.lodFootprintM < 0.0)
      return Error{where + ": level-of-detail footprint " + std::to_string(block.lodFootprintM) +
                   " is not finite and non-negative"};
    for (std::size_t i = 0; i < block.cells.size(); ++i) {
      const Cell& c = block.cells[i];
      if (c.kind == CellKind::Solid && c.solid.index >= kSolidCount)
        return Error{cellName(b, block, i) + ": solid " + std::to_string(c.solid.index) + " out of range"};
      if (c.kind == CellKind::Plane && c.cut >= block.cuts.size())
        return Error{cellName(b, block, i) + ": plane cut " + std::to_string(c.cut) + " out of range"};
      if (c.kind == CellKind::Redirection && c.redirection >= block.redirections.size())
        return Error{cellName(b, block, i) + ": redirection " + std::to_string(c.redirection) + " out of range"};
      if (c.hasMaterial() && c.material >= h.materials.size())
        return Error{cellName(b, block, i) + ": material " + std::to_string(c.material) + " out of range (" +
                     std::to_string(h.materials.size()) + " materials)"};
      if (c.hasMaterial() && c.texture > h.textures.size())
        return Error{cellName(b, block, i) + ": texture " + std::to_string(c.texture) + " out of range (" +
                     std::to_string(h.textures.size()) + " textures)"};
    }
    for (std::size_t k = 0; k < block.cuts.size(); ++k) {
      const PlaneCut& cut = block.cuts[k];
      const std::string cw = where + " plane cut " + std::to_string(k);
      if (cut.combine != PlaneCombine::One && cut.combine != PlaneCombine::Both &&
          cut.combine != PlaneCombine::Either)
        return Error{cw + ": combination " + std::to_string(static_cast<int>(cut.combine)) + " is not 1, 2 or 3"};
      for (int p = 0; p < cut.planeCount(); ++p) {
        const CutPlane& plane = cut.planes[static_cast<std::size_t>(p)];
        const double length = glm::length(plane.normal);
        if (!std::isfinite(length) || std::abs(length - 1.0) > 1e-6 || !std::isfinite(plane.offsetM))
          return Error{cw + " plane " + std::to_string(p) +
                       ": normal is not a finite unit vector or offset not finite"};
        const auto& surface = cut.surfaceMaterials[static_cast<std::size_t>(p)];
        if (surface && *surface >= h.materials.size())
          return Error{cw + " plane " + std::to_string(p) + ": surface material " + std::to_string(*surface) +
                       " out of range (" + std::to_string(h.materials.size()) + " materials)"};
      }
    }
    for (std::size_t r = 0; r < block.redirections.size(); ++r) {
      const Redirection& red = block.redirections[r];
      const std::string rw = where + " redirection " + std::to_string(r);
      if (red.target >= h.blocks.size()) return Error{rw + ": target block out of range"};
      if (red.rotation.cube >= format::kCubeRotationCount)
        return Error{rw + ": cube rotation out of range"};
      for (int a = 0; a < 3; ++a)
        if (!std::isfinite(red.offsetM[a])) return Error{rw + ": offset is not finite"};
    }
  }
  // The hierarchy must be a DAG: depth-first search with an on-stack mark.
  enum class Mark { None, OnStack, Done };
  std::vector<Mark> mark(h.blocks.size(), Mark::None);
  std::function<std::optional<BlockId>(BlockId)> visit = [&](BlockId b) -> std::optional<BlockId> {
    mark[b] = Mark::OnStack;
    for (const Redirection& r : h.blocks[b].redirections) {
      if (mark[r.target] == Mark::OnStack) return b;
      if (mark[r.target] == Mark::None)
        if (auto cycle = visit(r.target)) return cycle;
    }
    mark[b] = Mark::Done;
    return std::nullopt;
  };
  for (BlockId b = 0; b < h.blocks.size(); ++b)
    if (mark[b] == Mark::None)
      if (auto cycle = visit(b))
        return Error{"block " + std::to_string(*cycle) + ": redirection cycle (the hierarchy must be a DAG)"};
  return Ok{};
}

int dagDepth(const Hierarchy& h) {
  std::vector<int> depth(h.blocks.size(), -1);
  std::function<int(BlockId)> visit = [&](BlockId b) {
    if (depth[b] >= 0) return depth[b];
    int d = 0;
    for (const Cell& c : h.blocks[b].cells)
      if (c.kind == CellKind::Redirection)
        d = std::max(d, 1 + visit(h.blocks[b].redirections[c.redirection].target));
    return depth[b] = d;
  };
  return h.blocks.empty() ? 0 : visit(h.root);
}

Hierarchy quantized(const Hierarchy& h) {
  Hierarchy q = h;
  for (Block& block : q.blocks) {
    for (auto& bounds : block.boundsM)
      for (double& b : bounds) b = snapToUnits(b);
    // Redirections become one record per distinct value, listed in order of first use by the
    // cells (x fastest): that is the order decode() recovers them in.
    for (Redirection& r : block.redirections)
      for (int a = 0; a < 3; ++a) r.offsetM[a] = snapToUnits(r.offsetM[a]);
    // Plane cuts likewise: one per distinct encoded cut, in order of first use.
    std::vector<PlaneCut> usedCuts;
    std::vector<Redirection> used;
    for (Cell& c : block.cells) {
      if (c.kind == CellKind::Plane) {
        PlaneCut cut = block.cuts[c.cut];
        for (int p = cut.planeCount(); p < 2; ++p) cut.surfaceMaterials[static_cast<std::size_t>(p)].reset();
        for (int p = 0; p < 2; ++p)
          cut.planes[static_cast<std::size_t>(p)] =
              p < cut.planeCount() ? quantizedPlane(cut.planes[static_cast<std::size_t>(p)]) : CutPlane{};
        auto it = std::find(usedCuts.begin(), usedCuts.end(), cut);
        if (it == usedCuts.end()) it = usedCuts.insert(usedCuts.end(), cut);
        c = Cell::planeCell(static_cast<std::uint32_t>(it - usedCuts.begin()), c.material, c.texture);
        continue;
      }
      if (c.kind != CellKind::Redirection) {
        if (c.kind == CellKind::Empty) c = Cell::empty();
        c.redirection = 0;
        c.cut = 0;
        continue;
      }
      const Redirection& r = block.redirections[c.redirection];
      auto it = std::find(used.begin(), used.end(), r);
      if (it == used.end()) it = used.insert(used.end(), r);
      c = Cell::redirect(static_cast<std::uint32_t>(it - used.begin()));
    }
    block.redirections = std::move(used);
    block.cuts = std::move(usedCuts);
  }
  // A footprint is kept in the records that redirect to its block, in the code's steps.
  std::vector<bool> targeted(q.blocks.size(), false);
  for (const Block& block : q.blocks)
    for (const Cell& c : block.cells)
      if (c.kind == CellKind::Redirection) targeted[block.redirections[c.redirection].target] = true;
  for (BlockId b = 0; b < q.blocks.size(); ++b)
    q.blocks[b].lodFootprintM = targeted[b] ? lodFootprintM(lodCode(q.blocks[b].lodFootprintM)) : 0.0;
  for (TextureInfo& t : q.textures)
    for (int a = 0; a < 3; ++a) t.offsetM[a] = snapToUnits(t.offsetM[a]);
  return q;
}

}  // namespace nut
