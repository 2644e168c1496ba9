// Disjoint sets over 0..n-1 with path halving: the converter's grouping of faces into pieces
// (mesh checks) and into quarter-round, sphere-octant and corner-slope candidates (quadrics.cpp,
// corner_slopes.cpp); and with a parity, the mesh checks' open pieces that must face the same
// way or opposite ways.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
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

// Disjoint sets whose items each carry a parity relative to their set's root: unite(a, b, odd)
// records that a and b differ (odd) or agree, unless their sets are one already, and find(x)
// gives x's root and x's parity against it. A relation contradicting those recorded is ignored.
struct ParityUnionFind {
  std::vector<std::uint32_t> parent;
  std::vector<std::uint8_t> parity;  // against parent
  explicit ParityUnionFind(std::size_t n) : parent(n), parity(n, 0) { std::iota(parent.begin(), parent.end(), 0u); }
  std::pair<std::uint32_t, bool> find(std::uint32_t x) {
    std::uint32_t root = x;
    bool odd = false;
    for (; parent[root] != root; root = parent[root]) odd = odd != (parity[root] != 0);
    // Every item on the way now hangs from the root, with its parity against it.
    for (bool rest = odd; parent[x] != x;) {
      const std::uint32_t next = parent[x];
      const bool own = parity[x] != 0;
      parent[x] = root;
      parity[x] = rest ? 1 : 0;
      rest = rest != own;
      x = next;
    }
    return {root, odd};
  }
  void unite(std::uint32_t a, std::uint32_t b, bool odd) {
    const auto [ra, pa] = find(a);
    const auto [rb, pb] = find(b);
    if (ra == rb) return;
    parent[ra] = rb;
    parity[ra] = (pa != pb) != odd ? 1 : 0;
  }
};

}  // namespace nut::converter
