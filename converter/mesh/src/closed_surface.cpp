// Uncancelled edges matched along their supporting lines (closed_surface.hpp).
#include "closed_surface.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "union_find.hpp"

namespace nut::converter {

namespace {

using glm::dvec3;

using Cell = std::array<std::int64_t, 3>;

// A coordinate's cell index, clamped to +-2^62 so that the index and its neighbours (+-1) fit an
// int64: coordinates beyond 4.6e15 m, which no building has (such a mesh is refused for its size
// later), share the outermost cell, where vertices are still compared by their distance.
std::int64_t cellIndex(double x, double size) {
  constexpr double kLimit = 4611686018427387904.0;  // 2^62
  return static_cast<std::int64_t>(std::clamp(std::floor(x / size), -kLimit, kLimit));
}

Cell cellOf(const dvec3& p, double size) { return {cellIndex(p.x, size), cellIndex(p.y, size), cellIndex(p.z, size)}; }

double distanceToLine(const dvec3& q, const dvec3& a, const dvec3& b) {
  const dvec3 d = glm::normalize(b - a);
  const dvec3 v = q - a;
  return glm::length(v - glm::dot(v, d) * d);
}

// Items 0..n-1 ordered by key(item) < keys (a counting sort): the items, and where each key's
// items start (keys + 1 entries).
template <class Key>
std::pair<std::vector<std::uint32_t>, std::vector<std::uint32_t>> byKey(std::size_t n, std::size_t keys, Key key) {
  std::vector<std::uint32_t> start(keys + 1, 0), items(n);
  for (std::uint32_t i = 0; i < n; ++i) ++start[key(i) + 1];
  for (std::size_t k = 0; k < keys; ++k) start[k + 1] += start[k];
  std::vector<std::uint32_t> next(start.begin(), start.end() - 1);
  for (std::uint32_t i = 0; i < n; ++i) items[next[key(i)]++] = i;
  return {std::move(items), std::move(start)};
}

}  // namespace

// Two vertices `radius` apart lie in neighbouring cells of a grid of that size; sorted by cell, a vertex's neighbours
// in cells (x+dx, y+dy, z-1..z+1) are one run, whose start only moves forward as the vertices are taken in order.
std::vector<std::uint32_t> placesOf(std::span<const dvec3> points, std::span<const std::uint32_t> used, double radius) {
  std::vector<std::pair<Cell, std::uint32_t>> sorted;
  sorted.reserve(used.size());
  for (std::uint32_t v : used) sorted.emplace_back(cellOf(points[v], radius), v);
  std::sort(sorted.begin(), sorted.end());
  UnionFind same(points.size());
  std::array<std::size_t, 9> runStart{};
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    const auto& [cell, v] = sorted[i];
    std::size_t k = 0;
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const Cell first{cell[0] + dx, cell[1] + dy, cell[2] - 1}, last{cell[0] + dx, cell[1] + dy, cell[2] + 1};
        std::size_t& j = runStart[k++];
        while (j < sorted.size() && sorted[j].first < first) ++j;
        // Each pair once: the earlier vertex in the order is compared with the later.
        for (std::size_t m = j; m < i && sorted[m].first <= last; ++m)
          if (glm::length(points[sorted[m].second] - points[v]) <= radius) same.unite(sorted[m].second, v);
      }
  }
  std::vector<std::uint32_t> place(points.size());
  for (std::uint32_t v : used) place[v] = same.find(v);
  return place;
}

// Edges of one line that cancel along it also meet end to end: wherever the runs along a line
// start or stop, another run must stop or start at the same place for the sum to stay zero. So
// the lines are found as chains of edges that meet at a place and are collinear, and each chain
// must cancel on its own (if every chain cancels, so does the line; one that does not leaves its
// line open where it starts or stops).
LineChains chainsAlongLines(std::span<const dvec3> points, std::span<const UncancelledEdge> edges) {
  std::vector<std::uint8_t> isUsed(points.size(), 0);
  std::vector<std::uint32_t> used;
  for (const UncancelledEdge& e : edges)
    for (std::uint32_t v : {e.a, e.b})
      if (!isUsed[v]) {
        isUsed[v] = 1;
        used.push_back(v);
      }
  const std::vector<std::uint32_t> place = placesOf(points, used);
  // End 2e of edge e is at a, 2e + 1 at b; an edge within one place carries no run.
  const auto placeOfEnd = [&](std::uint32_t end) { return place[end % 2 ? edges[end / 2].b : edges[end / 2].a]; };
  const auto runs = [&](std::uint32_t e) { return placeOfEnd(2 * e) != placeOfEnd(2 * e + 1); };
  const auto at = [&](std::uint32_t end) -> const dvec3& { return points[placeOfEnd(end)]; };
  const auto length = [&](std::uint32_t e) { return glm::length(at(2 * e + 1) - at(2 * e)); };

  // Chains: edges meeting at a place, the shorter's far end on the longer's line.
  const auto [ends, endsStart] = byKey(2 * edges.size(), points.size(), placeOfEnd);
  UnionFind chains(edges.size());
  for (std::size_t p = 0; p < points.size(); ++p)
    for (std::uint32_t i = endsStart[p]; i < endsStart[p + 1]; ++i)
      for (std::uint32_t j = i + 1; j < endsStart[p + 1]; ++j) {
        std::uint32_t longer = ends[i], shorter = ends[j];
        if (!runs(longer / 2) || !runs(shorter / 2)) continue;
        if (length(longer / 2) < length(shorter / 2)) std::swap(longer, shorter);
        if (distanceToLine(at(shorter ^ 1), at(longer), at(longer ^ 1)) <= kSamePlaceM) chains.unite(longer / 2, shorter / 2);
      }

  // Each chain, along its longest edge: the runs as intervals with a weight along it, swept in
  // order; between two places the weights of the runs there must sum to zero.
  LineChains out;
  const auto [byChain, chainStart] = byKey(edges.size(), edges.size(), [&](std::uint32_t e) { return chains.find(e); });
  struct Event {
    double at;
    bool starts;
    std::uint32_t edge;
    int weight;  // along the chain
    bool operator<(const Event& o) const { return at < o.at || (at == o.at && starts && !o.starts); }
  };
  std::vector<Event> events;
  std::vector<Event> covering;  // the runs over the stretch swept
  for (std::size_t c = 0; c < edges.size(); ++c) {
    const std::span<const std::uint32_t> chain(byChain.data() + chainStart[c], chainStart[c + 1] - chainStart[c]);
    std::uint32_t longest = 0;
    double longestLength = -1;
    for (std::uint32_t e : chain)
      if (runs(e) && length(e) > longestLength) {
        longest = e;
        longestLength = length(e);
      }
    if (longestLength < 0) continue;
    const dvec3& origin = at(2 * longest);
    const dvec3 d = glm::normalize(at(2 * longest + 1) - origin);
    events.clear();
    for (std::uint32_t e : chain) {
      if (!runs(e)) continue;
      const double a = glm::dot(at(2 * e) - origin, d), b = glm::dot(at(2 * e + 1) - origin, d);
      const int weight = a < b ? edges[e].weight : -edges[e].weight;
      events.push_back({std::min(a, b), true, e, weight});
      events.push_back({std::max(a, b), false, e, weight});
    }
    std::sort(events.begin(), events.end());
    covering.clear();
    for (std::size_t i = 0; i < events.size();) {
      // Ends of runs at one place (one position: the place's point projected) are taken together.
      const double here = events[i].at;
      for (; i < events.size() && events[i].at == here; ++i) {
        if (events[i].starts)
          covering.push_back(events[i]);
        else
          std::erase_if(covering, [&](const Event& r) { return r.edge == events[i].edge; });
      }
      if (i == events.size()) break;
      int sum = 0;
      for (const Event& r : covering) sum += r.weight;
      out.cancel = out.cancel && sum == 0;
      if (covering.size() == 2)
        out.alone.push_back({covering[0].edge, covering[1].edge, (covering[0].weight > 0) == (covering[1].weight > 0)});
    }
  }
  return out;
}

}  // namespace nut::converter
