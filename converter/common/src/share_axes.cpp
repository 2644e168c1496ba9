// Refining block axes to shared boundary sets (converter/share_axes.hpp).
#include <converter/share_axes.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <iterator>
#include <map>
#include <vector>

#include <nut/format.hpp>
#include <nut/metadata.hpp>
#include <nut/solids.hpp>
#include <nut/units.hpp>

namespace nut::converter {

namespace {

// Estimated PNG bytes of a metadata pixel (both rows) and of a cell (`nut info --bytes` on the
// samples: 1.1-1.7 bytes per metadata pixel, 0.02-0.1 per cell). The cell weight is the high end,
// twice the block search's (pngBytesEstimate): a refinement is only tried when it clearly pays.
constexpr double kBytesPerMetadataPixel = 1.1;
constexpr double kBytesPerCell = 0.1;

using Units = std::vector<std::int64_t>;

Units unitsOf(const std::vector<double>& boundsM) {
  Units u;
  for (double m : boundsM) u.push_back(toUnits(m));
  return u;
}

int pixelsOf(const Units& bounds, double tolerance) {
  auto index = buildAxisIndexWithin(bounds, tolerance);
  return index ? index->pixels() : -1;
}

// Whether a cell cut across axis a shows in each part what it showed there.
bool cuttable(const Cell& c, int a) {
  if (c.kind != CellKind::Solid || c.solid.index == 0) return true;
  const SolidGroup g = solidGroup(c.solid);
  const bool extruded = g == SolidGroup::Wedge || g == SolidGroup::QuarterCylinder || g == SolidGroup::InverseQuarterCylinder;
  return extruded && solidOrientation(c.solid) / 4 == a;
}

// Whether every layer of b along a that the new boundaries cut holds only cuttable cells.
bool cuttableAt(const Block& b, int a, const Units& from, const Units& to) {
  for (std::size_t i = 0; i + 1 < from.size(); ++i) {
    const bool cut = std::any_of(to.begin(), to.end(), [&](std::int64_t t) { return t > from[i] && t < from[i + 1]; });
    if (!cut) continue;
    std::array<int, 3> at{};
    for (at[2] = 0; at[2] < b.cellCount(2); ++at[2])
      for (at[1] = 0; at[1] < b.cellCount(1); ++at[1])
        for (at[0] = 0; at[0] < b.cellCount(0); ++at[0])
          if (at[static_cast<std::size_t>(a)] == static_cast<int>(i) && !cuttable(b.cell(at[0], at[1], at[2]), a)) return false;
  }
  return true;
}

// b with axis a at the boundaries `to` (a superset of its own): each new layer copies the layer
// it lies in; a redirection cell that starts further into its old cell shows the target from
// there (its offset along a shorter by as much), with records shared where equal.
Block refined(const Block& b, int a, const Units& to) {
  const Units from = unitsOf(b.boundsM[static_cast<std::size_t>(a)]);
  Block out;
  out.boundsM = b.boundsM;
  out.boundsM[static_cast<std::size_t>(a)].clear();
  for (std::int64_t t : to) out.boundsM[static_cast<std::size_t>(a)].push_back(toMetres(t));
  out.redirections = b.redirections;
  out.cuts = b.cuts;  // plane cells keep their planes, which are the block's
  out.cells.resize(static_cast<std::size_t>(out.cellCount(0)) * static_cast<std::size_t>(out.cellCount(1)) * static_cast<std::size_t>(out.cellCount(2)));
  std::map<std::pair<std::uint32_t, std::int64_t>, std::uint32_t> shifted;  // (record, shift) -> record
  std::array<int, 3> at{};
  for (at[2] = 0; at[2] < out.cellCount(2); ++at[2])
    for (at[1] = 0; at[1] < out.cellCount(1); ++at[1])
      for (at[0] = 0; at[0] < out.cellCount(0); ++at[0]) {
        const std::int64_t start = to[static_cast<std::size_t>(at[static_cast<std::size_t>(a)])];
        const auto layer = static_cast<int>(std::upper_bound(from.begin(), from.end(), start) - from.begin()) - 1;
        std::array<int, 3> src = at;
        src[static_cast<std::size_t>(a)] = layer;
        Cell c = b.cell(src[0], src[1], src[2]);
        const std::int64_t shift = start - from[static_cast<std::size_t>(layer)];
        if (c.kind == CellKind::Redirection && shift != 0) {
          auto [it, added] = shifted.try_emplace({c.redirection, shift}, static_cast<std::uint32_t>(out.redirections.size()));
          if (added) {
            Redirection r = out.redirections[c.redirection];
            r.offsetM[a] = toMetres(toUnits(r.offsetM[a]) - shift);
            out.redirections.push_back(r);
          }
          c.redirection = it->second;
        }
        out.cell(at[0], at[1], at[2]) = c;
      }
  return out;
}

Units unionOf(const Units& x, const Units& y) {
  Units u;
  std::set_union(x.begin(), x.end(), y.begin(), y.end(), std::back_inserter(u));
  return u;
}

// Whether b's data component stays within the format's width with n cells along axis a.
bool dataFits(const Block& b, int a, std::size_t n) {
  std::array<long long, 3> cells{b.cellCount(0), b.cellCount(1), b.cellCount(2)};
  cells[static_cast<std::size_t>(a)] = static_cast<long long>(n);
  return cells[0] * cells[2] <= format::kMaxImageSize && cells[1] <= format::kMaxImageSize;
}

long long crossSection(const Block& b, int a) {
  return static_cast<long long>(b.cellCount((a + 1) % 3)) * b.cellCount((a + 2) % 3);
}

}  // namespace

int shareAxes(Hierarchy& h, double heuristicToleranceM) {
  struct Axis {
    std::size_t block;
    int a;
  };
  // Axes of two or more cells, by size.
  std::map<std::int64_t, std::vector<Axis>> bySize;
  for (std::size_t b = 0; b < h.blocks.size(); ++b)
    for (int a = 0; a < 3; ++a)
      if (h.blocks[b].cellCount(a) > 1) bySize[toUnits(h.blocks[b].boundsM[static_cast<std::size_t>(a)].back())].push_back({b, a});
  int refinedAxes = 0;
  for (auto& [size, axes] : bySize) {
    // Greedy: each axis joins the first group whose union it can share with profit.
    struct Group {
      Units bounds;
      std::vector<Axis> members;
    };
    std::vector<Group> groups;
    for (const Axis& x : axes) {
      const Block& b = h.blocks[x.block];
      const Units own = unitsOf(b.boundsM[static_cast<std::size_t>(x.a)]);
      bool joined = false;
      for (Group& g : groups) {
        if (g.bounds == own) {
          g.members.push_back(x);  // an equal item already: stored once as it is
          joined = true;
          break;
        }
        const Units u = unionOf(g.bounds, own);
        const int pixels = pixelsOf(u, heuristicToleranceM);
        if (pixels < 0) continue;
        // Pixels saved: the two items become one; cells added: every member's new layers.
        const double saved = static_cast<double>(pixelsOf(g.bounds, heuristicToleranceM) + pixelsOf(own, heuristicToleranceM) - pixels);
        double added = static_cast<double>(u.size() - own.size()) * static_cast<double>(crossSection(b, x.a));
        for (const Axis& m : g.members) added += static_cast<double>(u.size() - g.bounds.size()) * static_cast<double>(crossSection(h.blocks[m.block], m.a));
        if (saved * kBytesPerMetadataPixel <= added * kBytesPerCell) continue;
        if (!dataFits(b, x.a, u.size() - 1) || !cuttableAt(b, x.a, own, u)) continue;
        const bool othersCuttable = std::all_of(g.members.begin(), g.members.end(), [&](const Axis& m) {
          const Block& other = h.blocks[m.block];
          return dataFits(other, m.a, u.size() - 1) && cuttableAt(other, m.a, unitsOf(other.boundsM[static_cast<std::size_t>(m.a)]), u);
        });
        if (!othersCuttable) continue;
        g.bounds = u;
        g.members.push_back(x);
        joined = true;
        break;
      }
      if (!joined) groups.push_back({own, {x}});
    }
    for (const Group& g : groups)
      for (const Axis& m : g.members) {
        Block& b = h.blocks[m.block];
        if (unitsOf(b.boundsM[static_cast<std::size_t>(m.a)]) == g.bounds) continue;
        b = refined(b, m.a, g.bounds);
        ++refinedAxes;
      }
  }
  return refinedAxes;
}

}  // namespace nut::converter
