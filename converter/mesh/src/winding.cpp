// Fast generalized winding numbers: a median-split tree over triangle centroids, exact solid
// angles near the query, first-order far-field expansions far from it.
#include <converter/winding.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include <glm/geometric.hpp>

namespace nut::converter {

namespace {

using glm::dvec3;

constexpr std::uint32_t kLeafSize = 8;
// Triangles longer than the mesh's diagonal over this are split for the tree.
constexpr double kSplitDivisions = 32;

// Signed solid angle of triangle (a, b, c) seen from the origin (Van Oosterom and Strackee 1983);
// positive when the origin lies on the side the normal (b - a) x (c - a) points away from.
double solidAngle(const dvec3& a, const dvec3& b, const dvec3& c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double det = glm::dot(a, glm::cross(b, c));
  const double div = la * lb * lc + glm::dot(a, b) * lc + glm::dot(b, c) * la + glm::dot(c, a) * lb;
  return 2.0 * std::atan2(det, div);
}

}  // namespace

WindingNumber::WindingNumber(const std::vector<dvec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                             double beta)
    : origin_(0.0), beta_(beta) {
  if (triangles.empty()) return;
  dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  for (const auto& t : triangles)
    for (std::uint32_t v : t) {
      lo = glm::min(lo, positions[v]);
      hi = glm::max(hi, positions[v]);
    }
  origin_ = 0.5 * (lo + hi);
  // Long triangles are split (the solid angle is additive, so the sum does not change): a node
  // holding a 30 m facade strip has a 15 m radius and could never use its far-field expansion
  // for queries near the building, which made every query walk most of the tree.
  const double maxEdge = glm::length(hi - lo) / kSplitDivisions;
  std::vector<Triangle> pending;
  for (const auto& t : triangles) {
    pending.push_back({positions[t[0]] - origin_, positions[t[1]] - origin_, positions[t[2]] - origin_});
    while (!pending.empty()) {
      const Triangle tri = pending.back();
      pending.pop_back();
      const double ab = glm::length(tri.b - tri.a), bc = glm::length(tri.c - tri.b), ca = glm::length(tri.a - tri.c);
      if (std::max({ab, bc, ca}) <= maxEdge) {
        triangles_.push_back(tri);
        continue;
      }
      // Halve the longest edge.
      if (ab >= bc && ab >= ca) {
        const dvec3 m = 0.5 * (tri.a + tri.b);
        pending.push_back({tri.a, m, tri.c});
        pending.push_back({m, tri.b, tri.c});
      } else if (bc >= ca) {
        const dvec3 m = 0.5 * (tri.b + tri.c);
        pending.push_back({tri.a, tri.b, m});
        pending.push_back({tri.a, m, tri.c});
      } else {
        const dvec3 m = 0.5 * (tri.c + tri.a);
        pending.push_back({tri.a, tri.b, m});
        pending.push_back({m, tri.b, tri.c});
      }
    }
  }
  std::vector<dvec3> centroids;
  centroids.reserve(triangles_.size());
  for (const Triangle& tri : triangles_) centroids.push_back((tri.a + tri.b + tri.c) / 3.0);
  nodes_.reserve(4 * triangles_.size() / kLeafSize + 2);
  nodes_.resize(1);
  fill(0, 0, static_cast<std::uint32_t>(triangles_.size()), centroids);
}

// Fills nodes_[slot] for triangles [first, first + count) of triangles_, reordering them; the two
// children of an inner node are appended next to each other.
void WindingNumber::fill(std::uint32_t slot, std::uint32_t first, std::uint32_t count, std::vector<dvec3>& centroids) {
  Node node{};
  dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
  double area = 0;
  dvec3 weighted(0.0);
  for (std::uint32_t i = first; i < first + count; ++i) {
    const Triangle& t = triangles_[i];
    const double a = 0.5 * glm::length(glm::cross(t.b - t.a, t.c - t.a));
    node.normal += 0.5 * glm::cross(t.b - t.a, t.c - t.a);
    area += a;
    weighted += a * centroids[i];
    lo = glm::min(lo, centroids[i]);
    hi = glm::max(hi, centroids[i]);
  }
  node.centre = area > 0 ? weighted / area : 0.5 * (lo + hi);
  node.moment = glm::dmat3(0.0);
  for (std::uint32_t i = first; i < first + count; ++i) {
    const Triangle& t = triangles_[i];
    node.moment += glm::outerProduct(centroids[i] - node.centre, 0.5 * glm::cross(t.b - t.a, t.c - t.a));
    for (const dvec3& p : {t.a, t.b, t.c}) node.radius = std::max(node.radius, glm::length(p - node.centre));
  }
  if (count <= kLeafSize) {
    node.first = first;
    node.count = count;
    nodes_[slot] = node;
    return;
  }
  // Median split along the widest extent of the centroids.
  const dvec3 extent = hi - lo;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : extent.y >= extent.z ? 1 : 2;
  std::vector<std::uint32_t> order(count);
  std::iota(order.begin(), order.end(), first);
  const std::uint32_t half = count / 2;
  std::nth_element(order.begin(), order.begin() + half, order.end(),
                   [&](std::uint32_t x, std::uint32_t y) { return centroids[x][axis] < centroids[y][axis]; });
  std::vector<Triangle> tris(count);
  std::vector<dvec3> cents(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    tris[i] = triangles_[order[i]];
    cents[i] = centroids[order[i]];
  }
  std::copy(tris.begin(), tris.end(), triangles_.begin() + first);
  std::copy(cents.begin(), cents.end(), centroids.begin() + first);

  node.first = static_cast<std::uint32_t>(nodes_.size());
  node.count = 0;
  nodes_[slot] = node;
  nodes_.resize(nodes_.size() + 2);
  fill(node.first, first, half, centroids);
  fill(node.first + 1, first + half, count - half, centroids);
}

double WindingNumber::operator()(const dvec3& world) const {
  if (nodes_.empty()) return 0;
  const dvec3 q = world - origin_;
  double sum = 0;
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    const dvec3 r = node.centre - q;
    const double d2 = glm::dot(r, r);
    if (d2 > beta_ * beta_ * node.radius * node.radius) {
      // Far field: n . f(p~) + tr(J M), f(p) = (p - q) / |p - q|^3, J its Jacobian.
      const double d = std::sqrt(d2), inv3 = 1.0 / (d2 * d), inv5 = inv3 / d2;
      const glm::dmat3& m = node.moment;
      const double trace = m[0][0] + m[1][1] + m[2][2];
      sum += glm::dot(node.normal, r) * inv3 + trace * inv3 -
             3.0 * glm::dot(r, m * r) * inv5;
      continue;
    }
    if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i) {
        const Triangle& t = triangles_[i];
        sum += solidAngle(t.a - q, t.b - q, t.c - q);
      }
      continue;
    }
    stack[top++] = node.first;
    stack[top++] = node.first + 1;
  }
  return sum / (4.0 * std::numbers::pi);
}

double WindingNumber::exact(const dvec3& world) const {
  const dvec3 q = world - origin_;
  double sum = 0;
  for (const Triangle& t : triangles_) sum += solidAngle(t.a - q, t.b - q, t.c - q);
  return sum / (4.0 * std::numbers::pi);
}

}  // namespace nut::converter
