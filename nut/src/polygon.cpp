// Ear clipping of a polygon in space (polygon.hpp).
#include <nut/polygon.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

#include <glm/common.hpp>
#include <glm/vec2.hpp>

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

}  // namespace

void triangulatePolygon(std::span<const glm::dvec3> corners, std::vector<std::array<std::uint32_t, 3>>& triangles) {
  triangles.clear();
  if (corners.size() < 3) return;
  if (corners.size() == 3) {  // most faces
    triangles.push_back({0, 1, 2});
    return;
  }
  const std::vector<glm::dvec2> flat = flatten(corners);
  std::vector<std::uint32_t> left(corners.size());
  std::iota(left.begin(), left.end(), 0u);

  // Turns within `flatTurn` count as none: corners that are collinear in the face's own plane are
  // off by rounding once placed in space and flattened again.
  glm::dvec2 lo = flat[0], hi = flat[0];
  for (const glm::dvec2& p : flat) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const double extent = std::max(hi.x - lo.x, hi.y - lo.y);
  const double flatTurn = 1e-12 * extent * extent;
  // Corner j of `left` is an ear when it turns left and no other corner lies in or on its
  // triangle (corners at the same place as one of its three aside). When no corner is such an ear,
  // one whose cut only touches other corners will do (`touching`): a straight run of corners, common
  // in floor plans, can lie along every possible cut, and an edge of the polygon that entered the
  // triangle would end at a corner inside it.
  bool touching = false;
  const auto isEar = [&](std::size_t i, std::size_t j, std::size_t k) {
    const glm::dvec2 &a = flat[left[i]], &b = flat[left[j]], &c = flat[left[k]];
    if (!(turn(a, b, c) > flatTurn)) return false;
    const double limit = touching ? flatTurn : -flatTurn;
    for (std::size_t m = 0; m < left.size(); ++m) {
      const glm::dvec2& p = flat[left[m]];
      if (m == i || m == j || m == k || (!touching && (p == a || p == b || p == c))) continue;
      if (turn(a, b, p) > limit && turn(b, c, p) > limit && turn(c, a, p) > limit) return false;
    }
    return true;
  };
  // Going round from the second corner; after a cut the corner that took the ear's place is tried
  // next, which for a convex polygon is the fan. A round without an ear of either kind ends the
  // clipping.
  std::size_t j = 1, misses = 0;
  while (left.size() > 3) {
    if (misses >= left.size()) {
      if (touching) break;
      touching = true;
      misses = 0;
    }
    j %= left.size();
    const std::size_t i = (j + left.size() - 1) % left.size(), k = (j + 1) % left.size();
    if (isEar(i, j, k)) {
      triangles.push_back({left[i], left[j], left[k]});
      left.erase(left.begin() + static_cast<std::ptrdiff_t>(j));
      misses = 0;
      touching = false;
    } else {
      ++j;
      ++misses;
    }
  }
  for (std::size_t k = 1; k + 1 < left.size(); ++k) triangles.push_back({left[0], left[k], left[k + 1]});
}

}  // namespace nut
