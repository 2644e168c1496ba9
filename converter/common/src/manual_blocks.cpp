// The paper's user-selected blocks (manual_blocks.hpp): one-to-many width matching of a box's
// cells against the whole grid.
#include "manual_blocks.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include <nut/units.hpp>

namespace nut::converter {

namespace {

// The cells of g0 that a world box covers (snapped outwards to whole cells), or nullopt when it
// misses g0.
std::optional<std::pair<std::array<int, 3>, std::array<int, 3>>> cellRange(const Block& g0, const WorldBox& box,
                                                                           const glm::dvec3& originM) {
  std::array<int, 3> lo{}, hi{};
  for (int a = 0; a < 3; ++a) {
    const auto& bounds = g0.boundsM[static_cast<std::size_t>(a)];
    const double l = box.min[a] - originM[a], u = box.max[a] - originM[a];
    if (u <= 0 || l >= bounds.back()) return std::nullopt;
    lo[static_cast<std::size_t>(a)] =
        std::max(0, static_cast<int>(std::upper_bound(bounds.begin(), bounds.end(), l) - bounds.begin()) - 1);
    hi[static_cast<std::size_t>(a)] =
        std::min(g0.cellCount(a), static_cast<int>(std::lower_bound(bounds.begin(), bounds.end(), u) - bounds.begin()));
    if (hi[static_cast<std::size_t>(a)] <= lo[static_cast<std::size_t>(a)]) return std::nullopt;
  }
  return std::make_pair(lo, hi);
}

// One axis of a manual block's pattern, as pieces to match g0's cells against: a piece is a cell
// of the simplified block S, or (the second way to match, see axisMatches) a cell of the box as
// selected, which is part of an S cell.
struct Piece {
  double widthM = 0.0;
  int sCell = 0;              // the S cell it belongs to
  std::int64_t posUnits = 0;  // its minimum corner inside S
  bool wholeCell = true;      // it is the whole S cell
};

// How the g0 cells from some start along one axis map onto S: g0 cell start + k shows S cell
// sCell[k] from position posUnits[k] inside S; whole[k] when it alone stands for a whole S cell.
struct AxisMap {
  std::vector<int> sCell;
  std::vector<std::int64_t> posUnits;
  std::vector<bool> whole;
  friend bool operator==(const AxisMap&, const AxisMap&) = default;
};

// The paper's one-to-many width matching along axis a of g0 from cell `start`: each piece takes
// successive g0 cells whose widths sum to the piece's width within the tolerance. Greedy: a piece
// takes cells until their sum reaches its width minus the tolerance and is rejected when that sum
// exceeds its width plus the tolerance (the shortest group that fits; no backtracking). A g0 cell
// inside a group shows S from the group's start in S plus the g0 widths before it in the group.
std::optional<AxisMap> groupAxis(const Block& g0, int a, int start, const std::vector<Piece>& pieces, double slack) {
  const auto& bounds = g0.boundsM[static_cast<std::size_t>(a)];
  const int n = g0.cellCount(a);
  AxisMap map;
  int j = start;
  for (const Piece& piece : pieces) {
    if (j >= n) return std::nullopt;
    const int first = j;
    const double from = bounds[static_cast<std::size_t>(first)];
    double sum = 0.0;
    do {
      ++j;
      sum = bounds[static_cast<std::size_t>(j)] - from;
    } while (j < n && sum < piece.widthM - slack);
    if (std::abs(sum - piece.widthM) > slack) return std::nullopt;
    for (int k = first; k < j; ++k) {
      map.sCell.push_back(piece.sCell);
      map.posUnits.push_back(piece.posUnits + toUnits(bounds[static_cast<std::size_t>(k)] - from));
      map.whole.push_back(piece.wholeCell && j - first == 1);
    }
  }
  return map;
}

// The ways g0's cells from `start` along axis a can match S, best first: grouped against the cells
// of S, then against the cells of the box as selected. The second keeps every place that matches
// the selection cell for cell (against the unsimplified selection), which grouping against S
// can miss: the tolerance is per group, so small differences in several merged cells add up, and
// the greedy grouping can end a group early when a g0 cell is narrower than twice the tolerance.
std::vector<AxisMap> axisMatches(const Block& g0, int a, int start, const std::array<std::vector<Piece>, 2>& pieces,
                                 double slack) {
  std::vector<AxisMap> out;
  for (const auto& p : pieces)
    if (auto m = groupAxis(g0, a, start, p, slack); m && std::find(out.begin(), out.end(), *m) == out.end())
      out.push_back(std::move(*m));
  return out;
}

// Per axis: the pieces of S (index 0) and of the selection (index 1), whose boundaries include
// S's, the same values.
std::array<std::array<std::vector<Piece>, 2>, 3> piecesOf(const Block& pattern, const Block& selected) {
  std::array<std::array<std::vector<Piece>, 2>, 3> pieces;
  for (std::size_t a = 0; a < 3; ++a) {
    const auto& sb = pattern.boundsM[a];
    const auto& ub = selected.boundsM[a];
    for (std::size_t i = 0; i + 1 < sb.size(); ++i)
      pieces[a][0].push_back(Piece{sb[i + 1] - sb[i], static_cast<int>(i), toUnits(sb[i]), true});
    for (std::size_t k = 0; k + 1 < ub.size(); ++k) {
      const auto i = static_cast<std::size_t>(std::upper_bound(sb.begin(), sb.end(), ub[k]) - sb.begin()) - 1;
      const bool whole = toUnits(ub[k]) == toUnits(sb[i]) && toUnits(ub[k + 1]) == toUnits(sb[i + 1]);
      pieces[a][1].push_back(Piece{ub[k + 1] - ub[k], static_cast<int>(i), toUnits(ub[k]), whole});
    }
  }
  return pieces;
}

// A place of g0 that shows S: its first cell, and how its cells map onto S along each axis.
struct Place {
  std::array<int, 3> at;
  std::array<const AxisMap*, 3> map;
};

// The places of g0 that show S, found in cell order, none overlapping another. `matches`: per axis
// and start cell, the ways g0's cells from there map onto S (axisMatches).
std::vector<Place> findPlaces(const Block& g0, const Block& pattern,
                              const std::array<std::vector<std::vector<AxisMap>>, 3>& matches) {
  std::vector<Place> places;
  std::vector<bool> claimed(g0.cells.size(), false);  // cells of places found, which others may not overlap
  const auto fits = [&](const std::array<int, 3>& at, const std::array<const AxisMap*, 3>& m) {
    const std::array<int, 3> n{static_cast<int>(m[0]->sCell.size()), static_cast<int>(m[1]->sCell.size()),
                               static_cast<int>(m[2]->sCell.size())};
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x) {
          const std::size_t index = g0.cellIndex(at[0] + x, at[1] + y, at[2] + z);
          if (claimed[index]) return false;
          const auto sx = static_cast<std::size_t>(x), sy = static_cast<std::size_t>(y),
                     sz = static_cast<std::size_t>(z);
          const Cell& s = pattern.cell(m[0]->sCell[sx], m[1]->sCell[sy], m[2]->sCell[sz]);
          if (!sameAtAnotherPlace(g0.cells[index], s)) return false;
          if (!stretchable(s) && !(m[0]->whole[sx] && m[1]->whole[sy] && m[2]->whole[sz])) return false;
        }
    return true;
  };
  // The first combination of per-axis matches whose cells fit at `at`, if any.
  const auto firstFit = [&](const std::array<int, 3>& at) -> std::optional<std::array<const AxisMap*, 3>> {
    for (const AxisMap& cz : matches[2][static_cast<std::size_t>(at[2])])
      for (const AxisMap& cy : matches[1][static_cast<std::size_t>(at[1])])
        for (const AxisMap& cx : matches[0][static_cast<std::size_t>(at[0])])
          if (const std::array<const AxisMap*, 3> m{&cx, &cy, &cz}; fits(at, m)) return m;
    return std::nullopt;
  };
  for (int z = 0; z < g0.cellCount(2); ++z)
    for (int y = 0; y < g0.cellCount(1); ++y)
      for (int x = 0; x < g0.cellCount(0); ++x) {
        if (claimed[g0.cellIndex(x, y, z)]) continue;
        const std::array<int, 3> at{x, y, z};
        const auto m = firstFit(at);
        if (!m) continue;
        places.push_back(Place{at, *m});
        for (std::size_t k = 0; k < (*m)[2]->sCell.size(); ++k)
          for (std::size_t j = 0; j < (*m)[1]->sCell.size(); ++j)
            for (std::size_t i = 0; i < (*m)[0]->sCell.size(); ++i)
              claimed[g0.cellIndex(x + static_cast<int>(i), y + static_cast<int>(j), z + static_cast<int>(k))] = true;
      }
  return places;
}

// Every cell of every place redirects to S (block `target`) with the offset of its own corner
// inside S; one record per distinct offset.
void redirectPlaces(Block& g0, BlockId target, const std::vector<Place>& places) {
  std::map<std::array<std::int64_t, 3>, std::uint32_t> records;  // offset (units) -> record index
  for (const Place& p : places) {
    const auto& [mx, my, mz] = p.map;
    for (std::size_t k = 0; k < mz->sCell.size(); ++k)
      for (std::size_t j = 0; j < my->sCell.size(); ++j)
        for (std::size_t i = 0; i < mx->sCell.size(); ++i) {
          const std::array<std::int64_t, 3> pos{mx->posUnits[i], my->posUnits[j], mz->posUnits[k]};
          auto [it, added] = records.try_emplace(pos, static_cast<std::uint32_t>(g0.redirections.size()));
          if (added)
            g0.redirections.push_back(Redirection{target,
                                                  -glm::dvec3(toMetres(pos[0]), toMetres(pos[1]), toMetres(pos[2])),
                                                  Rotation{},
                                                  {false, false, false}});
          g0.cell(p.at[0] + static_cast<int>(i), p.at[1] + static_cast<int>(j), p.at[2] + static_cast<int>(k)) =
              Cell::redirect(it->second);
        }
  }
}

}  // namespace

// The paper's user-selected block: the cells the box covers, simplified (neighbour layers holding
// the same boxes and empty cells merge, so boundaries that only other parts of g0 needed go), become
// block S. Every place of g0 whose cells can be grouped along each axis to match S's widths (within
// the tolerance; groupAxis) and whose cells all equal the S cell they fall in redirects to S, each
// cell with the offset of its own corner inside S; a cell that is part of a group shows only its
// part of the S cell, so only boxes and empty S cells (which look the same however they are cut)
// may be grouped. One record per distinct offset: places that match cell for cell share records,
// so later repeats of the places are identical and the automatic search can tile them.
void extractManual(Hierarchy& h, Block& g0, const WorldBox& box, const glm::dvec3& originM, double tolerance,
                   BlockStats& stats) {
  const auto range = cellRange(g0, box, originM);
  if (!range) return;
  const auto [lo, hi] = *range;
  const Block selected = subBlock(g0, lo, hi);
  Block pattern = selected;
  simplify(pattern);
  // 1e-9 m absorbs rounding of differences of boundaries, so a tolerance of 0 matches equal widths.
  const double slack = tolerance + 1e-9;
  const auto pieces = piecesOf(pattern, selected);
  std::array<std::vector<std::vector<AxisMap>>, 3> matches;  // per axis and start
  for (int a = 0; a < 3; ++a)
    for (int s = 0; s < g0.cellCount(a); ++s)
      matches[static_cast<std::size_t>(a)].push_back(axisMatches(g0, a, s, pieces[static_cast<std::size_t>(a)], slack));
  const std::vector<Place> places = findPlaces(g0, pattern, matches);
  const BlockId target = h.addBlock(pattern);
  redirectPlaces(g0, target, places);
  ExtractedBlock found;
  found.block = target;
  found.cells = {pattern.cellCount(0), pattern.cellCount(1), pattern.cellCount(2)};
  found.sizeM = pattern.sizeM();
  found.instances = static_cast<int>(places.size());
  found.manual = true;
  stats.found.push_back(found);
}

}  // namespace nut::converter
