// Splitting blocks to the format's limits, and material compaction (converter/assemble.hpp).
#include <converter/assemble.hpp>

#include <algorithm>
#include <cstdint>
#include <optional>

#include <converter/blocks.hpp>
#include <nut/format.hpp>
#include <nut/metadata.hpp>
#include <nut/units.hpp>

namespace nut::converter {

namespace {

const char* axisName(int a) { return a == 0 ? "x" : a == 1 ? "y" : "z"; }

// More blocks than this cannot have their headers and metadata items in the 256 x 256 metadata
// region (each takes 12 pixels and three items of 2 rows), so splitting gives up beyond it.
constexpr std::size_t kMaxBlocks = 2048;

// Whether cells [first, last) of an axis with these boundaries can be indexed as one block axis.
bool indexable(const std::vector<double>& boundsM, int first, int last) {
  if (last - first > format::kMaxCellsPerAxis) return false;
  std::vector<std::int64_t> units;
  const std::int64_t base = toUnits(boundsM[static_cast<std::size_t>(first)]);
  for (int i = first; i <= last; ++i) units.push_back(toUnits(boundsM[static_cast<std::size_t>(i)]) - base);
  for (std::size_t i = 1; i < units.size(); ++i)
    if (units[i] <= units[i - 1]) return false;
  return buildAxisIndex(units).ok();
}

// Cuts cells [0, n) into consecutive pieces of at most `cap` cells that are each indexable, as
// long as possible (fewer pieces, fewer blocks). Returns the cut positions, 0 and n included.
std::vector<int> partition(const std::vector<double>& boundsM, int cap) {
  const int n = static_cast<int>(boundsM.size()) - 1;
  std::vector<int> cuts{0};
  int start = 0;
  while (start < n) {
    int end = std::min(n, start + cap);
    if (!indexable(boundsM, start, end)) {
      // Indexability shrinks as a piece grows (more cells, a wider block), so search for the edge.
      int lo = start + 1, hi = end - 1;  // one cell always fits
      end = lo;
      while (lo <= hi) {
        const int mid = (lo + hi) / 2;
        if (indexable(boundsM, start, mid)) {
          end = mid;
          lo = mid + 1;
        } else {
          hi = mid - 1;
        }
      }
    }
    cuts.push_back(end);
    start = end;
  }
  return cuts;
}

// Whether a parent whose cells are the pieces between these cuts can be indexed.
bool parentIndexable(const std::vector<double>& boundsM, const std::vector<int>& cuts) {
  std::vector<double> parent;
  for (int cut : cuts) parent.push_back(boundsM[static_cast<std::size_t>(cut)]);
  return indexable(parent, 0, static_cast<int>(cuts.size()) - 1);
}

// If every cell of the range is the same solid (or empty), that cell; else nullopt.
std::optional<Cell> uniform(const Block& b, const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
  const Cell first = b.cell(lo[0], lo[1], lo[2]);
  // A plane cell's planes belong to this block's frame, and a redirection to its records.
  if (first.kind == CellKind::Redirection || first.kind == CellKind::Plane) return std::nullopt;
  for (int z = lo[2]; z < hi[2]; ++z)
    for (int y = lo[1]; y < hi[1]; ++y)
      for (int x = lo[0]; x < hi[0]; ++x)
        if (!(b.cell(x, y, z) == first)) return std::nullopt;
  // A box fills any cell; other solids are shaped by their cell and cannot grow.
  if (first.kind == CellKind::Solid && first.solid.index != 0) return std::nullopt;
  return first;
}

}  // namespace

bool blockFits(const Block& b, std::string* why) {
  for (int a = 0; a < 3; ++a)
    if (!indexable(b.boundsM[static_cast<std::size_t>(a)], 0, b.cellCount(a))) {
      if (why) *why = std::string("axis ") + axisName(a) + " (" + std::to_string(b.cellCount(a)) + " cells) cannot be indexed";
      return false;
    }
  if (b.cellCount(0) * b.cellCount(2) > format::kMaxImageSize) {
    if (why) *why = "data component " + std::to_string(b.cellCount(0) * b.cellCount(2)) + " pixels wide";
    return false;
  }
  return true;
}

Result<int> splitBlocks(Hierarchy& h) {
  int added = 0;
  for (std::size_t id = 0; id < h.blocks.size(); ++id) {
    for (int guard = 0; !blockFits(h.blocks[id]); ++guard) {
      if (guard > 8) return Error{"block " + std::to_string(id) + " cannot be split into indexable pieces"};
      if (h.blocks.size() > kMaxBlocks)
        return Error{"splitting the grid into indexable blocks needs more than " + std::to_string(kMaxBlocks) +
                     " blocks, more than an HNI's metadata region holds"};
      const Block source = h.blocks[id];
      const int nx = source.cellCount(0), nz = source.cellCount(2);
      // Caps keep each piece's data component within 4096 pixels (n_x * n_z).
      std::array<int, 3> cap{format::kMaxCellsPerAxis, format::kMaxCellsPerAxis, format::kMaxCellsPerAxis};
      if (nx * nz > format::kMaxImageSize) {
        if (nx <= 64) cap[2] = format::kMaxImageSize / nx;
        else if (nz <= 64) cap[0] = format::kMaxImageSize / nz;
        else cap[0] = cap[2] = 64;
      }
      std::array<std::vector<int>, 3> cuts;
      for (int a = 0; a < 3; ++a) {
        const auto& bounds = source.boundsM[static_cast<std::size_t>(a)];
        std::vector<int>& c = cuts[static_cast<std::size_t>(a)] = partition(bounds, cap[static_cast<std::size_t>(a)]);
        // The parent must be indexable too: pieces far narrower than the block (a house in a
        // 10 km district) join their neighbours until each is at least a share of the block;
        // the joined piece, a block of its own, is split again in its turn.
        for (double share = 1.0 / 128; !parentIndexable(bounds, c) && share <= 0.5; share *= 2) {
          const double minWidth = share * bounds.back();
          std::vector<int> joined{0};
          for (std::size_t i = 1; i < c.size(); ++i)
            if (bounds[static_cast<std::size_t>(c[i])] - bounds[static_cast<std::size_t>(joined.back())] >= minWidth || i + 1 == c.size())
              joined.push_back(c[i]);
          // A narrow last piece joins the one before it.
          if (joined.size() > 2 && bounds.back() - bounds[static_cast<std::size_t>(joined[joined.size() - 2])] < minWidth)
            joined.erase(joined.end() - 2);
          c = std::move(joined);
        }
      }
      Block parent;
      for (int a = 0; a < 3; ++a)
        for (int c : cuts[static_cast<std::size_t>(a)])
          parent.boundsM[static_cast<std::size_t>(a)].push_back(source.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(c)]);
      const std::array<int, 3> pieces{static_cast<int>(cuts[0].size()) - 1, static_cast<int>(cuts[1].size()) - 1,
                                      static_cast<int>(cuts[2].size()) - 1};
      parent.cells.assign(static_cast<std::size_t>(pieces[0]) * static_cast<std::size_t>(pieces[1]) * static_cast<std::size_t>(pieces[2]),
                          Cell::empty());
      std::vector<Block> newBlocks;
      for (int pz = 0; pz < pieces[2]; ++pz)
        for (int py = 0; py < pieces[1]; ++py)
          for (int px = 0; px < pieces[0]; ++px) {
            const std::array<int, 3> lo{cuts[0][static_cast<std::size_t>(px)], cuts[1][static_cast<std::size_t>(py)], cuts[2][static_cast<std::size_t>(pz)]};
            const std::array<int, 3> hi{cuts[0][static_cast<std::size_t>(px + 1)], cuts[1][static_cast<std::size_t>(py + 1)], cuts[2][static_cast<std::size_t>(pz + 1)]};
            if (auto cell = uniform(source, lo, hi)) {
              parent.cell(px, py, pz) = *cell;
              continue;
            }
            Block piece = subBlock(source, lo, hi);
            const auto target = static_cast<BlockId>(h.blocks.size() + newBlocks.size());
            parent.cell(px, py, pz) = Cell::redirect(static_cast<std::uint32_t>(parent.redirections.size()));
            parent.redirections.push_back(Redirection{target, glm::dvec3(0.0), Rotation{}, {false, false, false}});
            newBlocks.push_back(std::move(piece));
          }
      h.blocks[id] = std::move(parent);
      for (Block& b : newBlocks) h.blocks.push_back(std::move(b));
      added += static_cast<int>(newBlocks.size());
    }
  }
  return added;
}

void compactMaterials(Hierarchy& h) {
  std::vector<int> remap(h.materials.size(), -1);
  for (const Block& b : h.blocks) {
    for (const Cell& c : b.cells)
      if (c.hasMaterial()) remap[c.material] = 0;
    for (const PlaneCut& cut : b.cuts)
      for (const auto& m : cut.surfaceMaterials)
        if (m) remap[*m] = 0;
  }
  std::vector<Material> kept;
  std::vector<std::uint16_t> to(remap.size(), 0);
  for (std::size_t m = 0; m < remap.size(); ++m)
    if (remap[m] == 0) {
      to[m] = static_cast<std::uint16_t>(kept.size());
      kept.push_back(h.materials[m]);
    }
  for (Block& b : h.blocks) renumberMaterials(b, to);
  h.materials = std::move(kept);
}

void renumberMaterials(Block& b, const std::vector<std::uint16_t>& to) {
  for (Cell& c : b.cells)
    if (c.hasMaterial()) c.material = to[c.material];
  for (PlaneCut& cut : b.cuts)
    for (auto& m : cut.surfaceMaterials)
      if (m) m = to[*m];
}

}  // namespace nut::converter
