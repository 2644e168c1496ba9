// The derivation as a NUT hierarchy (grammar/derive.hpp, derivationHierarchy): one block per node.
#include <grammar/derive.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include <converter/assemble.hpp>
#include <converter/blocks.hpp>

namespace nut::grammar {

namespace {

// Boundaries closer than this are one: the format stores millimetres.
constexpr double kMergeM = 5e-4;

std::vector<double> axisBounds(const Node& node, int axis) {
  const double size = node.sizeM[axis];
  std::vector<double> v{0.0, size};
  for (const Piece& p : node.pieces)
    for (double b : {p.region.min[axis], p.region.max[axis]}) v.push_back(std::clamp(b, 0.0, size));
  std::sort(v.begin(), v.end());
  std::vector<double> bounds{0.0};
  for (double b : v)
    if (b - bounds.back() > kMergeM) bounds.push_back(b);
  bounds.back() = size;  // the last boundary is the size, even where a piece ends just short of it
  return bounds;
}

// Block ids of the nodes the root reaches, in node order (a node's pieces name earlier nodes), and
// -1 for nodes a layer or a clip left unused.
std::vector<long> reachedBlocks(const Derivation& d) {
  std::vector<char> reached(d.nodes.size(), 0);
  reached[d.root.node] = 1;
  for (std::size_t i = d.nodes.size(); i-- > 0;)
    if (reached[i])
      for (const Piece& p : d.nodes[i].pieces)
        if (p.kind == Piece::Kind::Node) reached[p.node] = 1;
  std::vector<long> id(d.nodes.size(), -1);
  long next = 0;
  for (std::size_t i = 0; i < d.nodes.size(); ++i)
    if (reached[i]) id[i] = next++;
  return id;
}

// The cells [first, last) of `bounds` that a piece's [lo, hi] covers.
std::pair<int, int> cellRange(const std::vector<double>& bounds, double lo, double hi) {
  const auto cell = [&](double v) {
    return static_cast<int>(std::upper_bound(bounds.begin(), bounds.end(), v) - bounds.begin()) - 1;
  };
  const int first = std::max(0, cell(lo + kMergeM / 2));
  const int last = std::min(static_cast<int>(bounds.size()) - 1, cell(hi - kMergeM / 2) + 1);
  return {first, last};
}

Block blockOf(const Node& node, const std::vector<long>& blockId) {
  Block b;
  for (int a = 0; a < 3; ++a) b.boundsM[static_cast<std::size_t>(a)] = axisBounds(node, a);
  b.cells.assign(static_cast<std::size_t>(b.cellCount(0)) * static_cast<std::size_t>(b.cellCount(1)) *
                     static_cast<std::size_t>(b.cellCount(2)),
                 Cell::empty());
  // Pieces do not overlap, so each cell is covered by one piece at most: fill each piece's cells.
  using RecordKey = std::tuple<BlockId, double, double, double, int, std::array<bool, 3>>;
  std::map<RecordKey, std::uint32_t> records;
  for (const Piece& p : node.pieces) {
    std::array<std::pair<int, int>, 3> range;
    for (int a = 0; a < 3; ++a) range[a] = cellRange(b.boundsM[a], p.region.min[a], p.region.max[a]);
    for (int z = range[2].first; z < range[2].second; ++z)
      for (int y = range[1].first; y < range[1].second; ++y)
        for (int x = range[0].first; x < range[0].second; ++x) {
          if (p.kind == Piece::Kind::Box) {
            b.cell(x, y, z) = Cell::box(p.material);
            continue;
          }
          const glm::dvec3 lo(b.boundsM[0][x], b.boundsM[1][y], b.boundsM[2][z]);
          const auto target = static_cast<BlockId>(blockId[p.node]);
          const glm::dvec3 offset = p.offsetM - lo;
          const auto [it, added] = records.try_emplace(RecordKey{target, offset.x, offset.y, offset.z, p.cube, p.wrap},
                                                       static_cast<std::uint32_t>(b.redirections.size()));
          if (added) b.redirections.push_back({target, offset, Rotation{static_cast<std::uint8_t>(p.cube), 0}, p.wrap});
          b.cell(x, y, z) = Cell::redirect(it->second);
        }
  }
  return b;
}

}  // namespace

Result<Hierarchy> derivationHierarchy(const Derivation& d, glm::dvec3& originM) {
  if (d.root.kind != Piece::Kind::Node || d.root.cube != 0) return Error{"the derivation's root is not a node"};
  Hierarchy h;
  h.materials = d.materials;
  const std::vector<long> blockId = reachedBlocks(d);
  for (std::size_t i = 0; i < d.nodes.size(); ++i) {
    if (blockId[i] < 0) continue;
    Block b = blockOf(d.nodes[i], blockId);
    converter::simplify(b);
    h.addBlock(std::move(b));
  }
  h.root = static_cast<BlockId>(blockId[d.root.node]);
  originM = d.root.offsetM;
  auto added = converter::splitBlocks(h);
  if (!added) return added.error();
  converter::compactMaterials(h);
  if (Status s = checkHierarchy(h); !s) return s.error();
  if (const int depth = dagDepth(h); depth > 31)
    return Error{"the grammar nests " + std::to_string(depth) + " levels of shapes; the format's casters follow 31"};
  return h;
}

}  // namespace nut::grammar
