// Ear clipping of a polygon in space (polygon.hpp).
#include <nut/polygon.hpp>

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/ext/vector_int2.hpp>

namespace nut {

namespace {

// Twice the signed area of triangle (a, b, c): positive when it turns counter-clockwise.
double turn(const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

// The corners in the plane across the Newell normal's largest component, turned so that the
// polygon runs counter-clockwise.
std::vector<glm::dvec2> flatten(std::span<const glm::dvec3> corners) {
  glm::dvec3 normal(0.0);
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const glm::dvec3& p = corners[i];
    const glm::dvec3& q = corners[(i + 1) % corners.size()];
    normal += glm::dvec3((p.y - q.y) * (p.z + q.z), (p.z - q.z) * (p.x + q.x), (p.x - q.x) * (p.y + q.y));
  }
  int across = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(normal[a]) > std::abs(normal[across])) across = a;
  // (u, v, across) is a right-handed cyclic order of the axes.
  const int u = (across + 1) % 3, v = (across + 2) % 3;
  const double flip = normal[across] < 0 ? -1.0 : 1.0;
  std::vector<glm::dvec2> flat;
  flat.reserve(corners.size());
  for (const glm::dvec3& p : corners) flat.emplace_back(p[u], flip * p[v]);
  return flat;
}

// The corners that may block an ear, bucketed by place in a grid of about one per cell over the
// polygon's box, so that an ear asks only those near it: a comb of 64,000 corners, half of them
// reflex, took 5.9 s testing every one against every ear, and takes 0.6 s so. (Long thin ears
// still ask many cells: a comb of a million corners takes minutes. Building faces have hundreds.)
class BlockerGrid {
 public:
  BlockerGrid(const std::vector<glm::dvec2>& flat, const std::vector<char>& blocking, glm::dvec2 lo, glm::dvec2 hi)
      : lo_(lo) {
    std::size_t count = 0;
    for (char b : blocking) count += b != 0;
    side_ = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(count))));
    const glm::dvec2 size = hi - lo;
    scale_ = glm::dvec2(size.x > 0 ? side_ / size.x : 0.0, size.y > 0 ? side_ / size.y : 0.0);
    // Counting sort of the blockers by cell: cell k holds items_[start_[k] .. start_[k + 1]).
    start_.assign(static_cast<std::size_t>(side_ * side_) + 1, 0);
    for (std::uint32_t c = 0; c < blocking.size(); ++c)
      if (blocking[c]) ++start_[cellOf(flat[c]) + 1];
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    items_.resize(count);
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::uint32_t c = 0; c < blocking.size(); ++c)
      if (blocking[c]) items_[fill[cellOf(flat[c])]++] = c;
  }

  // Whether `blocks` is false for every blocker in the cells over the box [lo, hi].
  template <typename Blocks>
  bool none(const glm::dvec2& lo, const glm::dvec2& hi, const Blocks& blocks) const {
    const glm::ivec2 first = cell(lo), last = cell(hi);
    for (int y = first.y; y <= last.y; ++y)
      for (int x = first.x; x <= last.x; ++x) {
        const std::size_t k = static_cast<std::size_t>(y * side_ + x);
        for (std::uint32_t i = start_[k]; i < start_[k + 1]; ++i)
          if (blocks(items_[i])) return false;
      }
    return true;
  }

 private:
  glm::ivec2 cell(const glm::dvec2& p) const {
    const glm::dvec2 at = (p - lo_) * scale_;
    return {index(at.x), index(at.y)};
  }
  // The cell of a place along one axis, clamped before the conversion to int: a polygon wider than
  // a double's range has an infinite extent, a zero scale, and places that are NaN (inf * 0).
  int index(double at) const {
    if (!(at >= 1)) return 0;  // also NaN
    return at < side_ ? static_cast<int>(at) : side_ - 1;
  }
  std::size_t cellOf(const glm::dvec2& p) const {
    const glm::ivec2 c = cell(p);
    return static_cast<std::size_t>(c.y * side_ + c.x);
  }

  glm::dvec2 lo_, scale_;
  int side_ = 1;
  std::vector<std::uint32_t> start_, items_;
};

}  // namespace

void triangulatePolygon(std::span<const glm::dvec3> corners, std::vector<std::array<std::uint32_t, 3>>& triangles) {
  triangles.clear();
  if (corners.size() < 3) return;
  if (corners.size() == 3) {  // most faces
    triangles.push_back({0, 1, 2});
    return;
  }
  const std::vector<glm::dvec2> flat = flatten(corners);
  const auto n = static_cast<std::uint32_t>(corners.size());

  // Turns within `flatTurn` count as none: corners that are collinear in the face's own plane are
  // off by rounding once placed in space and flattened again.
  glm::dvec2 lo = flat[0], hi = flat[0];
  for (const glm::dvec2& p : flat) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  const double flatTurn = 1e-12 * extent * extent;

  // The corners still to cut, as a ring of links (a cut is O(1)), and how many there are.
  std::vector<std::uint32_t> next(n), prev(n);
  for (std::uint32_t c = 0; c < n; ++c) next[c] = (c + 1) % n, prev[c] = (c + n - 1) % n;
  std::uint32_t left = n;
  const auto convex = [&](std::uint32_t c) { return turn(flat[prev[c]], flat[c], flat[next[c]]) > flatTurn; };
  // Only a corner that is not convex can lie in or on an ear (a convex one inside would make a
  // corner between them reflex), so only those are tested: a convex polygon takes linear time. A
  // cut only takes away from its neighbours' angles, so a convex corner stays convex and the list
  // only loses corners (`blocking` says which are still in it).
  std::vector<char> blocking(n, 0);
  for (std::uint32_t c = 0; c < n; ++c) blocking[c] = !convex(c);
  const BlockerGrid grid(flat, blocking, lo, hi);

  // Corner b is an ear when it turns left and no other corner lies in or on its triangle (corners
  // at the same place as one of its three aside). When no corner is such an ear, one whose cut
  // only touches other corners will do (`touching`): a straight run of corners, common in floor
  // plans, can lie along every possible cut, and an edge of the polygon that entered the triangle
  // would end at a corner inside it.
  bool touching = false;
  const auto isEar = [&](std::uint32_t b) {
    const std::uint32_t ia = prev[b], ic = next[b];
    const glm::dvec2 &pa = flat[ia], &pb = flat[b], &pc = flat[ic];
    if (!(turn(pa, pb, pc) > flatTurn)) return false;
    const double limit = touching ? flatTurn : -flatTurn;
    return grid.none(glm::min(glm::min(pa, pb), pc), glm::max(glm::max(pa, pb), pc), [&](std::uint32_t m) {
      if (!blocking[m] || m == ia || m == b || m == ic) return false;
      const glm::dvec2& p = flat[m];
      if (!touching && (p == pa || p == pb || p == pc)) return false;
      return turn(pa, pb, p) > limit && turn(pb, pc, p) > limit && turn(pc, pa, p) > limit;
    });
  };
  // Going round from the second corner; after a cut the corner after the ear is tried next, which
  // for a convex polygon is the fan. A round without an ear of either kind ends the clipping.
  std::uint32_t b = 1, misses = 0;
  while (left > 3) {
    if (misses >= left) {
      if (touching) break;
      touching = true;
      misses = 0;
    }
    if (!isEar(b)) {
      b = next[b];
      ++misses;
      continue;
    }
    const std::uint32_t a = prev[b], c = next[b];
    triangles.push_back({a, b, c});
    next[a] = c, prev[c] = a, blocking[b] = 0, --left;
    for (std::uint32_t neighbour : {a, c})
      if (blocking[neighbour] && convex(neighbour)) blocking[neighbour] = 0;
    b = c;
    misses = 0;
    touching = false;
  }
  // What is left, fanned from its first corner in the polygon's order: one triangle when the
  // clipping went through.
  std::uint32_t first = 0;
  while (first < n && next[prev[first]] != first) ++first;
  for (std::uint32_t c = next[first]; next[c] != first; c = next[c]) triangles.push_back({first, c, next[c]});
}

}  // namespace nut
