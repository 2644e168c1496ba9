// Block extraction and simplification (converter/blocks.hpp), top-down: a block is simplified
// (identical neighbouring layers of boxes and empty cells, or of cells placing one block at one
// place, merge, which removes the boundaries only other parts needed), then cut along one axis
// where that pays most:
//
//   repeat  a run of layers whose width pattern (within the tolerance) and content repeat with
//           period p, r times, becomes one cell that redirects to a block of one period, tiled
//           (wrapped) along the axis; what precedes and follows the run become cells of their own.
//           This is the paper's block extraction with its "merge aligned touching repeats".
//   split   the block is cut in two where the two halves need the fewest boundaries between them
//           (a base whose shop windows share no boundary with the floors above; the four houses
//           of a street block).
//
// The parts are decomposed the same way, recursively, so a floor repeated up a tower is found
// first and the window bay repeated along the floor inside it. The cost model counts cells (4
// bytes each in a data component); a cut is taken when it saves at least BlockOptions::
// minSavedCells cells, where a redirection record to a round piece counts as a share of a block
// (findRecordCut). BlockOptions::priced prices every cut in estimated PNG bytes instead. Boxes a
// person selected (--block) are extracted first (manual_blocks.cpp).
#include <converter/blocks.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <nut/format.hpp>
#include <nut/metadata.hpp>
#include <nut/solids.hpp>
#include <nut/units.hpp>

#include "manual_blocks.hpp"

namespace nut::converter {

namespace {
// pngBytesEstimate's weights.
constexpr double kHeaderBytes = 30, kBytesPerMetadataPixel = 1.1, kBytesPerCell = 0.05, kBytesPerRecord = 4;
}  // namespace

long long estimatedBytes(const Block& b) {
  long long bytes = 4LL * format::kHeaderPixels;
  for (int a = 0; a < 3; ++a) bytes += 8LL * std::min(format::kMaxMetadataPixels, b.cellCount(a) + 1);
  bytes += 4LL * static_cast<long long>(b.cells.size());
  bytes += 16LL * static_cast<long long>(b.redirections.size());
  return bytes;
}

Block subBlock(const Block& b, const std::array<int, 3>& lo, const std::array<int, 3>& hi) {
  Block out;
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
    const double base = bounds[static_cast<std::size_t>(lo[static_cast<std::size_t>(a)])];
    for (int i = lo[static_cast<std::size_t>(a)]; i <= hi[static_cast<std::size_t>(a)]; ++i)
      out.boundsM[static_cast<std::size_t>(a)].push_back(snapToUnits(bounds[static_cast<std::size_t>(i)] - base));
  }
  out.cells.reserve(static_cast<std::size_t>(hi[0] - lo[0]) * static_cast<std::size_t>(hi[1] - lo[1]) * static_cast<std::size_t>(hi[2] - lo[2]));
  for (int z = lo[2]; z < hi[2]; ++z)
    for (int y = lo[1]; y < hi[1]; ++y)
      for (int x = lo[0]; x < hi[0]; ++x) out.cells.push_back(b.cell(x, y, z));
  out.redirections = b.redirections;  // cells keep their record and cut indices
  // The planes move into the sub-block's frame: n . (p + base) <= d is n . p <= d - n . base.
  glm::dvec3 base;
  for (int a = 0; a < 3; ++a)
    base[a] = b.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(lo[static_cast<std::size_t>(a)])];
  out.cuts = b.cuts;
  for (PlaneCut& cut : out.cuts)
    for (CutPlane& plane : cut.planes) plane.offsetM -= glm::dot(plane.normal, base);
  return out;
}

double pngBytesEstimate(const Block& b, double heuristicToleranceM) {
  double bytes = kHeaderBytes;
  for (int a = 0; a < 3; ++a) {
    std::vector<std::int64_t> units;
    for (double m : b.boundsM[static_cast<std::size_t>(a)]) units.push_back(toUnits(m));
    const auto index = buildAxisIndexWithin(units, heuristicToleranceM);
    // An axis no index fits is split into blocks of full items.
    bytes += kBytesPerMetadataPixel * (index ? index->pixels() : 2 * format::kMaxMetadataPixels);
  }
  std::vector<bool> used(b.redirections.size(), false);
  for (const Cell& c : b.cells)
    if (c.kind == CellKind::Redirection && !used[c.redirection]) {
      used[c.redirection] = true;
      bytes += kBytesPerRecord;
    }
  return bytes + kBytesPerCell * static_cast<double>(b.cells.size());
}

namespace {

// Deeper than this the ray casters' 32-level stack would run out (docs/RENDERING.md).
constexpr int kMaxDepth = 24;
// Repeats longer than this many layers per period are not searched for.
constexpr int kMaxPeriod = 64;
// findRecordCut: blocks larger than this are not tried (every cut is built), and a block costs
// about as much as this many redirection records (a header and metadata against 4 pixels).
constexpr std::size_t kMaxRecordCutCells = 20000;
constexpr long long kRecordsPerBlock = 40;
// BlockOptions::priced: larger blocks are cut by cells first (every cut is built); a parent
// stacking two or three parts costs about this many PNG bytes.
constexpr std::size_t kMaxPricedCells = 50000;
constexpr double kStackBytes = 45;
// A surface within this (in a cell's unit cube) of a part's corner only touches the part.
constexpr double kCoverageEpsilon = 1e-6;

// What a part of a block becomes in its parent: a plain cell, or a redirection to a block (a
// block of its own, or the block a part that is one redirection cell shows, placed as it was).
struct Part {
  Cell cell;                 // when target is empty
  std::optional<BlockId> target;
  std::array<bool, 3> wrap{false, false, false};
  glm::dvec3 offsetM{0.0};
  Rotation rotation;

  bool placedAsItself() const { return offsetM == glm::dvec3(0.0) && rotation == Rotation{} && wrap == std::array<bool, 3>{}; }
};


// Index steps of b's cells along axis a and the next two axes in cyclic order, so that loops over
// layers walk the cell array directly.
struct Strides {
  std::size_t a, b, c;
  int nb, nc;
};
Strides stridesOf(const Block& block, int a) {
  const std::array<std::size_t, 3> step{1, static_cast<std::size_t>(block.cellCount(0)),
                                        static_cast<std::size_t>(block.cellCount(0)) * static_cast<std::size_t>(block.cellCount(1))};
  return {step[static_cast<std::size_t>(a)], step[static_cast<std::size_t>((a + 1) % 3)], step[static_cast<std::size_t>((a + 2) % 3)],
          block.cellCount((a + 1) % 3), block.cellCount((a + 2) % 3)};
}

// Whether `upper`, the neighbour of `lower` along axis a (lower being widthM wide along a), goes
// on showing what lower shows, so that the two may be one cell: equal boxes or empty cells, or
// redirections placing the same target at the same place of b (the target is clipped by the
// cell, so the merged cell shows the union of the two views). A round corner or dome held by a
// sub-block redirects each cell its box is cut into with its own offset; boundaries that only
// cut such a box go, like those that only cut a wall.
bool continues(const Block& b, const Cell& lower, const Cell& upper, int a, double widthM) {
  if (lower == upper) return stretchable(lower);
  if (lower.kind != CellKind::Redirection || upper.kind != CellKind::Redirection) return false;
  const Redirection& l = b.redirections[lower.redirection];
  const Redirection& u = b.redirections[upper.redirection];
  if (l.target != u.target || !(l.rotation == u.rotation) || l.wrap != u.wrap) return false;
  for (int o = 0; o < 3; ++o)
    if (toUnits(u.offsetM[o]) != toUnits(l.offsetM[o] - (o == a ? widthM : 0.0))) return false;
  return true;
}

bool sameLayers(const Block& b, const Strides& st, int i, int j) {
  const Cell* x = b.cells.data() + static_cast<std::size_t>(i) * st.a;
  const Cell* y = b.cells.data() + static_cast<std::size_t>(j) * st.a;
  for (int k = 0; k < st.nc; ++k)
    for (int l = 0; l < st.nb; ++l) {
      const std::size_t o = static_cast<std::size_t>(k) * st.c + static_cast<std::size_t>(l) * st.b;
      if (!sameAtAnotherPlace(x[o], y[o])) return false;
    }
  return true;
}

// Per axis, the first layer equal to each layer (layers[a][i] == i for the first of its kind).
// Walking a layer across the cell array is what costs (an x layer's cells are far apart), so the
// layers are hashed in one pass over the cells in memory order, each layer's candidate is the
// first layer of its hash, and every candidate is verified in a second such pass; only a layer
// whose hash collided is compared layer by layer.
using EqualLayers = std::array<std::vector<int>, 3>;
EqualLayers equalLayers(const Block& b) {
  std::array<std::vector<std::uint64_t>, 3> hash;
  for (int a = 0; a < 3; ++a) hash[static_cast<std::size_t>(a)].assign(static_cast<std::size_t>(b.cellCount(a)), 1469598103934665603ull);
  const std::array<int, 3> n{b.cellCount(0), b.cellCount(1), b.cellCount(2)};
  const auto forEachCell = [&](auto&& visit) {
    std::size_t index = 0;
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x, ++index) visit(index, std::array<int, 3>{x, y, z});
  };
  forEachCell([&](std::size_t index, const std::array<int, 3>& at) {
    const Cell& c = b.cells[index];
    const std::uint64_t v = static_cast<std::uint64_t>(c.kind) | static_cast<std::uint64_t>(c.solid.index) << 8 |
                            static_cast<std::uint64_t>(c.material) << 16 | static_cast<std::uint64_t>(c.redirection) << 32;
    for (std::size_t a = 0; a < 3; ++a) {
      auto& h = hash[a][static_cast<std::size_t>(at[a])];
      h = (h ^ v) * 1099511628211ull;
    }
  });
  EqualLayers layers;
  std::array<std::vector<bool>, 3> verified;
  for (std::size_t a = 0; a < 3; ++a) {
    std::unordered_map<std::uint64_t, int> first;
    layers[a].resize(static_cast<std::size_t>(n[a]));
    for (int i = 0; i < n[a]; ++i) layers[a][static_cast<std::size_t>(i)] = first.try_emplace(hash[a][static_cast<std::size_t>(i)], i).first->second;
    verified[a].assign(static_cast<std::size_t>(n[a]), true);
  }
  const std::array<std::size_t, 3> stride{1, static_cast<std::size_t>(n[0]), static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1])};
  forEachCell([&](std::size_t index, const std::array<int, 3>& at) {
    for (std::size_t a = 0; a < 3; ++a) {
      const auto i = static_cast<std::size_t>(at[a]);
      const auto candidate = static_cast<std::size_t>(layers[a][i]);
      if (candidate != i && verified[a][i] && !sameAtAnotherPlace(b.cells[index], b.cells[index - (i - candidate) * stride[a]]))
        verified[a][i] = false;
    }
  });
  for (int a = 0; a < 3; ++a) {
    auto& cls = layers[static_cast<std::size_t>(a)];
    const Strides st = stridesOf(b, a);
    for (int i = 0; i < n[static_cast<std::size_t>(a)]; ++i) {
      if (verified[static_cast<std::size_t>(a)][static_cast<std::size_t>(i)]) continue;
      cls[static_cast<std::size_t>(i)] = i;
      for (int j = 0; j < i; ++j)
        if (cls[static_cast<std::size_t>(j)] == j && sameLayers(b, st, i, j)) {
          cls[static_cast<std::size_t>(i)] = j;
          break;
        }
    }
  }
  return layers;
}

// Whether every cell of layer i + 1 along axis a continues its neighbour in layer i.
bool mergeableLayers(const Block& b, const Strides& st, int a, int i) {
  const Cell* x = b.cells.data() + static_cast<std::size_t>(i) * st.a;
  const Cell* y = x + st.a;
  const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
  const double width = bounds[static_cast<std::size_t>(i + 1)] - bounds[static_cast<std::size_t>(i)];
  for (int k = 0; k < st.nc; ++k)
    for (int l = 0; l < st.nb; ++l) {
      const std::size_t o = static_cast<std::size_t>(k) * st.c + static_cast<std::size_t>(l) * st.b;
      if (!continues(b, x[o], y[o], a, width)) return false;
    }
  return true;
}

// Whether simplify() would leave b as it is.
bool isSimplified(const Block& b) {
  for (int a = 0; a < 3; ++a) {
    const Strides st = stridesOf(b, a);
    for (int i = 0; i + 1 < b.cellCount(a); ++i)
      if (mergeableLayers(b, st, a, i)) return false;
  }
  return true;
}

}  // namespace

void simplify(Block& b) {
  for (bool changed = true; changed;) {
    changed = false;
    for (int a = 0; a < 3; ++a) {
      const int n = b.cellCount(a);
      if (n < 2) continue;
      std::vector<bool> keepBoundary(static_cast<std::size_t>(n + 1), true);  // boundary i sits before layer i
      const Strides st = stridesOf(b, a);
      for (int i = 1; i < n; ++i) keepBoundary[static_cast<std::size_t>(i)] = !mergeableLayers(b, st, a, i - 1);
      if (std::all_of(keepBoundary.begin(), keepBoundary.end(), [](bool k) { return k; })) continue;
      // Rebuild with the kept layers (the first layer of each merged run stands for it).
      std::vector<int> layers;
      std::vector<double> bounds;
      for (int i = 0; i <= n; ++i)
        if (keepBoundary[static_cast<std::size_t>(i)]) {
          bounds.push_back(b.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(i)]);
          if (i < n) layers.push_back(i);
        }
      Block out;
      out.boundsM = b.boundsM;
      out.boundsM[static_cast<std::size_t>(a)] = bounds;
      out.redirections = b.redirections;
      out.cuts = b.cuts;
      out.cells.resize(static_cast<std::size_t>(out.cellCount(0)) * static_cast<std::size_t>(out.cellCount(1)) * static_cast<std::size_t>(out.cellCount(2)));
      for (int z = 0; z < out.cellCount(2); ++z)
        for (int y = 0; y < out.cellCount(1); ++y)
          for (int x = 0; x < out.cellCount(0); ++x) {
            std::array<int, 3> src{x, y, z};
            src[static_cast<std::size_t>(a)] = layers[static_cast<std::size_t>(src[static_cast<std::size_t>(a)])];
            out.cell(x, y, z) = b.cell(src[0], src[1], src[2]);
          }
      b = std::move(out);
      changed = true;
    }
  }
}

namespace {

std::optional<Cell> uniformCell(const Block& b) {
  if (b.cells.empty()) return Cell::empty();
  const Cell& first = b.cells.front();
  if (!stretchable(first)) return std::nullopt;
  for (const Cell& c : b.cells)
    if (!(c == first)) return std::nullopt;
  return first;
}

struct Run {
  int axis = 0, start = 0, period = 0, count = 0;
  long long savedCells = 0;
};

// The repeat along axis a that removes the most cells: layers [start, start + period * count)
// where layer i and layer i + period hold the same cells and have widths within the tolerance,
// and the whole run is count periods long within the tolerance.
std::optional<Run> findRun(const Block& b, const EqualLayers& equal, int a, double tolerance) {
  const int n = b.cellCount(a);
  const long long slice = static_cast<long long>(b.cellCount((a + 1) % 3)) * b.cellCount((a + 2) % 3);
  const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
  const auto width = [&](int i) { return bounds[static_cast<std::size_t>(i + 1)] - bounds[static_cast<std::size_t>(i)]; };
  const std::vector<int>& cls = equal[static_cast<std::size_t>(a)];
  std::optional<Run> best;
  for (int p = 1; p <= std::min(kMaxPeriod, n / 2); ++p) {
    int i = 0;
    while (i + p < n) {
      // Longest stretch from i where layer k matches layer k + p.
      int k = i;
      while (k + p < n && cls[static_cast<std::size_t>(k)] == cls[static_cast<std::size_t>(k + p)] &&
             std::abs(width(k) - width(k + p)) <= tolerance)
        ++k;
      const int matched = k - i;  // layers i .. k-1 match their successors
      if (matched >= p) {
        int count = matched / p + 1;
        // The run must be count periods long, or the tiling drifts against the content.
        const double period = bounds[static_cast<std::size_t>(i + p)] - bounds[static_cast<std::size_t>(i)];
        while (count >= 2 && std::abs(bounds[static_cast<std::size_t>(i + p * count)] - bounds[static_cast<std::size_t>(i)] - count * period) > tolerance)
          --count;
        const long long saved = static_cast<long long>(p) * (count - 1) * slice;
        if (count >= 2 && (!best || saved > best->savedCells)) best = Run{a, i, p, count, saved};
      }
      i = std::max(k, i + 1);
    }
  }
  return best;
}

struct Cut {
  int axis = 0, at = 0;
  long long savedCells = 0;
};

// Which boundaries each layer needs, for every layer axis at once: need[a][o] holds, for layer i
// of axis a and interior boundary j of its o-th other axis ((a + 1 + o) % 3), whether the cells on
// the two sides of that boundary in that layer differ or are shaped by their cell (row i, column
// j). One pass over the cells in memory order, each compared with its lower neighbour per axis:
// walking layers across the array instead cost a cache miss per cell.
using NeedTable = std::array<std::array<std::vector<std::uint8_t>, 2>, 3>;
NeedTable neededBoundaries(const Block& b) {
  const std::array<int, 3> n{b.cellCount(0), b.cellCount(1), b.cellCount(2)};
  const auto columns = [&](int a, int o) { return static_cast<std::size_t>(std::max(n[static_cast<std::size_t>((a + 1 + o) % 3)] - 1, 0)); };
  NeedTable need;
  for (int a = 0; a < 3; ++a)
    for (int o = 0; o < 2; ++o)
      need[static_cast<std::size_t>(a)][static_cast<std::size_t>(o)].assign(static_cast<std::size_t>(n[static_cast<std::size_t>(a)]) * columns(a, o), 0);
  const std::array<std::size_t, 3> step{1, static_cast<std::size_t>(n[0]), static_cast<std::size_t>(n[0]) * static_cast<std::size_t>(n[1])};
  std::size_t index = 0;
  for (int z = 0; z < n[2]; ++z)
    for (int y = 0; y < n[1]; ++y)
      for (int x = 0; x < n[0]; ++x, ++index) {
        const std::array<int, 3> at{x, y, z};
        for (int d = 0; d < 3; ++d) {
          if (at[static_cast<std::size_t>(d)] == 0) continue;
          const Cell& lower = b.cells[index - step[static_cast<std::size_t>(d)]];
          const auto& bounds = b.boundsM[static_cast<std::size_t>(d)];
          const auto i = static_cast<std::size_t>(at[static_cast<std::size_t>(d)]);
          if (continues(b, lower, b.cells[index], d, bounds[i] - bounds[i - 1])) continue;
          for (int a = 0; a < 3; ++a) {
            if (a == d) continue;
            const int o = (a + 1) % 3 == d ? 0 : 1;
            need[static_cast<std::size_t>(a)][static_cast<std::size_t>(o)]
                [static_cast<std::size_t>(at[static_cast<std::size_t>(a)]) * columns(a, o) + static_cast<std::size_t>(at[static_cast<std::size_t>(d)] - 1)] = 1;
          }
        }
      }
  return need;
}

// The cut in two along any axis that leaves the fewest cells, counting for each half only the
// boundaries of the other two axes that some layer of the half needs.
std::optional<Cut> findCut(const Block& b) {
  std::optional<Cut> best;
  const long long total = static_cast<long long>(b.cells.size());
  const NeedTable table = neededBoundaries(b);
  for (int a = 0; a < 3; ++a) {
    const int n = b.cellCount(a);
    if (n < 2) continue;
    const auto& need = table[static_cast<std::size_t>(a)];
    // Needed boundaries of the halves [0, c) and [c, n), per other axis.
    std::array<std::vector<int>, 2> left, right;
    for (int o = 0; o < 2; ++o) {
      const std::size_t m = need[static_cast<std::size_t>(o)].size() / static_cast<std::size_t>(n);
      std::vector<bool> acc(m, false);
      left[static_cast<std::size_t>(o)].assign(static_cast<std::size_t>(n + 1), 0);
      int count = 0;
      for (int i = 0; i < n; ++i) {
        for (std::size_t j = 0; j < m; ++j)
          if (need[static_cast<std::size_t>(o)][static_cast<std::size_t>(i) * m + j] && !acc[j]) {
            acc[j] = true;
            ++count;
          }
        left[static_cast<std::size_t>(o)][static_cast<std::size_t>(i + 1)] = count;
      }
      std::fill(acc.begin(), acc.end(), false);
      right[static_cast<std::size_t>(o)].assign(static_cast<std::size_t>(n + 1), 0);
      count = 0;
      for (int i = n - 1; i >= 0; --i) {
        for (std::size_t j = 0; j < m; ++j)
          if (need[static_cast<std::size_t>(o)][static_cast<std::size_t>(i) * m + j] && !acc[j]) {
            acc[j] = true;
            ++count;
          }
        right[static_cast<std::size_t>(o)][static_cast<std::size_t>(i)] = count;
      }
    }
    for (int c = 1; c < n; ++c) {
      const long long l = static_cast<long long>(c) * (left[0][static_cast<std::size_t>(c)] + 1) * (left[1][static_cast<std::size_t>(c)] + 1);
      const long long r = static_cast<long long>(n - c) * (right[0][static_cast<std::size_t>(c)] + 1) * (right[1][static_cast<std::size_t>(c)] + 1);
      const long long saved = total - l - r;
      if (!best || saved > best->savedCells) best = Cut{a, c, saved};
    }
  }
  return best;
}

// What the search finds in a block before it cuts it: the repeat that removes the most cells,
// and the cut in two that does (findCut; findRecordCut is the decomposer's, as it depends on the
// options).
struct Found {
  std::optional<Run> run;
  std::optional<Cut> cut;
};

Found findIn(const Block& b, double toleranceM, bool cuts) {
  Found found;
  const EqualLayers equal = equalLayers(b);
  for (int a = 0; a < 3; ++a)
    if (auto r = findRun(b, equal, a, toleranceM); r && (!found.run || r->savedCells > found.run->savedCells)) found.run = r;
  if (cuts) found.cut = findCut(b);
  return found;
}

// The plain cell (a box or empty) that redirection cell `at` of b shows, when it shows one: the
// target's cells under it are all that box or empty, solids counting by what they fill of the
// part the cell shows (a cell beside a round corner, on one side of its arc). Tiled or yawed
// placements, and parts reaching out of the target, are left as they are.
std::optional<Cell> plainView(const Hierarchy& h, const Block& b, const std::array<int, 3>& at) {
  const Redirection& r = b.redirections[b.cell(at[0], at[1], at[2]).redirection];
  if (r.rotation.yaw != 0 || r.wrap != std::array<bool, 3>{}) return std::nullopt;
  const Block& target = h.blocks[r.target];
  glm::dvec3 size;
  for (int a = 0; a < 3; ++a)
    size[a] = b.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(at[static_cast<std::size_t>(a)] + 1)] -
              b.boundsM[static_cast<std::size_t>(a)][static_cast<std::size_t>(at[static_cast<std::size_t>(a)])];
  // The cell's box in the target's frame: R^-1 (p - O) at two opposite corners (R permutes axes).
  const glm::dmat3 inverse = glm::transpose(glm::dmat3(cubeRotationMatrix(r.rotation.cube)));
  const glm::dvec3 c0 = inverse * (-r.offsetM), c1 = inverse * (size - r.offsetM);
  const glm::dvec3 lo = glm::min(c0, c1), hi = glm::max(c0, c1);
  const double slack = 0.5 * format::kMetresPerUnit;
  std::array<int, 3> first{}, last{};
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = target.boundsM[static_cast<std::size_t>(a)];
    if (lo[a] < -slack || hi[a] > bounds.back() + slack) return std::nullopt;
    first[static_cast<std::size_t>(a)] = std::max(0, static_cast<int>(std::upper_bound(bounds.begin(), bounds.end(), lo[a] + slack) - bounds.begin()) - 1);
    last[static_cast<std::size_t>(a)] = std::min(target.cellCount(a) - 1, static_cast<int>(std::lower_bound(bounds.begin(), bounds.end(), hi[a] - slack) - bounds.begin()) - 1);
  }
  std::optional<Cell> seen;
  for (int z = first[2]; z <= last[2]; ++z)
    for (int y = first[1]; y <= last[1]; ++y)
      for (int x = first[0]; x <= last[0]; ++x) {
        Cell c = target.cell(x, y, z);
        if (c.kind == CellKind::Redirection || c.kind == CellKind::Plane) return std::nullopt;
        if (c.kind == CellKind::Solid && c.solid.index != 0) {
          // The part of the cell's unit cube that `at` shows.
          const std::array<int, 3> t{x, y, z};
          glm::dvec3 unitLo, unitHi;
          for (int a = 0; a < 3; ++a) {
            const auto& bounds = target.boundsM[static_cast<std::size_t>(a)];
            const double from = bounds[static_cast<std::size_t>(t[static_cast<std::size_t>(a)])];
            const double width = bounds[static_cast<std::size_t>(t[static_cast<std::size_t>(a)] + 1)] - from;
            unitLo[a] = std::clamp((lo[a] - from) / width, 0.0, 1.0);
            unitHi[a] = std::clamp((hi[a] - from) / width, 0.0, 1.0);
          }
          const Coverage coverage = solidCoverage(c.solid, unitLo, unitHi, kCoverageEpsilon);
          if (coverage == Coverage::Part) return std::nullopt;
          c = coverage == Coverage::All ? Cell::solidCell(Solid{0}, c.material, c.texture) : Cell::empty();
        }
        if (seen && !(*seen == c)) return std::nullopt;
        seen = c;
      }
  return seen;
}

// Replaces the redirection cells of b to blocks [0, pieces) (the solid grid's sub-blocks of round
// pieces; blocks a person selected stay redirected to) that show a plain cell by that cell; true
// when any did.
bool showPlainCells(const Hierarchy& h, Block& b, BlockId pieces) {
  bool changed = false;
  for (int z = 0; z < b.cellCount(2); ++z)
    for (int y = 0; y < b.cellCount(1); ++y)
      for (int x = 0; x < b.cellCount(0); ++x)
        if (const Cell& c = b.cell(x, y, z); c.kind == CellKind::Redirection && b.redirections[c.redirection].target < pieces)
          if (const auto plain = plainView(h, b, {x, y, z})) {
            b.cell(x, y, z) = *plain;
            changed = true;
          }
  return changed;
}

class Decomposer {
 public:
  Decomposer(Hierarchy& h, BlockId pieces, const BlockOptions& options, BlockStats& stats)
      : h_(h), pieces_(pieces), options_(options), stats_(stats) {}

  // What block b becomes in its parent's cell.
  Part decompose(Block b, int depth) {
    simplify(b);
    return decomposeSimplified(b, depth);
  }

  // The same for a block that simplify() leaves as it is. b is only read (a leaf is copied), so
  // the grid that every variant starts from is not copied per variant; `known` is what findIn
  // found in b, when the caller has it.
  Part decomposeSimplified(const Block& b, int depth, const Found* known = nullptr) {
    if (auto part = wholeBlockAsPart(b)) return *part;
    if (depth >= kMaxDepth || (b.cells.size() <= static_cast<std::size_t>(options_.minSavedCells) && !showsPieces(b)))
      return leaf(b);

    if (options_.priced && b.cells.size() <= kMaxPricedCells) return decomposePriced(b, depth);
    const Found found = known ? *known : findIn(b, options_.toleranceM, options_.cuts);
    const std::optional<Run>& run = found.run;
    const std::optional<Cut> cut = bestCut(b, found.cut);
    const long long runSaved = run ? run->savedCells : 0, cutSaved = cut ? cut->savedCells : 0;
    if (std::max(runSaved, cutSaved) < options_.minSavedCells) return leaf(b);
    if (runSaved >= cutSaved) return repeat(b, *run, depth);
    return split(b, *cut, depth);
  }

 private:
  // b as a leaf would be stored: simplified, cells beside round pieces plain.
  Block leafForm(Block b) const {
    simplify(b);
    if (showPlainCells(h_, b, pieces_)) simplify(b);
    return b;
  }
  double leafBytes(const Block& b) const { return pngBytesEstimate(leafForm(b), options_.heuristicToleranceM); }

  // BlockOptions::priced: the cut in two or the repeat whose blocks (each as a leaf, and the
  // parent that stacks them) are estimated smallest, when smaller than b as a leaf.
  Part decomposePriced(const Block& b, int depth) {
    double best = leafBytes(b);
    std::optional<Cut> bestCut;
    std::optional<Run> bestRun;
    const std::array<int, 3> n{b.cellCount(0), b.cellCount(1), b.cellCount(2)};
    const auto part = [&](int a, int from, int to) {
      std::array<int, 3> lo{0, 0, 0}, hi = n;
      lo[static_cast<std::size_t>(a)] = from;
      hi[static_cast<std::size_t>(a)] = to;
      return leafBytes(subBlock(b, lo, hi));
    };
    for (int a = 0; a < 3; ++a)
      for (int at = 1; at < n[static_cast<std::size_t>(a)]; ++at)
        if (const double bytes = kStackBytes + part(a, 0, at) + part(a, at, n[static_cast<std::size_t>(a)]); bytes < best) {
          best = bytes;
          bestCut = Cut{a, at, 0};
        }
    const EqualLayers equal = equalLayers(b);
    for (int a = 0; a < 3; ++a)
      if (auto r = findRun(b, equal, a, options_.toleranceM)) {
        const int end = r->start + r->period * r->count;
        double bytes = kStackBytes + part(a, r->start, r->start + r->period);
        if (r->start > 0) bytes += part(a, 0, r->start);
        if (end < n[static_cast<std::size_t>(a)]) bytes += part(a, end, n[static_cast<std::size_t>(a)]);
        if (bytes < best) {
          best = bytes;
          bestRun = r;
        }
      }
    if (bestRun) return repeat(b, *bestRun, depth);
    if (bestCut) return split(b, *bestCut, depth);
    return leaf(b);
  }

  // Whether cells of b redirect to the solid grid's sub-blocks of round pieces.
  bool showsPieces(const Block& b) const {
    return pieces_ > 0 && std::any_of(b.cells.begin(), b.cells.end(), [&](const Cell& c) {
      return c.kind == CellKind::Redirection && b.redirections[c.redirection].target < pieces_;
    });
  }

  // What b costs as a leaf: cells, and distinct records its cells reference.
  std::pair<long long, long long> leafCost(Block b) const {
    const Block leaf = leafForm(std::move(b));
    std::vector<bool> used(leaf.redirections.size(), false);
    long long records = 0;
    for (const Cell& c : leaf.cells)
      if (c.kind == CellKind::Redirection && !used[c.redirection]) used[c.redirection] = true, ++records;
    return {static_cast<long long>(leaf.cells.size()), records};
  }

  // The cut in two that saves most when a record counts as many cells as it costs bytes (a
  // block's cost, which minSavedCells stands for, is about kRecordsPerBlock records): findCut
  // counts cells only, and a round piece's sub-block cut into many cells by boundaries from a
  // part nearby (a dome on a roof amid the window columns) costs a record per cell until a cut
  // separates it. Tried by cutting, on small blocks whose cells redirect to such pieces.
  std::optional<Cut> findRecordCut(const Block& b) const {
    if (b.cells.size() > kMaxRecordCutCells || !showsPieces(b)) return std::nullopt;
    const long long recordCells = std::max(1LL, options_.minSavedCells / kRecordsPerBlock);
    const auto [cells, records] = leafCost(b);
    std::optional<Cut> best;
    for (int a = 0; a < 3; ++a)
      for (int at = 1; at < b.cellCount(a); ++at) {
        std::array<int, 3> lo{0, 0, 0}, hi{b.cellCount(0), b.cellCount(1), b.cellCount(2)};
        hi[static_cast<std::size_t>(a)] = at;
        const auto [cellsL, recordsL] = leafCost(subBlock(b, lo, hi));
        lo[static_cast<std::size_t>(a)] = at;
        hi[static_cast<std::size_t>(a)] = b.cellCount(a);
        const auto [cellsR, recordsR] = leafCost(subBlock(b, lo, hi));
        const long long saved = cells - cellsL - cellsR + (records - recordsL - recordsR) * recordCells;
        if (!best || saved > best->savedCells) best = Cut{a, at, saved};
      }
    return best;
  }

  // The better of byCells (findCut's) and findRecordCut's.
  std::optional<Cut> bestCut(const Block& b, const std::optional<Cut>& byCells) const {
    if (!options_.cuts) return std::nullopt;
    const std::optional<Cut> byRecords = findRecordCut(b);
    return byRecords && (!byCells || byRecords->savedCells > byCells->savedCells) ? byRecords : byCells;
  }

  // A block that is one plain cell, or one redirection, needs no block of its own.
  static std::optional<Part> wholeBlockAsPart(const Block& b) {
    if (auto uniform = uniformCell(b)) return Part{*uniform, std::nullopt};
    if (b.cells.size() == 1 && b.cells[0].kind == CellKind::Redirection) {
      const Redirection& r = b.redirections[b.cells[0].redirection];
      return Part{Cell::empty(), r.target, r.wrap, r.offsetM, r.rotation};
    }
    return std::nullopt;
  }

  // A block the search cuts no further. Its redirection cells on one side of a round piece's
  // surface kept the piece's placement so far, which let them merge across boundaries nothing
  // else needed; now they become plain cells, which merge with the walls beside them.
  Part leaf(Block b) {
    if (showPlainCells(h_, b, pieces_)) {
      simplify(b);
      if (auto part = wholeBlockAsPart(b)) return *part;
    }
    return emit(std::move(b));
  }

  Part emit(Block b) {
    const BlockId id = h_.addBlock(std::move(b));
    return {Cell::empty(), id};
  }

  // A parent stacking `parts` along axis a at `bounds` (the other axes one cell each).
  Part stack(const Block& b, int a, const std::vector<double>& bounds, const std::vector<Part>& parts) {
    Block parent;
    for (int o = 0; o < 3; ++o) parent.boundsM[static_cast<std::size_t>(o)] = {0.0, b.sizeM()[o]};
    parent.boundsM[static_cast<std::size_t>(a)] = bounds;
    parent.cells.resize(parts.size());
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (!parts[i].target) {
        parent.cells[i] = parts[i].cell;
        continue;
      }
      parent.cells[i] = Cell::redirect(static_cast<std::uint32_t>(parent.redirections.size()));
      parent.redirections.push_back(Redirection{*parts[i].target, parts[i].offsetM, parts[i].rotation, parts[i].wrap});
    }
    return emit(std::move(parent));
  }

  std::array<int, 3> full(const Block& b) const { return {b.cellCount(0), b.cellCount(1), b.cellCount(2)}; }

  Part repeat(const Block& b, const Run& run, int depth) {
    const int a = run.axis, end = run.start + run.period * run.count;
    const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
    std::vector<double> cuts;
    std::vector<Part> parts;
    cuts.push_back(0.0);
    std::array<int, 3> lo{0, 0, 0}, hi = full(b);
    if (run.start > 0) {
      hi[static_cast<std::size_t>(a)] = run.start;
      parts.push_back(decompose(subBlock(b, lo, hi), depth + 1));
      cuts.push_back(bounds[static_cast<std::size_t>(run.start)]);
    }
    lo[static_cast<std::size_t>(a)] = run.start;
    hi[static_cast<std::size_t>(a)] = run.start + run.period;
    Part period = decompose(subBlock(b, lo, hi), depth + 1);
    // The period tiles as a block of its own size (a uniform period merges in simplify; kept for safety).
    if (!period.target || !period.placedAsItself()) period = emit(subBlock(b, lo, hi));
    period.wrap[static_cast<std::size_t>(a)] = true;
    parts.push_back(period);
    cuts.push_back(bounds[static_cast<std::size_t>(end)]);
    if (end < b.cellCount(a)) {
      lo[static_cast<std::size_t>(a)] = end;
      hi[static_cast<std::size_t>(a)] = b.cellCount(a);
      parts.push_back(decompose(subBlock(b, lo, hi), depth + 1));
      cuts.push_back(bounds.back());
    }
    ExtractedBlock found;
    found.block = *period.target;
    const Block& target = h_.blocks[*period.target];
    found.cells = {target.cellCount(0), target.cellCount(1), target.cellCount(2)};
    found.sizeM = target.sizeM();
    found.instances = run.count;
    found.wrap[static_cast<std::size_t>(a)] = true;
    found.savedBytes = 4 * run.savedCells;
    stats_.found.push_back(found);
    return stack(b, a, cuts, parts);
  }

  Part split(const Block& b, const Cut& cut, int depth) {
    const int a = cut.axis;
    std::array<int, 3> lo{0, 0, 0}, hi = full(b);
    hi[static_cast<std::size_t>(a)] = cut.at;
    const Part first = decompose(subBlock(b, lo, hi), depth + 1);
    lo[static_cast<std::size_t>(a)] = cut.at;
    hi[static_cast<std::size_t>(a)] = b.cellCount(a);
    const Part second = decompose(subBlock(b, lo, hi), depth + 1);
    const auto& bounds = b.boundsM[static_cast<std::size_t>(a)];
    return stack(b, a, {0.0, bounds[static_cast<std::size_t>(cut.at)], bounds.back()}, {first, second});
  }

  Hierarchy& h_;
  BlockId pieces_;
  const BlockOptions& options_;
  BlockStats& stats_;
};

long long totalBytes(const Hierarchy& h) {
  long long sum = 0;
  for (const Block& b : h.blocks) sum += estimatedBytes(b);
  return sum;
}

long long totalCells(const Hierarchy& h) {
  long long sum = 0;
  for (const Block& b : h.blocks) sum += static_cast<long long>(b.cells.size());
  return sum;
}

}  // namespace

struct GridSearch {
  bool simplified = false;  // otherwise found is empty: buildHierarchy searches the simplified grid
  Found found;
};

std::shared_ptr<const GridSearch> searchGrid(const Block& grid, double toleranceM) {
  auto search = std::make_shared<GridSearch>();
  search->simplified = isSimplified(grid);
  if (search->simplified) search->found = findIn(grid, toleranceM, true);
  return search;
}

Result<Hierarchy> buildHierarchy(const Block& grid, std::vector<Material> materials, const glm::dvec3& originM,
                                 const BlockOptions& options, BlockStats& stats, const std::vector<Block>& subBlocks,
                                 const GridSearch* search) {
  Hierarchy h;
  h.materials = std::move(materials);
  // The solid grid's sub-blocks (quarter-round pieces) come first: sub-block i is block i, so
  // g0's redirection targets stand as they are in every part g0 is cut into.
  for (const Block& s : subBlocks) h.addBlock(s);
  stats.cellsBefore = static_cast<long long>(grid.cells.size());
  stats.bytesBefore = estimatedBytes(grid);
  if (!options.automatic) {
    Block g0 = grid;
    for (const WorldBox& box : options.manual) extractManual(h, g0, box, originM, options.toleranceM, stats);
    showPlainCells(h, g0, static_cast<BlockId>(subBlocks.size()));
    simplify(g0);
    h.root = h.addBlock(std::move(g0));
  } else {
    const glm::dvec3 size = grid.sizeM();
    Decomposer decomposer(h, static_cast<BlockId>(subBlocks.size()), options, stats);
    Part root;
    if (!options.manual.empty()) {
      Block g0 = grid;
      for (const WorldBox& box : options.manual) extractManual(h, g0, box, originM, options.toleranceM, stats);
      root = decomposer.decompose(std::move(g0), 0);
    } else if (search) {
      root = search->simplified ? decomposer.decomposeSimplified(grid, 0, &search->found) : decomposer.decompose(grid, 0);
    } else {
      root = isSimplified(grid) ? decomposer.decomposeSimplified(grid, 0) : decomposer.decompose(grid, 0);
    }
    if (root.target && root.placedAsItself()) {
      h.root = *root.target;
    } else {
      // The whole building is one box, nothing, or one block placed in it: a block of one cell.
      Block one = Block::fromSizes({{{size.x}, {size.y}, {size.z}}});
      one.cells[0] = root.cell;
      if (root.target) {
        one.cells[0] = Cell::redirect(0);
        one.redirections.push_back(Redirection{*root.target, root.offsetM, root.rotation, root.wrap});
      }
      h.root = h.addBlock(std::move(one));
    }
  }
  stats.cellsAfter = totalCells(h);
  stats.bytesAfter = totalBytes(h);
  return h;
}

}  // namespace nut::converter
