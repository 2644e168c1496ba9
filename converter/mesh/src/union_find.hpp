// Disjoint sets over 0..n-1 with path halving: the converter's grouping of faces into pieces
// (mesh checks) and into quarter-round, sphere-octant and corner-slope candidates (quadrics.cpp,
// corner_slopes.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

namespace nut::converter {

struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) { parent[find(a)] = find(b); }

  // The sets of the items `keep` accepts, each listing its items in increasing order, ordered by
  // their first item: the same pieces in the same order on every run.
  template <class Keep>
  std::vector<std::vector<std::uint32_t>> groups(Keep keep) {
    constexpr auto kNone = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::vector<std::uint32_t>> out;
    std::vector<std::uint32_t> slotOfRoot(parent.size(), kNone);
    for (std::uint32_t x = 0; x < parent.size(); ++x) {
      if (!keep(x)) continue;
      std::uint32_t& slot = slotOfRoot[find(x)];
      if (slot == kNone) {
        slot = static_cast<std::uint32_t>(out.size());
        out.emplace_back();
      }
      out[slot].push_back(x);
    }
    return out;
  }
};

}  // namespace nut::converter
